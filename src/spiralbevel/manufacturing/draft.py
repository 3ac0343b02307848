"""Forging draft of a log-spiral flank: where can the forged part leave the die? (seed 000 §5.1,
docs/theory/logspiral.md, Eq. (S13))

The part moves along the unit die direction v_d relative to the die. A flank point can be released without damage
when its outward normal does not face the motion, n_out · v_d ≤ 0 (seed 000 Eq. (38) with the outward normal).
For v_d = +z, n_out·z = -sign(psi) sin(psi - beta) cos(delta) (docs/theory/logspiral.md, Eq. (S13)), so

* convex flank (sign psi = sign beta): draftable iff |varphi - phi| ≥ |beta| / sin(delta), i.e. |psi| ≥ |beta|;
* concave flank: always draftable.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..conventions import Side
from ..errors import DesignError
from ._flank import FlankLike, FlankParams, check_flank, outward_geometry, unit_vector

__all__ = ["DraftResult", "draft_map", "analytic_failing_fraction"]

_AXIAL_TOL = 1e-12


@dataclass(frozen=True)
class DraftResult:
    """Draft map of one flank for one die direction.

    Attributes
    ----------
    varphi, phi, psi : (n_phi, n_psi) float, rad
        Grid over the domain: rows from toe (phi_min) to heel, columns from psi_min to psi_max.
    points : (n_phi, n_psi, 3) float, mm
        Flank points in the member frame.
    normal_dot_die : (n_phi, n_psi) float
        n_out · v_d (dimensionless).
    draftable : (n_phi, n_psi) bool
        ``normal_dot_die <= 0``.
    failing_area_fraction : float
        Area-weighted fraction of the flank that is not draftable (0..1).
    failing_area, total_area : float, mm^2
        Failing and total flank area.
    die_direction : (3,) float
        Unit die direction v_d.
    side : Side
        CONVEX or CONCAVE.
    spiral_angle, base_cone_angle : float, rad
        beta and delta of the flank.
    boundary_psi : float or None, rad
        Analytic boundary psi = beta (a straight line varphi - phi = beta/sin(delta) in the (varphi, phi) plane)
        when v_d is parallel to ±z and the line crosses the domain; otherwise None.
    boundary : (2, 2) float or None, rad
        End points (varphi, phi) of that line at phi_min and phi_max, or None.
    analytic_fraction : float or None
        Closed-form failing area fraction when v_d is parallel to ±z (see :func:`analytic_failing_fraction`), else
        None.
    """

    varphi: np.ndarray
    phi: np.ndarray
    psi: np.ndarray
    points: np.ndarray
    normal_dot_die: np.ndarray
    draftable: np.ndarray
    failing_area_fraction: float
    failing_area: float
    total_area: float
    die_direction: np.ndarray
    side: Side
    spiral_angle: float
    base_cone_angle: float
    boundary_psi: "float | None"
    boundary: "np.ndarray | None"
    analytic_fraction: "float | None"

    @property
    def passes(self) -> bool:
        """True when every grid point is draftable."""
        return bool(np.all(self.draftable))


def _check_count(value, field: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 2:
        raise DesignError.single(field, value, "an integer >= 2", "-")
    return int(value)


def _positive_integral(g, J, area):
    """Integral of the linear interpolant of J over the part of each triangle where the linear interpolant of g > 0.

    Parameters
    ----------
    g, J : (..., 3) float
        Vertex values of the level function and of the integrand.
    area : float or (...) float
        Triangle areas (any coordinates).

    Notes
    -----
    Exact for linear g and J on each triangle. One positive vertex P: the region is the triangle P, P + tA (A - P),
    P + tB (B - P) with t = g_P / (g_P - g_X), of area tA tB area, and the integral of a linear function over a
    triangle is its area times the mean of its vertex values. Two positive vertices: the full integral minus the
    clipped triangle at the non-positive vertex.
    """
    pos = g > 0
    npos = pos.sum(-1)
    full = area * J.mean(-1)

    def corner(gs, k):
        # integral over the corner triangle at vertex k, cut where the interpolant of gs changes sign
        others = np.stack([(k + 1) % 3, (k + 2) % 3], -1)
        gk = np.take_along_axis(gs, k[..., None], -1)[..., 0]
        Jk = np.take_along_axis(J, k[..., None], -1)[..., 0]
        go = np.take_along_axis(gs, others, -1)
        Jo = np.take_along_axis(J, others, -1)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(gk[..., None] - go > 0, gk[..., None] / (gk[..., None] - go), 0.0)
        Jc = Jk[..., None] + t * (Jo - Jk[..., None])
        return area * t[..., 0] * t[..., 1] * (Jk + Jc[..., 0] + Jc[..., 1]) / 3.0

    one = corner(g, np.argmax(g, -1))
    two = full - corner(-g, np.argmin(g, -1))
    return np.where(npos == 3, full, np.where(npos == 2, two, np.where(npos == 1, one, 0.0)))


def _grid_integrals(psi, phi, gval, J):
    """Failing and total area on a tensor grid in (psi, phi): two triangles per cell, linear interpolation."""
    dpsi = np.diff(psi[0, :])
    dphi = np.diff(phi[:, 0])
    cell = dphi[:, None] * dpsi[None, :]
    q = [(slice(None, -1), slice(None, -1)), (slice(1, None), slice(None, -1)),
         (slice(1, None), slice(1, None)), (slice(None, -1), slice(1, None))]
    gv = [gval[s] for s in q]
    Jv = [J[s] for s in q]
    fail = total = 0.0
    for a, b, c in ((0, 1, 2), (0, 2, 3)):
        g3 = np.stack([gv[a], gv[b], gv[c]], -1)
        J3 = np.stack([Jv[a], Jv[b], Jv[c]], -1)
        fail += float(_positive_integral(g3, J3, 0.5 * cell).sum())
        total += float((0.5 * cell * J3.mean(-1)).sum())
    return fail, total


def _axial_sign(v) -> int:
    """+1 or -1 when v is parallel to ±z (within 1e-12), else 0."""
    if math.hypot(v[0], v[1]) <= _AXIAL_TOL:
        return 1 if v[2] > 0 else -1
    return 0


def _fraction_axial(p: FlankParams, domain, sz: int) -> float:
    """Closed-form failing fraction for v_d = sz * z (sz = ±1).

    dA = rho(phi)^2 |sin psi| cos(delta)/|sin beta| dpsi dphi separates, so the phi factor cancels and the fraction
    is a ratio of integrals of |sin psi| over |psi| intervals: (cos lo - cos hi) / (cos a - cos b).
    """
    a, b = sorted((abs(domain.psi_min), abs(domain.psi_max)))
    bb = abs(p.beta)
    if p.side is Side.CONVEX:
        lo, hi = (a, min(b, max(a, bb))) if sz > 0 else (min(b, max(a, bb)), b)
    else:
        lo, hi = (a, a) if sz > 0 else (a, b)
    return (math.cos(lo) - math.cos(hi)) / (math.cos(a) - math.cos(b))


def analytic_failing_fraction(flank: FlankLike, domain, die_direction=(0.0, 0.0, 1.0)) -> float:
    """Closed-form area fraction of the flank that fails the draft test, for a die direction along ±z.

    Parameters
    ----------
    flank : FlankLike
        ``rho0`` mm, ``base_cone_angle`` rad, ``spiral_angle`` rad.
    domain : ParallelogramDomain
    die_direction : (3,) float
        Must be parallel to +z or -z (normalized here).

    Returns
    -------
    float
        Failing area fraction, 0..1.

    Notes
    -----
    With a = min|psi|, b = max|psi| over the domain, the failing set for v_d = +z is a <= |psi| < min(b, |beta|)
    on the convex flank and empty on the concave flank (docs/theory/logspiral.md, Eq. (S13)); the fraction is
    (cos a - cos min(b, max(a, |beta|))) / (cos a - cos b). For v_d = -z the complement.
    """
    p = check_flank(flank, domain)
    v = unit_vector(die_direction, "die_direction")
    sz = _axial_sign(v)
    if sz == 0:
        raise DesignError.single("die_direction", tuple(np.asarray(die_direction, float)), "parallel to +z or -z",
                                 "-", "the closed form exists only for an axial die direction; use draft_map")
    return _fraction_axial(p, domain, sz)


def draft_map(flank: FlankLike, domain, die_direction=(0.0, 0.0, 1.0), n_phi: int = 101,
              n_psi: int = 101) -> DraftResult:
    """Draft map of a log-spiral flank: n_out · v_d over the domain, draftable mask and failing area.

    Parameters
    ----------
    flank : FlankLike
        Object with ``rho0`` (float, mm), ``base_cone_angle`` (float, rad), ``spiral_angle`` (float, rad), such
        as ``LogSpiralFlank``.
    domain : ParallelogramDomain
        Flank domain (rectangle in (psi, phi)); its sign of psi selects the convex or concave branch.
    die_direction : (3,) float
        Direction v_d in which the part leaves the die, member frame; normalized here. Zero -> DesignError.
    n_phi, n_psi : int
        Grid size (>= 2) along phi (toe to heel) and psi (root to top).

    Returns
    -------
    DraftResult

    Notes
    -----
    seed 000 Eq. (38) with the outward normal n_out = sign(psi) n (docs/theory/logspiral.md, Eqs. (S9), (S13)): a point
    is draftable
    iff n_out · v_d <= 0. The failing area is the integral of the area element
    dA = sqrt(EG - F^2) dvarphi dphi = rho^2 |sin psi| cos(delta)/|sin beta| dpsi dphi over {n_out · v_d > 0}: each
    grid cell is split into two triangles, n_out·v_d and dA are interpolated linearly and the positive part is
    clipped exactly, which converges as O(h^2) in the grid step (measured in tests/manufacturing/test_draft.py).
    """
    p = check_flank(flank, domain)
    v = unit_vector(die_direction, "die_direction")
    n_phi = _check_count(n_phi, "n_phi")
    n_psi = _check_count(n_psi, "n_psi")
    varphi, phi = domain.grid(n_phi, n_psi)
    geo = outward_geometry(varphi, phi, p)
    gval = geo["n_out"] @ v
    J = geo["dA"] / math.sin(p.delta)  # area element per dpsi dphi
    fail, total = _grid_integrals(geo["psi"], phi, gval, J)
    sz = _axial_sign(v)
    boundary_psi = boundary = analytic = None
    if sz != 0:
        analytic = _fraction_axial(p, domain, sz)
        if domain.psi_min < p.beta < domain.psi_max:
            boundary_psi = p.beta
            ph = np.array([domain.phi_min, domain.phi_max])
            boundary = np.stack([domain.to_varphi(p.beta, ph), ph], -1)
    return DraftResult(
        varphi=varphi, phi=phi, psi=geo["psi"], points=geo["r"], normal_dot_die=gval, draftable=gval <= 0.0,
        failing_area_fraction=fail / total, failing_area=fail, total_area=total, die_direction=v, side=p.side,
        spiral_angle=p.beta, base_cone_angle=p.delta, boundary_psi=boundary_psi, boundary=boundary,
        analytic_fraction=analytic,
    )
