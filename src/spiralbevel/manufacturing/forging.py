"""Forging relief of a log-spiral flank: the smallest two-parameter modification that draws from the die.

Seed 000 §5.1 (Eqs. (38)-(39), Figure 8) shows that the convex flank of a log-spiral bevel gear cannot leave a forging
die that opens along the gear axis where |psi| < |beta| (with the outward normal; the printed inequalities hold for
beta > 0 only), and says the modification "can be easily controlled by two simple feature parameters". This module
defines those two parameters and chooses them.

**The relief.** Below a coaxial cone of the flank (toward the root), material is added along the outward normal,

    w(varphi, phi) = rho(phi) kappa (psi_s - |psi|)^2 / 2      for |psi| < psi_s,      w = 0 elsewhere,

with psi = (varphi - phi) sin(delta) (seed 000 Eq. (16)). The two feature parameters are

* ``start_psi`` psi_s (rad): the flank line where the relief begins, the intersection of the flank with the coaxial
  cone of half-angle gamma_s, cos(gamma_s) = cos(psi_s) cos(delta) (a straight line varphi - phi = psi_s / sin(delta)
  in the parameter plane, parallel to the line of Eq. (39));
* ``rate`` kappa (dimensionless): how fast the relief leaves the theoretical flank. w / rho is the relief seen from
  the apex as an angle; kappa is its second derivative with respect to psi. Scaling with rho makes the relief
  self-similar like the flank itself (a dilation about the apex maps the flank and the relief onto themselves).

w and its gradient vanish on |psi| = psi_s, so the relieved flank is continuous in position and in normal there
(G1); its curvature jumps, as for any tangent relief. Why material is *added* below the cone: n_out . v_d decreases
when w decreases in the direction of steepest rise of the flank along v_d, and on the convex flank that direction
points from the top toward the root (e1 . z = -sin(delta) < 0) and toward the toe; a relief that vanishes
tangentially on a line across the flank must therefore grow toward the root.

**Exact geometry.** r' = r + w n_out with the closed forms of seed 000 (corrected Eqs. (19)-(21)):
r'_a = r_a + w_a n_out + w (n_out)_a, n' = unit(r'_varphi x r'_phi) oriented like n_out, with
(n_out)_varphi = sign(psi) cos(delta) cos(psi - beta) m and (n_out)_phi = sign(psi) sin(delta) e2. Curvatures of the
relieved flank are those of the generic differential geometry (:func:`spiralbevel.geometry.diffgeom.surface_geometry`).

**Choice of the parameters.** The draft condition with a minimum draft angle theta is n' . v_d <= -sin(theta) at
every point. psi_s must lie where the theoretical flank already passes; for each admissible psi_s the smallest
kappa that passes is found by bisection, and psi_s is chosen to minimise the added volume int w dA. At the optimum,
lowering either parameter fails the condition (tests/manufacturing/test_forging.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._core import logspiral as _ls
from ..errors import DesignError
from ._flank import FlankLike, FlankParams, check_flank, unit_vector
from .draft import DraftResult, _grid_integrals

__all__ = ["ForgingRelief", "RelievedFlank", "design_forging_relief", "relieved_draft_map"]

_RATE_MAX = 1.0e4        # kappa beyond which no relief of this family is sought (w ~ rho kappa dpsi^2 / 2)
_BISECT_REL = 1.0e-7     # relative bracket of the bisection on kappa


@dataclass(frozen=True)
class ForgingRelief:
    """The two feature parameters of the forging relief (see the module docstring).

    Attributes
    ----------
    start_psi : float, rad
        psi_s > 0: |psi| of the flank line where the relief leaves the theoretical flank.
    rate : float
        kappa >= 0 (dimensionless): w = rho kappa (psi_s - |psi|)^2 / 2 below that line.
    """

    start_psi: float
    rate: float

    def __post_init__(self):
        for name, strict, unit in (("start_psi", True, "rad"), ("rate", False, "-")):
            v = getattr(self, name)
            real = not isinstance(v, bool) and isinstance(v, (int, float, np.floating)) and math.isfinite(v)
            if not real or v < 0 or (strict and v == 0):
                raise DesignError.single(name, v, "a finite number > 0" if strict else "a finite number >= 0", unit)
            object.__setattr__(self, name, float(v))

    def deviation(self, psi, phi, p: FlankParams):
        """w (mm) and its partial derivatives (w_varphi, w_phi) in mm/rad at signed ``psi`` and ``phi`` (rad)."""
        psi, phi = np.broadcast_arrays(np.asarray(psi, float), np.asarray(phi, float))
        rho = p.rho0 * np.exp(phi * math.sin(p.delta) / math.tan(p.beta))
        s = np.where(psi >= 0, 1.0, -1.0)
        u = np.maximum(self.start_psi - np.abs(psi), 0.0)
        sd = math.sin(p.delta)
        w = 0.5 * rho * self.rate * u**2
        w_u = rho * self.rate * u
        w_varphi = -w_u * s * sd
        w_phi = w * sd / math.tan(p.beta) + w_u * s * sd
        return w, w_varphi, w_phi

    def contact_deviation(self, p: FlankParams):
        """``params (..., 2) -> (w, grad)`` in the flank parameters (varphi, phi) for
        :class:`~spiralbevel.meshing.contact_surface.NormalDeviation` (TCA of the relieved flank)."""
        sd = math.sin(p.delta)

        def deviation(params):
            q = np.asarray(params, float)
            w, wa, wb = self.deviation((q[..., 0] - q[..., 1]) * sd, q[..., 1], p)
            return w, np.stack([wa, wb], -1)

        return deviation


@dataclass(frozen=True)
class RelievedFlank:
    """A log-spiral flank with a forging relief (or none), in the unrotated frame of its surface.

    Parameters
    ----------
    flank : FlankLike
        ``rho0`` mm, ``base_cone_angle`` rad, ``spiral_angle`` rad (e.g. ``LogSpiralFlank``).
    domain : ParallelogramDomain
        Its domain; the sign of psi selects the branch.
    relief : ForgingRelief or None
        None: no forging relief.
    base_deviation : callable, optional
        A further displacement along the theoretical outward normal, ``params (..., 2) -> (w (...), grad (..., 2))``
        in (varphi, phi) (mm, mm/rad), e.g. the crowning of a mismatched pair
        (:meth:`~spiralbevel.meshing.synthesis.logspiral_crowning.LogSpiralCrowning.deviation`); the relief adds to it.
    """

    flank: FlankLike
    domain: Any
    relief: "ForgingRelief | None" = None
    base_deviation: object = None

    @property
    def params(self) -> FlankParams:
        return check_flank(self.flank, self.domain)

    def evaluate(self, varphi, phi):
        """Exact points, outward unit normals and area elements at (varphi, phi).

        Parameters
        ----------
        varphi, phi : array_like float, rad
            Broadcast together; psi must be nonzero.

        Returns
        -------
        point : (..., 3) float, mm
        normal : (..., 3) float
            Outward unit normal of the relieved flank.
        dA : (...) float, mm^2/rad^2
            |r'_varphi x r'_phi|.
        w : (...) float, mm
            Relief plus base deviation along the theoretical outward normal (+ = material added).
        """
        p = self.params
        g = _ls.geometry(varphi, phi, p.rho0, p.delta, p.beta)
        s = np.where(g["psi"] >= 0, 1.0, -1.0)[..., None]
        n = s * g["n"]
        shape = g["psi"].shape
        if self.relief is None and self.base_deviation is None:
            cr = np.cross(g["r_varphi"], g["r_phi"])
            return g["r"], n, np.linalg.norm(cr, axis=-1), np.zeros(shape)
        phi_b = np.broadcast_to(np.asarray(phi, float), shape)
        if self.relief is not None:
            w, wa, wb = self.relief.deviation(g["psi"], phi_b, p)
        else:
            w, wa, wb = np.zeros(shape), np.zeros(shape), np.zeros(shape)
        if self.base_deviation is not None:
            varphi_b = np.broadcast_to(np.asarray(varphi, float), shape)
            w0, g0 = self.base_deviation(np.stack([varphi_b, phi_b], -1))
            w, wa, wb = w + w0, wa + g0[..., 0], wb + g0[..., 1]
        cpb = np.cos(g["psi"] - p.beta)
        n_a = s * (math.cos(p.delta) * cpb)[..., None] * g["e1"]           # e1 of the kernel is m
        n_b = s * math.sin(p.delta) * g["e2"]
        ra = g["r_varphi"] + wa[..., None] * n + w[..., None] * n_a
        rb = g["r_phi"] + wb[..., None] * n + w[..., None] * n_b
        cr = np.cross(ra, rb)
        dA = np.linalg.norm(cr, axis=-1)
        nn = cr / dA[..., None]
        nn *= np.sign(np.einsum("...i,...i->...", nn, n))[..., None]
        return g["r"] + w[..., None] * n, nn, dA, w

    def point(self, varphi, phi):
        """Points of the relieved flank, (..., 3) mm."""
        return self.evaluate(varphi, phi)[0]


def _check_angle(value, field):
    try:
        x = float(value)
    except (TypeError, ValueError) as err:
        raise DesignError.single(field, value, "0 <= value < pi/2", "rad", "not a number") from err
    if not (math.isfinite(x) and 0.0 <= x < 0.5 * math.pi):
        raise DesignError.single(field, value, "0 <= value < pi/2", "rad")
    return x


def relieved_draft_map(relieved: RelievedFlank, die_direction=(0.0, 0.0, 1.0), draft_angle: float = 0.0,
                       n_phi: int = 101, n_psi: int = 101) -> DraftResult:
    """Draft map of a (relieved) flank with a minimum draft angle.

    Parameters
    ----------
    relieved : RelievedFlank
    die_direction : (3,) float
        v_d, member frame of the unrotated surface (an axial direction is invariant under the placement rotation).
    draft_angle : float, rad
        theta >= 0: a point passes when n' . v_d <= -sin(theta).
    n_phi, n_psi : int
        Grid along phi and psi (>= 2).

    Returns
    -------
    DraftResult
        ``normal_dot_die`` is n' . v_d; ``draftable`` is n' . v_d <= -sin(theta); the failing area is that of
        {n' . v_d + sin(theta) > 0} (exact clipping of the linear interpolant on the grid triangles). The analytic
        fields are left None (they belong to the theoretical flank, see :func:`~.draft.draft_map`).
    """
    v = unit_vector(die_direction, "die_direction")
    theta = _check_angle(draft_angle, "draft_angle")
    for name, k in (("n_phi", n_phi), ("n_psi", n_psi)):
        if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or k < 2:
            raise DesignError.single(name, k, "an integer >= 2", "-")
    p = relieved.params
    d = relieved.domain
    varphi, phi = d.grid(int(n_phi), int(n_psi))
    r, n, dA, _ = relieved.evaluate(varphi, phi)
    gval = n @ v
    psi = (varphi - phi) * math.sin(p.delta)
    fail, total = _grid_integrals(psi, phi, gval + math.sin(theta), dA / math.sin(p.delta))
    return DraftResult(
        varphi=varphi, phi=phi, psi=psi, points=r, normal_dot_die=gval, draftable=gval <= -math.sin(theta),
        failing_area_fraction=fail / total, failing_area=fail, total_area=total, die_direction=v, side=p.side,
        spiral_angle=p.beta, base_cone_angle=p.delta, boundary_psi=None, boundary=None, analytic_fraction=None)


@dataclass(frozen=True)
class ReliefDesign:
    """Result of :func:`design_forging_relief`.

    Attributes
    ----------
    relief : ForgingRelief or None
        None when the theoretical flank already passes.
    relieved : RelievedFlank
    volume : float, mm^3
        Added material int w dA over the flank.
    max_deviation : float, mm
        Largest relief w (at the root edge), the base deviation left out.
    relieved_fraction : float
        Area fraction of the flank below the start line.
    theoretical_failing_fraction : float
        Failing area fraction of the theoretical flank with the same draft angle.
    """

    relief: "ForgingRelief | None"
    relieved: RelievedFlank
    volume: float
    max_deviation: float
    relieved_fraction: float
    theoretical_failing_fraction: float


def _worst(relieved, v, sin_t, varphi, phi):
    return float(np.max(relieved.evaluate(varphi, phi)[1] @ v + sin_t))


def design_forging_relief(flank: FlankLike, domain, die_direction=(0.0, 0.0, 1.0), draft_angle: float = 0.0,
                          n_phi: int = 101, n_psi: int = 101, n_start: int = 12,
                          base_deviation=None) -> ReliefDesign:
    """The forging relief of least added volume that makes the flank draw from the die.

    Parameters
    ----------
    flank : FlankLike
    domain : ParallelogramDomain
    die_direction : (3,) float
        v_d (part leaves the die along +v_d), member frame.
    draft_angle : float, rad
        Minimum draft angle theta, 0 <= theta < pi/2.
    n_phi, n_psi : int
        Check grid (the grid of :func:`relieved_draft_map`): the relief passes on every node of it.
    n_start : int
        Number of trial start lines between the first admissible one and the top (then refined by golden section).
    base_deviation : callable, optional
        Deviation already carried by the flank (e.g. its crowning), see :class:`RelievedFlank`; the relief is
        designed on top of it and the volume counts the relief only.

    Returns
    -------
    ReliefDesign

    Raises
    ------
    DesignError
        The top of the flank fails the draft condition (no relief below a start line can help: choose a smaller
        spiral angle, a smaller draft angle or the other die direction), or no rate up to 1e4 passes.
    """
    p = check_flank(flank, domain)
    v = unit_vector(die_direction, "die_direction")
    theta = _check_angle(draft_angle, "draft_angle")
    sin_t = math.sin(theta)
    varphi, phi = domain.grid(int(n_phi), int(n_psi))
    psi = (varphi - phi) * math.sin(p.delta)
    apsi = np.abs(psi)
    theo = RelievedFlank(flank, domain, None, base_deviation)
    base = relieved_draft_map(theo, v, theta, n_phi, n_psi)
    g0 = base.normal_dot_die + sin_t
    col_fail = np.any(g0 > 0, axis=0)
    if not col_fail.any():
        return ReliefDesign(None, theo, 0.0, 0.0, 0.0, base.failing_area_fraction)
    top = int(np.argmax(apsi[0]))
    if col_fail[top]:
        raise DesignError.single(
            "manufacturing.draft_angle", math.degrees(theta), "a draft angle the top of the flank already has", "deg",
            f"the {p.side.value} flank fails the draft at its top edge (|psi| = {math.degrees(apsi[0, top]):.3f} deg, "
            f"spiral angle {math.degrees(abs(p.beta)):.3f} deg): a relief below a start line cannot fix it; lower "
            "gear_set.mean_spiral_angle (seed 000 Eq. (39): |psi| >= |beta| on the convex flank) or the draft angle")
    # lowest admissible start: every column with |psi| >= psi_s must pass on the theoretical flank
    order = np.argsort(apsi[0])
    a_sorted, f_sorted = apsi[0][order], col_fail[order]
    last_fail = np.nonzero(f_sorted)[0].max()
    lo_psi = float(a_sorted[last_fail])
    psi_top = float(a_sorted[-1])

    def rate_for(ps):
        """Smallest kappa passing on the grid with start ps (bisection on a monotone condition)."""
        def worst(k):
            return _worst(RelievedFlank(flank, domain, ForgingRelief(ps, k), base_deviation), v, sin_t, varphi, phi)
        hi = 1.0
        while worst(hi) > 0:
            hi *= 2.0
            if hi > _RATE_MAX:
                return math.inf
        lo = 0.0
        while hi - lo > _BISECT_REL * hi:
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if worst(mid) > 0 else (lo, mid)
        return hi

    area = base.total_area

    def volume(ps, k):
        r = RelievedFlank(flank, domain, ForgingRelief(ps, k))
        _, _, dA, w = r.evaluate(varphi, phi)  # relief alone
        return _trapz2(w * dA / math.sin(p.delta), psi, phi)

    # start lines strictly above the last failing column (a start on a failing node cannot pass there)
    starts = lo_psi + (psi_top - lo_psi) * (np.arange(1, n_start + 1) / n_start) ** 2 * 0.999
    best = None
    for ps in starts:
        k = rate_for(float(ps))
        if not math.isfinite(k):
            continue
        vol = volume(float(ps), k)
        if best is None or vol < best[0]:
            best = (vol, float(ps), k)
    if best is None:
        raise DesignError.single("manufacturing.draft_angle", math.degrees(theta), "a smaller draft angle", "deg",
                                 f"no relief rate up to {_RATE_MAX:g} makes the {p.side.value} flank draw")
    # golden-section refinement of the start between its neighbours
    i = int(np.searchsorted(starts, best[1]))
    a = float(starts[i - 1]) if i > 0 else lo_psi + 1e-9 * (psi_top - lo_psi)
    b = float(starts[min(i + 1, len(starts) - 1)])
    gr = 0.5 * (math.sqrt(5.0) - 1.0)
    cache = {}

    def f(ps):
        if ps not in cache:
            k = rate_for(ps)
            cache[ps] = (volume(ps, k) if math.isfinite(k) else math.inf, k)
        return cache[ps][0]

    c, d = b - gr * (b - a), a + gr * (b - a)
    for _ in range(12):
        if f(c) < f(d):
            b, d = d, c
            c = b - gr * (b - a)
        else:
            a, c = c, d
            d = a + gr * (b - a)
    for ps in (c, d):
        f(ps)
        if cache[ps][0] < best[0]:
            best = (cache[ps][0], ps, cache[ps][1])
    vol, ps, k = best
    relief = ForgingRelief(ps, k)
    relieved = RelievedFlank(flank, domain, relief, base_deviation)
    w = RelievedFlank(flank, domain, relief).evaluate(varphi, phi)[3]
    frac = _trapz2((apsi < ps) * base_dA(theo, varphi, phi) / math.sin(p.delta), psi, phi) / area
    return ReliefDesign(relief, relieved, float(vol), float(w.max()), float(frac), base.failing_area_fraction)


def base_dA(relieved, varphi, phi):
    """Area element |r_varphi x r_phi| (mm^2/rad^2) of the flank on a grid."""
    return relieved.evaluate(varphi, phi)[2]


def _trapz2(f, psi, phi):
    """Trapezoidal integral of f over the (psi, phi) tensor grid (rows phi, columns psi)."""
    return float(abs(np.trapezoid(np.trapezoid(f, psi[0, :], axis=1), phi[:, 0])))
