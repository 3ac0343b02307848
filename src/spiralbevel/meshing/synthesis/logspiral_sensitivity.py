"""Transmission error of a log-spiral pair from the first touch of sampled flank points, edge contacts included.

Surface-to-surface TCA (:func:`~spiralbevel.meshing.tca.solve_tca`) needs a tangency of the two flanks; a misaligned
*line-contact* pair has none (the flanks cross, and the real contact is at an edge). This module measures the TE of
any pair, conjugate or crowned, by a brute-force kinematic method that needs no tangency:

* every node of a pinion flank grid (its edges included) is carried to the fixed frame at pinion angle phi1, and the
  gear angle phi2 at which the gear flank (extended analytically) passes through it is solved by Newton on
  (u2, v2, phi2): o2 + R(a2, phi2) B2 r2(u2, v2) = P; the landing point must lie on the gear flank domain;
* conversely every node of the gear flank grid is turned about the gear axis until it pierces the pinion flank
  (unknowns u1, v1, phi2).

Each solution is a gear angle at which one point pair touches; with TE = drive (-(phi2 - phi2_mean) - (z1/z2)(phi1 -
phi1_mean)) (the sign rule of :class:`~spiralbevel.meshing.tca_result.TCAResult`), the pair in contact is the one
with the largest TE, over the points and over the tooth pairs k = -1, 0, 1. On a crowned pair this reproduces the
TE of the surface TCA (tests/meshing/synthesis/test_logspiral_sensitivity.py); on a misaligned conjugate pair it
gives the edge-contact TE that the surface TCA cannot.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from ..._core.rotations import rot_axis, rot_z
from ..contact_surface import surface_contains, surface_derivatives
from ..misalignment import Misalignment

__all__ = ["first_touch_te", "SensitivityRow", "SensitivityStudy", "misalignment_sensitivity"]


def _rot(axis, ang):
    """Rotation matrices (m, 3, 3) about the unit ``axis`` by angles ``ang`` (m,) rad (Rodrigues)."""
    k = np.asarray(axis, float)
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    a = np.atleast_1d(np.asarray(ang, float))[:, None, None]
    return np.eye(3) + np.sin(a) * K + (1.0 - np.cos(a)) * (K @ K)


def _peak(values, shape):
    """Largest value of a grid function (NaN = no touch), refined by a quadratic fit on the 3 x 3 nodes around the
    largest node (the touching point lies between nodes; the fit's maximum is kept when it falls inside the patch)."""
    v = values.reshape(shape)
    if not np.isfinite(v).any():
        return -np.inf
    i, j = np.unravel_index(np.nanargmax(v), shape)
    best = float(v[i, j])
    if 0 < i < shape[0] - 1 and 0 < j < shape[1] - 1:
        patch = v[i - 1:i + 2, j - 1:j + 2]
        if np.isfinite(patch).all():
            x, y = np.meshgrid([-1.0, 0.0, 1.0], [-1.0, 0.0, 1.0], indexing="ij")
            A = np.stack([np.ones(9), x.ravel(), y.ravel(), x.ravel() ** 2, (x * y).ravel(), y.ravel() ** 2], -1)
            c = np.linalg.lstsq(A, patch.ravel(), rcond=None)[0]
            H = np.array([[2 * c[3], c[4]], [c[4], 2 * c[5]]])
            if np.all(np.linalg.eigvalsh(H) < 0):
                xy = np.linalg.solve(H, -c[1:3])
                if np.all(np.abs(xy) <= 1.0):
                    best = max(best, float(c[0] + c[1:3] @ xy + 0.5 * xy @ H @ xy))
    return best


def _base(surface):
    return getattr(surface, "base", surface)


def _grid_params(surface, n_phi, n_psi):
    """(n_phi * n_psi, 2) parameters over the flank domain and the node spacing (d psi, d phi) in rad."""
    b = _base(surface)
    phi = np.linspace(*b.phi_range, n_phi)[:, None]
    psi = np.linspace(*b.psi_range, n_psi)[None, :]
    h = (abs(b.psi_range[1] - b.psi_range[0]) / (n_psi - 1), abs(b.phi_range[1] - b.phi_range[0]) / (n_phi - 1))
    return b.params_of(psi, phi).reshape(-1, 2), h


def _newton(F, x0, iters=30, tol=1e-10):
    """Vectorized Newton on F(x, sel) -> (res (k, 3), J (k, 3, 3)) for the systems ``sel``; converged systems leave
    the iteration. Returns x and a converged mask (max |res| < 1e-8 mm)."""
    x = x0.copy()
    active = np.arange(len(x))
    for _ in range(iters):
        res, J = F(x[active], active)
        done = np.abs(res).max(-1) < tol
        active, res, J = active[~done], res[~done], J[~done]
        if active.size == 0:
            break
        with np.errstate(all="ignore"):
            dx = np.linalg.solve(J, res[..., None])[..., 0]
        dx[~np.isfinite(dx).all(-1)] = 0.0
        step = np.linalg.norm(dx[:, :2], axis=-1)
        big = step > 0.2
        dx[big] *= (0.2 / step[big])[:, None]  # keep parameter steps modest (rad)
        x[active] -= dx
    res, _ = F(x, np.arange(len(x)))
    return x, (np.abs(res).max(-1) < 1e-8) & np.isfinite(x).all(-1)


def first_touch_te(pinion, gear, kinematics, phi1, *, phi1_mean, phi2_mean, drive_sign, misalignment=None,
                   grid=(41, 21)) -> np.ndarray:
    """TE envelope (rad of gear rotation) at pinion angles ``phi1`` from point-wise first touch (module docstring).

    Parameters
    ----------
    pinion, gear : LogSpiralSurface or NormalDeviation of one
        Flanks of the meshing side, member frames, with ``psi_range`` and ``phi_range`` (the base's).
    kinematics : object
        ``z1``, ``z2``, ``shaft_angle`` rad.
    phi1 : (n,) float, rad
    phi1_mean, phi2_mean : float, rad
        Reference angles of the TE (those of the aligned surface TCA of the same pair).
    drive_sign : int
        +1 or -1, as in :class:`~spiralbevel.meshing.tca_result.TCAResult`.
    misalignment : Misalignment, optional
    grid : (int, int)
        Nodes along phi (toe-heel) and psi (root-top) of both flank grids.

    Returns
    -------
    (n,) float, rad
        TE of the pair in contact; NaN where no point touches.
    """
    mis = misalignment or Misalignment()
    z1, z2, S = int(kinematics.z1), int(kinematics.z2), float(kinematics.shaft_angle)
    a1, o1, a2, o2, B2 = mis.axes(S)
    ratio = z1 / z2
    q1, h1 = _grid_params(pinion, *grid)
    q2, h2 = _grid_params(gear, *grid)
    r1g = pinion.evaluate(q1)[0]
    r2g = gear.evaluate(q2)[0]
    tree1, tree2 = cKDTree(r1g), cKDTree(r2g)
    phi1 = np.atleast_1d(np.asarray(phi1, float))
    T1, T2 = 2 * math.pi / z1, 2 * math.pi / z2
    best = np.full(phi1.shape, -np.inf)
    for k in (-1, 0, 1):
        for i, p1 in enumerate(phi1):
            pe = p1 + k * T1                      # pair k at phi1 = pair 0 at phi1 + k T1, gear phased by k T2
            ph2 = phi2_mean - ratio * (pe - phi1_mean)
            R1 = rot_z(pe)

            def solve_pinion(q, R1=R1, ph2=ph2):                  # pinion points q onto the gear flank
                P = o1 + pinion.evaluate(q)[0] @ R1.T
                return _pinion_nodes(P, gear, q2, tree2, a2, o2, B2, ph2)

            def solve_gear(q, R1=R1, ph2=ph2):                    # gear points q onto the pinion flank
                return _gear_nodes(gear.evaluate(q)[0], pinion, q1, tree1, R1, o1, a2, o2, B2, ph2)

            for solve, q, h, surf in ((solve_pinion, q1, h1, pinion), (solve_gear, q2, h2, gear)):
                t = _te(solve(q), ph2, drive_sign, T2)
                if not np.isfinite(t).any():
                    continue
                # refine on 9 x 9 grids around the best node (the touching point lies between nodes, and the TE
                # falls steeply across the narrow contact ellipse)
                j = int(np.nanargmax(t))
                qc, hc, top = q[j], (2.0 * h[0], 2.0 * h[1]), float(t[j])
                for _ in range(3):  # zoom in: the coarse best node may sit off the ridge top along the ridge
                    qf = _sub_grid(surf, qc, hc, 9)
                    tf = _te(solve(qf), ph2, drive_sign, T2)
                    if not np.isfinite(tf).any():
                        break
                    jf = int(np.nanargmax(tf))
                    top = max(top, _peak(tf, (9, 9)))
                    qc, hc = qf[jf], (hc[0] / 3.0, hc[1] / 3.0)
                best[i] = max(best[i], top)
    return np.where(np.isfinite(best), best, np.nan)


def _te(phis, ph2, drive_sign, T2):
    """TE relative to the conjugate position ph2 of the pair; NaN beyond half a gear pitch (no such contact)."""
    t = drive_sign * (-(phis - ph2))
    return np.where(np.abs(t) < T2 / 2, t, np.nan)


def _sub_grid(surface, q, h, n):
    """(n*n, 2) parameters (varphi, phi) on the psi-phi square of half-width h = (h_psi, h_phi) around q."""
    b = _base(surface)
    sd = math.sin(b.delta)
    psi0, phi0 = (q[0] - q[1]) * sd, q[1]
    psi = psi0 + np.linspace(-h[0], h[0], n)[None, :]
    phi = phi0 + np.linspace(-h[1], h[1], n)[:, None]
    return b.params_of(psi, phi).reshape(-1, 2)


def _pinion_nodes(P, gear, q2, tree2, a2, o2, B2, ph2):
    """Gear angles at which the gear flank passes through the fixed points P (m, 3)."""
    Rg = rot_axis(a2, ph2) @ B2
    local = (P - o2) @ Rg  # gear member coordinates at ph2
    idx = tree2.query(local)[1]
    x0 = np.concatenate([q2[idx], np.full((len(P), 1), ph2)], axis=1)

    def F(x, sel):
        r, _, dr, _ = surface_derivatives(gear, x[:, :2])
        R = _rot(a2, x[:, 2]) @ B2
        g = np.einsum("mij,mj->mi", R, r)
        res = o2 + g - P[sel]
        J = np.empty((len(x), 3, 3))
        J[:, :, :2] = R @ dr
        J[:, :, 2] = np.cross(a2, g)
        return res, J

    x, ok = _newton(F, x0)
    ok &= surface_contains(gear, x[:, :2])
    return np.where(ok, x[:, 2], np.nan)


def _gear_nodes(r2g, pinion, q1, tree1, R1, o1, a2, o2, B2, ph2):
    """Gear angles at which gear nodes r2g (member frame) pierce the pinion flank (pinion fixed at R1)."""
    G0 = o2 + r2g @ (rot_axis(a2, ph2) @ B2).T
    local = (G0 - o1) @ R1  # pinion member coordinates
    idx = tree1.query(local)[1]
    x0 = np.concatenate([q1[idx], np.full((len(r2g), 1), ph2)], axis=1)
    b2 = r2g @ B2.T

    def F(x, sel):
        r, _, dr, _ = surface_derivatives(pinion, x[:, :2])
        Rg = _rot(a2, x[:, 2])
        g = np.einsum("mij,mj->mi", Rg, b2[sel])
        res = o1 + r @ R1.T - (o2 + g)
        J = np.empty((len(x), 3, 3))
        J[:, :, :2] = R1 @ dr
        J[:, :, 2] = -np.cross(a2, g)
        return res, J

    x, ok = _newton(F, x0)
    ok &= surface_contains(pinion, x[:, :2])
    return np.where(ok, x[:, 2], np.nan)


@dataclass(frozen=True)
class SensitivityRow:
    """TE growth of one misalignment for the line-contact and the mismatched pair.

    Attributes
    ----------
    name : str
        Misalignment name (``pinion_axial``, ``gear_axial``, ``offset``, ``shaft_angle``).
    value : float
        Its size (mm, or rad for the shaft angle).
    line_growth, mismatched_growth : float, rad
        Peak-to-peak TE with the misalignment minus the aligned peak-to-peak, for each pair.
    line_ptp, mismatched_ptp : float, rad
        Peak-to-peak TE with the misalignment.
    """

    name: str
    value: float
    line_growth: float
    mismatched_growth: float
    line_ptp: float
    mismatched_ptp: float


@dataclass(frozen=True)
class SensitivityStudy:
    """Result of :func:`misalignment_sensitivity`.

    Attributes
    ----------
    phi1 : (n,) float, rad
        Pinion angles over one cycle.
    aligned_line_te, aligned_mismatched_te : (n,) float, rad
        First-touch TE of the aligned pairs (for the mismatched pair it must reproduce the surface TCA; a larger TE
        means that some other point, e.g. a forging relief, touches first: interference).
    rows : list of SensitivityRow
    """

    phi1: np.ndarray
    aligned_line_te: np.ndarray
    aligned_mismatched_te: np.ndarray
    rows: list


def _ptp(te):
    te = te[np.isfinite(te)]
    return float(te.max() - te.min()) if te.size else math.nan


def misalignment_sensitivity(line_pinion, mismatched_pinion, gear, kinematics, *, phi1_mean, phi2_mean, drive_sign,
                             misalignments, n_positions=21, grid=(41, 21)):
    """TE growth under each misalignment, line-contact pair beside the mismatched pair (both by first touch).

    Parameters
    ----------
    line_pinion, mismatched_pinion, gear : contact surfaces
    kinematics : object
    phi1_mean, phi2_mean, drive_sign
        Reference of the TE (aligned TCA of the mismatched pair).
    misalignments : mapping name -> Misalignment
    n_positions : int
        Positions over one mesh cycle centred on phi1_mean.
    grid : (int, int)

    Returns
    -------
    SensitivityStudy
    """
    T = 2 * math.pi / int(kinematics.z1)
    phi1 = phi1_mean + np.linspace(-T / 2, T / 2, n_positions)
    kw = dict(phi1_mean=phi1_mean, phi2_mean=phi2_mean, drive_sign=drive_sign, grid=grid)
    te_line = first_touch_te(line_pinion, gear, kinematics, phi1, **kw)
    te_mm = first_touch_te(mismatched_pinion, gear, kinematics, phi1, **kw)
    base = {"line": _ptp(te_line), "mm": _ptp(te_mm)}
    rows = []
    for name, mis in misalignments.items():
        lp = _ptp(first_touch_te(line_pinion, gear, kinematics, phi1, misalignment=mis, **kw))
        mp = _ptp(first_touch_te(mismatched_pinion, gear, kinematics, phi1, misalignment=mis, **kw))
        value = next((getattr(mis, f) for f in ("pinion_axial", "gear_axial", "offset", "shaft_angle")
                      if getattr(mis, f) != 0.0), 0.0)
        rows.append(SensitivityRow(name, float(value), lp - base["line"], mp - base["mm"], lp, mp))
    return SensitivityStudy(phi1, te_line, te_mm, rows)
