"""Loaded tooth contact analysis driver: mesh positions x tooth pairs -> :class:`LTCAResult`.

Input protocol (what an unloaded TCA must supply, per mesh position and per tooth pair): :class:`PairContact` — the
unloaded contact point and common normal in the pair frame, the major-axis direction of the contact ellipse, the
pair's unloaded transmission error, the relative curvature (or an exact separation function), and the poses that map
pair-frame points to the member frames of pinion and gear (reference tooth) with the FE tooth index of the pair.

Per position (seed 001 Eq. (18), docs/theory/ltca.md, Eqs. (L1)-(L4)): potential contact points on a regular grid of the
common
tangent plane of each pair; lever arms h_i = ((q_i - o2) x n) . a2 about the gear axis; initial separations
w_i = w_sep(s, t) - te_pair h_i, so the gear lag dtheta that closes pair k first is -te_k and the loaded transmission
error is -dtheta; flexibility C = C_FE,pinion + C_FE,gear + C_halfspace (the last within each pair only, its cells
being far apart from those of other pairs); exact load distribution by :func:`solve_load_distribution`.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import Callable, Optional, Sequence

import numpy as np
from scipy.optimize import brentq

from ...errors import DesignError, NoContactError
from .compliance import ToothCompliance
from .halfspace import STEEL, Material, contact_modulus, halfspace_flexibility
from .lcp import solve_load_distribution
from .result import ARCSEC, LTCAResult
from .separation import quadratic_separations

__all__ = ["PairContact", "ContactPosition", "run_ltca", "torque_for_approach", "APPROACH_TARGET"]

log = logging.getLogger(__name__)

APPROACH_TARGET = 0.00635  # mm, Gleason's 0.00025 in rule (seed 001 §4.3.2, docs/theory/ltca.md, Eq. (L6))


@dataclass(frozen=True)
class PairContact:
    """Unloaded contact of one tooth pair at one mesh position (pair frame of docs/conventions.md).

    Attributes
    ----------
    point : (3,) float, mm
        Contact point.
    normal : (3,) float
        Unit common normal, outward from the pinion flank (the direction of the force on the gear).
    direction : (3,) float
        Tangent direction of the major axis of the contact ellipse (or of the contact line).
    te : float, rad
        Unloaded transmission error of this pair (seed 001 Eq. (1); negative: the gear lags).
    curvature : (2, 2) float, 1/mm, optional
        Relative normal curvature in the (direction, normal x direction) basis (second-order separations).
    separation : callable, optional
        ``separation(s (ns,), t (nt,)) -> (ns, nt)`` exact separations in mm (e.g. from
        :func:`~spiralbevel.meshing.ltca.separation.surface_separations`); overrides ``curvature``.
    to_pinion, to_gear : ((3, 3), (3,)) float
        Poses (R, o): point in the frame of the member's FE segment model = R @ (x - o) (member frame at the mesh
        position's rotation, turned back so that the pair's tooth lands on tooth ``tooth_*`` of the segment, which
        sits at tooth_* pitch angles from the reference tooth).
    tooth_pinion, tooth_gear : int
        FE tooth index of the pair in each member's segment model (-1, 0, +1 for a 3-tooth segment).
    extents : (float, float), mm, optional
        Half extents (along ``direction``, across it) of this pair's potential-contact grid; None: the driver's
        ``half_length``, ``half_width``.
    edge : bool
        True for an edge contact (a flank boundary of one member against the other's flank: TCA status EDGE, or a
        trailing edge contact added by :func:`~spiralbevel.meshing.ltca.trailing.follow_trailing_edges`); its
        pressure peaks at the edge and grows with the grid.
    """

    point: np.ndarray
    normal: np.ndarray
    direction: np.ndarray
    te: float
    curvature: Optional[np.ndarray] = None
    separation: Optional[Callable] = None
    to_pinion: tuple = (np.eye(3), np.zeros(3))
    to_gear: tuple = (np.eye(3), np.zeros(3))
    tooth_pinion: int = 0
    tooth_gear: int = 0
    extents: Optional[tuple] = None
    edge: bool = False


@dataclass(frozen=True)
class ContactPosition:
    """One mesh position: pinion rotation (rad, from the mean position) and the pairs (None: out of mesh)."""

    pinion_angle: float
    pairs: Sequence[Optional[PairContact]]


@dataclass
class _System:
    C: np.ndarray
    w: np.ndarray
    h: np.ndarray
    q: np.ndarray
    x1: np.ndarray
    x2: np.ndarray
    pair: np.ndarray
    flat: np.ndarray  # index in the full (n_pairs, ns, nt) grid
    cell: np.ndarray  # area (mm^2) of each point's cell
    te: np.ndarray
    h0: np.ndarray  # lever arm at each pair's contact point


def _grid(ns, nt, half_length, half_width):
    ds, dt = 2 * half_length / ns, 2 * half_width / nt
    s = -half_length + ds * (np.arange(ns) + 0.5)
    t = -half_width + dt * (np.arange(nt) + 0.5)
    return s, t, ds, dt


def _assemble(k, pos, comp1, comp2, a2, o2, grid, half_length, half_width, estar) -> _System:
    ns, nt = grid
    blocks, te = [], np.full(len(pos.pairs), np.nan)
    h0 = np.full(len(pos.pairs), np.nan)
    for j, pc in enumerate(pos.pairs):
        if pc is None:
            continue
        hl, hw = pc.extents if pc.extents is not None else (half_length, half_width)
        if hl is None or hw is None:
            raise DesignError.single(f"positions[{k}].pairs[{j}].extents", None, "(half_length, half_width) > 0",
                                     "mm", "LTCA potential contact grid (or the driver's half_length, half_width)")
        s, t, ds, dt = _grid(ns, nt, float(hl), float(hw))
        S, T = np.meshgrid(s, t, indexing="ij")
        P, n = np.asarray(pc.point, float), np.asarray(pc.normal, float)
        n = n / np.linalg.norm(n)
        e1 = np.asarray(pc.direction, float) - np.dot(pc.direction, n) * n
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(n, e1)
        if pc.separation is not None:
            wsep = np.asarray(pc.separation(s, t), float)
        elif pc.curvature is not None:
            wsep = quadratic_separations(pc.curvature, s, t)
        else:
            raise DesignError.single(f"positions[{k}].pairs[{j}]", "no curvature/separation", "one of them", "-",
                                     "LTCA separations")
        q = P + S[..., None] * e1 + T[..., None] * e2
        lever = np.einsum("...i,i->...", np.cross(q - o2, n), a2)
        sgn = np.sign(np.dot(np.cross(P - o2, n), a2))
        if sgn == 0 or np.any(sgn * lever <= 0):
            raise DesignError.single(f"positions[{k}].pairs[{j}].normal", list(np.round(n, 6)),
                                     "a normal with a lever arm of one sign about the gear axis", "-",
                                     f"LTCA at mesh position {k}")
        h = sgn * lever
        h0[j] = sgn * np.dot(np.cross(P - o2, n), a2)
        te[j] = pc.te
        w = wsep - pc.te * h
        (R1, o1), (R2, og) = pc.to_pinion, pc.to_gear
        x1 = (q - np.asarray(o1)) @ np.asarray(R1).T
        x2 = (q - np.asarray(og)) @ np.asarray(R2).T
        flat = j * ns * nt + np.arange(ns * nt)
        xy = np.stack([S.ravel(), T.ravel()], 1)
        blocks.append((q.reshape(-1, 3), x1.reshape(-1, 3), x2.reshape(-1, 3), w.ravel(), h.ravel(), flat,
                       np.full(ns * nt, j), np.full(ns * nt, pc.tooth_pinion), np.full(ns * nt, pc.tooth_gear),
                       xy, np.tile([ds, dt], (ns * nt, 1))))
    if not blocks:
        raise NoContactError(f"no tooth pair in mesh at mesh position {k} (pinion angle {pos.pinion_angle:.6g} rad)")
    q, x1, x2, w, h, flat, pair, k1, k2, xy, dsdt = (np.concatenate(c) for c in zip(*blocks))
    keep = np.isfinite(w)
    W1 = W2 = None
    if comp1 is not None:
        W1, in1 = comp1.weight_matrix(k1, x1)
        keep &= in1
    if comp2 is not None:
        W2, in2 = comp2.weight_matrix(k2, x2)
        keep &= in2
    if not keep.any():
        raise NoContactError(f"no potential contact point on the flanks at mesh position {k}")
    C = np.zeros((keep.sum(), keep.sum()))
    if W1 is not None:
        Wk = W1[keep]
        C += Wk @ comp1.G @ Wk.T
    if W2 is not None:
        Wk = W2[keep]
        C += Wk @ comp2.G @ Wk.T
    pk = pair[keep]
    xy, dsdt = xy[keep], dsdt[keep]
    for j in np.unique(pk):
        sel = np.flatnonzero(pk == j)
        C[np.ix_(sel, sel)] += halfspace_flexibility(xy[sel], dsdt[sel[0], 0], dsdt[sel[0], 1], estar)
    return _System(C, w[keep], h[keep], q[keep], x1[keep], x2[keep], pk, flat[keep], dsdt[:, 0] * dsdt[:, 1], te,
                   h0)


def _check(torque, positions, grid, half_length, half_width):
    if not (np.isfinite(torque) and torque > 0):
        raise DesignError.single("torque", torque, "> 0", "N mm", "LTCA gear torque")
    if len(positions) == 0:
        raise DesignError.single("positions", 0, ">= 1 mesh position", "-", "LTCA")
    if len(grid) != 2 or min(grid) < 1:
        raise DesignError.single("grid", grid, "(n_major >= 1, n_minor >= 1)", "-", "LTCA potential contact grid")
    for name, v in (("half_length", half_length), ("half_width", half_width)):
        if v is None:  # per-pair extents (PairContact.extents); checked where used
            continue
        if not (np.isfinite(v) and v > 0):
            raise DesignError.single(name, v, "> 0", "mm", "LTCA potential contact grid")


def fe_local_flexibility(compliance, reach: float = 3.5) -> np.ndarray:
    """The local (contact-scale) part of an FE flank compliance, to be removed where the half-space term models it.

    For a load at node j, the deflection of the loaded flank of the same tooth is split into a smooth part (bending,
    shear, base rotation: a quadratic in the flank's arc-length coordinates fitted to the nodes farther than
    ``reach`` node spacings from j) and the local rest near j (the FE's own indentation at its mesh resolution). This
    returns that rest (mm/N, node order of ``compliance.G``, symmetrized, zero beyond ``reach`` and between teeth).
    The indentation decays like 1/r, so the split depends on ``reach``: measured against Hertz at a one-pair position
    (peak pressure, log-spiral pair, 9 x 6 / 15 x 8 FE flank grids) 1.5 spacings give -3.2 / -5.2 %, 2.5 give
    -2.9 / -5.1 %, 3.5 give +1.0 / -1.2 % (the default).
    """
    G = np.asarray(compliance.G, float)
    L = np.zeros_like(G)
    o = 0
    for k in compliance.teeth:
        g = np.asarray(compliance.grids[k], float)
        nf, npf = g.shape[:2]
        s = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(g[:, npf // 2], axis=0), axis=-1))]
        t = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(g[nf // 2, :], axis=0), axis=-1))]
        S, T = (a.ravel() for a in np.meshgrid(s / (s[-1] / (nf - 1)), t / (t[-1] / (npf - 1)), indexing="ij"))
        n = nf * npf
        A = np.stack([np.ones(n), S, T, S * S, S * T, T * T], 1)
        blk = G[o:o + n, o:o + n]
        for j in range(n):
            d = np.hypot(S - S[j], T - T[j])
            far, near = d > reach, d <= reach
            if far.sum() < 2 * A.shape[1]:
                continue  # too few nodes away from the load to fit the smooth part: nothing removed
            coef = np.linalg.lstsq(A[far], blk[far, j], rcond=None)[0]
            L[o + np.flatnonzero(near), o + j] = blk[near, j] - A[near] @ coef
        o += n
    return 0.5 * (L + L.T)


class _BendingOnly:
    """A ToothCompliance with its local part removed (``G - fe_local_flexibility``, projected onto the positive
    semi-definite matrices): bending, shear and base rotation of the tooth, the local deformation being the
    half-space term's."""

    _cache: dict = {}

    def __init__(self, comp):
        self._comp = comp
        key = (getattr(comp, "key", None), id(comp.G))
        if key not in _BendingOnly._cache:
            if len(_BendingOnly._cache) > 8:
                _BendingOnly._cache.clear()
            B = comp.G - fe_local_flexibility(comp)
            # a flexibility is positive semi-definite: the split leaves small negative modes (oscillating from node
            # to node, the fit's residue), which a fine contact grid would resolve; they are clipped to zero
            lam, V = np.linalg.eigh(0.5 * (B + B.T))
            B = (V * np.maximum(lam, 0.0)) @ V.T
            _BendingOnly._cache[key] = (comp.G, B)
        self.G = _BendingOnly._cache[key][1]

    def weight_matrix(self, teeth, points):
        return self._comp.weight_matrix(teeth, points)


def _bending_only(comp):
    """``comp`` without its FE local response (None stays None; already split stays as is)."""
    return comp if comp is None or isinstance(comp, _BendingOnly) else _BendingOnly(comp)


def run_ltca(positions: Sequence[ContactPosition], torque: float, pinion_compliance: ToothCompliance | None = None,
             gear_compliance: ToothCompliance | None = None, *, gear_axis, gear_origin=(0.0, 0.0, 0.0),
             grid=(21, 7), half_length=8.0, half_width=0.8, material_pinion: Material = STEEL,
             material_gear: Material = STEEL, mean_position: int | None = None,
             approach_target: float | None = APPROACH_TARGET) -> LTCAResult:
    """Loaded tooth contact analysis over mesh positions (seed 001 §4.3.2, Eq. (18); docs/theory/ltca.md, Eqs.
    (L1)-(L4)).

    Parameters
    ----------
    positions : sequence of ContactPosition
        Unloaded contact of every pair at every mesh position (same pair order at every position).
    torque : float, N mm
        Gear torque T (> 0).
    pinion_compliance, gear_compliance : ToothCompliance, optional
        FE flexibility of the loaded flanks (:func:`~spiralbevel.meshing.ltca.compliance.tooth_compliance`); None
        means rigid teeth (contact flattening only).
    gear_axis : (3,) float
        Unit gear axis a2 in the pair frame.
    gear_origin : (3,) float, mm
        A point of the gear axis.
    grid : (int, int)
        Potential contact points per pair along the major and the minor axis.
    half_length, half_width : float or None, mm
        Half extents of that grid for pairs without their own ``PairContact.extents`` (points off either flank grid
        are dropped when compliances are given).
    material_pinion, material_gear : Material
        For the contact modulus of the half-space term.
    mean_position : int, optional
        Index of the mean position for the approach torque; default the position with the smallest |pinion angle|.
    approach_target : float or None, mm
        Tooth approach at the mean contact point whose torque is searched (None: skip the root find).

    Returns
    -------
    LTCAResult
    """
    _check(torque, positions, grid, half_length, half_width)
    a2 = np.asarray(gear_axis, float)
    a2 = a2 / np.linalg.norm(a2)
    o2 = np.asarray(gear_origin, float)
    estar = contact_modulus(material_pinion, material_gear)
    # the local deformation is counted once: the half-space term at the contact cells, the FE model without its own
    # local response at the flank nodes (fe_local_flexibility)
    pinion_compliance, gear_compliance = _bending_only(pinion_compliance), _bending_only(gear_compliance)
    n_pairs = max(len(p.pairs) for p in positions)
    ns, nt = grid
    cell_state = np.zeros(n_pairs * ns * nt, bool)
    out: dict[str, list] = {
        k: [] for k in ("dtheta", "dtheta0", "share", "pf", "pmax", "pts", "pair", "F", "p", "x1", "x2", "te")}
    for k, pos in enumerate(positions):
        sysk = _assemble(k, pos, pinion_compliance, gear_compliance, a2, o2, grid, half_length, half_width, estar)
        warm = cell_state[sysk.flat]
        sol = solve_load_distribution(sysk.C, sysk.w, sysk.h, torque, active=warm if warm.any() else None,
                                      position=k, check_spd=(k == 0))
        cell_state[:] = False
        cell_state[sysk.flat[sol.active]] = True
        pf = np.bincount(sysk.pair, weights=sol.force, minlength=n_pairs)
        out["share"].append(np.bincount(sysk.pair, weights=sol.force * sysk.h, minlength=n_pairs) / torque)
        out["pf"].append(pf)
        out["dtheta"].append(sol.dtheta)
        out["dtheta0"].append(np.min(sysk.w / sysk.h))
        p = sol.force / sysk.cell
        out["pmax"].append(p.max())
        for key, v in (("pts", sysk.q), ("pair", sysk.pair), ("F", sol.force), ("p", p), ("x1", sysk.x1),
                       ("x2", sysk.x2)):
            out[key].append(v)
        te = np.full(n_pairs, np.nan)
        te[: len(sysk.te)] = sysk.te
        out["te"].append(te)
    angles = np.array([p.pinion_angle for p in positions], float)
    T_app = None
    if approach_target is not None:
        m = int(np.argmin(np.abs(angles))) if mean_position is None else int(mean_position)
        T_app = torque_for_approach(positions[m], approach_target, pinion_compliance, gear_compliance, a2, o2, grid,
                                    half_length, half_width, estar, m)
    return LTCAResult(
        pinion_angles=angles, torque=float(torque), te_unloaded=-np.array(out["dtheta0"]) / ARCSEC,
        te_loaded=-np.array(out["dtheta"]) / ARCSEC, te_pairs=np.array(out["te"]) / ARCSEC,
        load_share=np.array(out["share"]), pair_force=np.array(out["pf"]), max_pressure=np.array(out["pmax"]),
        points=out["pts"], pair_of_point=out["pair"], force=out["F"], pressure=out["p"], points1=out["x1"],
        points2=out["x2"], dtheta=np.array(out["dtheta"]), approach_torque=T_app,
        approach_target=approach_target if approach_target is not None else APPROACH_TARGET,
        pair_names=tuple(f"pair {j - (n_pairs - 1) // 2:+d}" for j in range(n_pairs)))


def torque_for_approach(position, target, comp1, comp2, a2, o2, grid, half_length, half_width, estar, index=0):
    """Gear torque [N mm] at which the tooth approach at the mean contact point reaches ``target`` [mm].

    The approach is (dtheta(T) - dtheta(0)) h_m, the elastic closure at the contact point of the pair that touches
    first (lever arm h_m); it grows monotonically with T, so a bracketing root find (Brent, on log T) is exact.
    """
    if not (np.isfinite(target) and target > 0):
        raise DesignError.single("approach_target", target, "> 0", "mm", "approach torque")
    comp1, comp2 = _bending_only(comp1), _bending_only(comp2)  # the local deformation counted once (run_ltca)
    sysm = _assemble(index, position, comp1, comp2, a2, o2, grid, half_length, half_width, estar)
    j = int(np.nanargmax(sysm.te))
    th0 = np.min(sysm.w / sysm.h)
    hm = sysm.h0[j]

    def f(logT):
        sol = solve_load_distribution(sysm.C, sysm.w, sysm.h, np.exp(logT), position=index, check_spd=False)
        return (sol.dtheta - th0) * hm - target

    lo, hi = np.log(1e-3), np.log(1e10)
    if f(lo) > 0 or f(hi) < 0:
        raise DesignError.single("approach_target", target, "an approach reached between 1e-3 and 1e10 N mm", "mm",
                                 f"approach torque at mesh position {index}")
    return float(np.exp(brentq(f, lo, hi, xtol=1e-10, rtol=1e-12)))
