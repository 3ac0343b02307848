"""5-axis ball-end milling of a log-spiral flank along its lengthwise lines of curvature (seed 000 §5.2).

The passes are the phi-curves (varphi = const): planar log spirals, which are lines of curvature because F = M = 0
(docs/theory/logspiral.md, Eqs. (S7)-(S8)), as seed 000 §5.2 recommends to keep the curvature streamlines. Neighbouring
passes are
spaced across the profile direction e1 from a requested scallop height with the exact circle model of
:mod:`spiralbevel.manufacturing.scallop`, using the profile curvature kappa1 (the normal curvature across the pass).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq

from .._core.rotations import rot_z
from ..conventions import Side
from ..errors import DesignError, DesignWarning, GeometryError, Problem
from ._flank import FlankLike, FlankParams, check_flank, outward_geometry
from .scallop import max_scallop, scallop_for_stepover, stepover_for_scallop

__all__ = ["CuttingPath", "ToolPath", "plan_toolpath"]

_N_OVERLAP = 257  # phi samples per pair of passes for the worst case along the pass
_OVERRUN_MARGIN = 1.25


@dataclass(frozen=True)
class CuttingPath:
    """One pass: the flank curve varphi = const, from toe to heel (or back with ``zigzag``).

    Attributes
    ----------
    varphi : float, rad
        Rolling angle of the pass.
    phi, psi : (k,) float, rad
        Spiral parameter and psi = (varphi - phi) sin(delta) of the points.
    surface : (k, 3) float, mm
        Contact points on the flank.
    normal : (k, 3) float
        Outward unit normals n_out.
    feed : (k, 3) float
        Unit tangent of the pass in the feed direction (parallel to e2).
    center : (k, 3) float, mm
        Ball centre, surface + R n_out (the cutter-location point).
    tip : (k, 3) float, mm
        Tool tip, center - R axis.
    axis : (k, 3) float
        Unit tool-axis vector, pointing from the tip toward the spindle.
    arc_length : (k,) float, mm
        Surface arc length from the first point of the pass, |rho - rho_first| / cos(beta).
    """

    varphi: float
    phi: np.ndarray
    psi: np.ndarray
    surface: np.ndarray
    normal: np.ndarray
    feed: np.ndarray
    center: np.ndarray
    tip: np.ndarray
    axis: np.ndarray
    arc_length: np.ndarray


@dataclass(frozen=True)
class ToolPath:
    """Ball-end tool path over a flank.

    Attributes
    ----------
    paths : tuple of CuttingPath
        Passes in the order they are cut (increasing varphi).
    tool_radius : float, mm
    scallop_height : float, mm
        Requested scallop height (the upper bound the stepover was chosen for).
    lead, tilt : float, rad
        Tool-axis angles from the normal (see :func:`plan_toolpath`).
    side : Side
        Flank machined.
    predicted_scallop : (n_paths - 1,) float, mm
        Largest scallop between pass i and i + 1 predicted by the circle model (<= scallop_height).
    overrun : (2,) float, rad
        How far the passes run beyond psi_min and psi_max (in psi).
    """

    paths: tuple
    tool_radius: float
    scallop_height: float
    lead: float
    tilt: float
    side: Side
    predicted_scallop: np.ndarray
    overrun: np.ndarray

    def __len__(self) -> int:
        return len(self.paths)

    @property
    def path_index(self) -> np.ndarray:
        """(N,) int: pass number of every point of :meth:`stacked` order."""
        return np.concatenate([np.full(len(p.phi), i) for i, p in enumerate(self.paths)])

    @property
    def point_index(self) -> np.ndarray:
        """(N,) int: index of every point within its pass."""
        return np.concatenate([np.arange(len(p.phi)) for p in self.paths])

    def rotated(self, angle: float) -> "ToolPath":
        """The same path turned by ``angle`` (rad) about the member axis +z (a flank placed in its member frame)."""
        R = rot_z(float(angle))
        vec = ("surface", "normal", "feed", "center", "tip", "axis")
        paths = tuple(replace(p, **{k: getattr(p, k) @ R.T for k in vec}) for p in self.paths)
        return replace(self, paths=paths)

    def stacked(self, name: str) -> np.ndarray:
        """All passes' ``name`` attribute (``"center"``, ``"tip"``, ``"axis"``, ...) concatenated, (N, ...)."""
        return np.concatenate([getattr(p, name) for p in self.paths])


def _check_positive(value, field, unit):
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = float("nan")
    if not (math.isfinite(v) and v > 0):
        raise DesignError.single(field, value, "0 < value < inf", unit)
    return v


def _check_angle(value, field):
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = float("nan")
    if not (math.isfinite(v) and abs(v) < math.radians(60)):
        raise DesignError.single(field, value, "|value| < pi/3", "rad")
    return v


def _kappa1(psi, rho, beta):
    """Profile curvature, convex positive: cos(psi - beta) / (rho |sin psi|) (docs/theory/logspiral.md, Eq. (S9)
    (#flank-types) k1 with n_out)."""
    return np.cos(psi - beta) / (rho * np.abs(np.sin(psi)))


def _rho(phi, p: FlankParams):
    return p.rho0 * np.exp(phi * math.sin(p.delta) / math.tan(p.beta))


def _gouge_check(p: FlankParams, psi_lo, psi_hi, domain, R):
    """Ball radius against the most concave normal curvature of the machined region."""
    psi = np.array([psi_lo, psi_hi])[None, :]
    phi = np.array([domain.phi_min, domain.phi_max])[:, None]
    rho = _rho(phi, p)
    k1 = _kappa1(psi, rho, p.beta)
    k2 = p.psi_sign * math.sin(p.beta) / rho * np.ones_like(k1)
    kmin = float(min(k1.min(), k2.min()))  # both are monotone: the extremes sit at the corners
    if kmin < 0 and R * -kmin >= 1.0:
        raise GeometryError.single(
            "tool_radius", R, f"< {1.0 / -kmin:.6g}", "mm",
            f"a ball larger than the smallest concave radius of curvature 1/|kappa| = {1.0 / -kmin:.6g} mm of the "
            f"{p.side.value} flank gouges it")


def _scallop_limit_check(p: FlankParams, psi_lo, psi_hi, domain, R, h):
    """h must stay below the largest scallop two balls can leave at the most convex profile curvature."""
    psi_near = psi_lo if p.psi_sign > 0 else psi_hi
    rho = _rho(np.array([domain.phi_min, domain.phi_max]), p)
    hmax = float(np.min(max_scallop(R, _kappa1(psi_near, rho, p.beta))))
    if h >= hmax:
        raise DesignError.single("scallop_height", h, f"< {hmax:.6g}", "mm",
                                 "two neighbouring balls cannot leave a larger scallop on the most convex part")


_SAMPLE_NUMBERS = np.arange(_N_OVERLAP, dtype=float)


def _samples(lo: float, hi: float) -> np.ndarray:
    """``np.linspace(lo, hi, _N_OVERLAP)`` by the same arithmetic (sample number times step, plus lo; the last sample
    hi), the same floats without linspace's argument handling: the march asks for it about 500 times per flank."""
    step = (hi - lo) / (_N_OVERLAP - 1)
    if step == 0.0:  # equal or denormally close ends: linspace's own special case
        return np.linspace(lo, hi, _N_OVERLAP)
    ph = _SAMPLE_NUMBERS * step
    ph += lo
    ph[-1] = hi
    return ph


def _pair_strip(phi_a, dvarphi, p, psi_lo, psi_hi, domain):
    """Surface arc between passes varphi_a and varphi_a + dvarphi, and the most convex kappa1 of the strip between
    them, at _N_OVERLAP samples of the phi range both passes share; None if they share none."""
    s = math.sin(p.delta)
    lo = max(domain.phi_min, phi_a + dvarphi - psi_hi / s)
    hi = min(domain.phi_max, phi_a - psi_lo / s)
    # at the corners of the parallelogram the shared range is a single point; phi_a - psi_lo/s may round to just
    # below phi_min there, so compare with a tolerance of round-off size
    if hi < lo - 1e-12 * max(1.0, abs(lo)):
        return None
    hi = max(hi, lo)
    ph = _samples(lo, hi)
    psi_a = (phi_a - ph) * s
    psi_b = psi_a + dvarphi * s
    rho = _rho(ph, p)
    arc = rho * math.cos(p.delta) / s * np.abs(np.cos(psi_a) - np.cos(psi_b))
    # kappa1 falls monotonically with |psi| (d/dpsi [cos(psi-beta)/sin psi] = -cos(beta)/sin^2 psi): the worst
    # (most convex) curvature of the strip is at its end nearer the singular edge.
    psi_near = np.where(np.abs(psi_a) < np.abs(psi_b), psi_a, psi_b)
    return arc, _kappa1(psi_near, rho, p.beta)


def _pair_ratio(phi_a, dvarphi, p, psi_lo, psi_hi, domain, R, h):
    """max over the shared phi range of (surface arc between passes) / (allowed stepover)."""
    strip = _pair_strip(phi_a, dvarphi, p, psi_lo, psi_hi, domain)
    if strip is None:
        return math.inf
    arc, kappa = strip
    return float(np.max(arc / stepover_for_scallop(R, h, kappa)))


def _memo(f):
    """``f`` that evaluates each argument once: the march asks for the ratio at the bracket's end twice before
    ``brentq``, which asks for both ends again (about a quarter of the evaluations of a plan, the same numbers)."""
    seen: dict = {}

    def g(x):
        if x not in seen:
            seen[x] = f(x)
        return seen[x]

    return g


def _march(p, psi_lo, psi_hi, domain, R, h, max_paths):
    """varphi of the passes from the first to the last corner of the (extended) parallelogram."""
    s = math.sin(p.delta)
    start = domain.phi_min + psi_lo / s
    end = domain.phi_max + psi_hi / s
    out = [start]
    guess = 0.01 * (psi_hi - psi_lo) / s
    while out[-1] < end:
        a = out[-1]
        f = _memo(lambda d, a=a: _pair_ratio(a, d, p, psi_lo, psi_hi, domain, R, h) - 1.0)
        rest = end - a
        if rest <= 1e-12 * (end - start):  # the last pass is (numerically) the end corner
            out[-1] = end
            break
        hi = min(guess, rest)
        while f(hi) < 0 and hi < rest:
            hi = min(2.0 * hi, rest)
        if f(hi) <= 0:
            out.append(end)
            break
        lo = 0.0
        if f(lo) >= 0:  # pragma: no cover - cannot happen for h > 0
            raise GeometryError.single("scallop_height", h, "> 0", "mm", "no stepover meets it")
        d = brentq(f, lo, hi, xtol=1e-14, rtol=1e-12)
        out.append(a + d)
        guess = 2.0 * d
        if len(out) > max_paths:
            raise DesignError.single("scallop_height", h, "a larger value", "mm",
                                     f"more than max_paths = {max_paths} passes would be needed")
    return np.array(out)


def _overrun(p, domain, R, h):
    """psi distances to run past psi_min / psi_max: 1.25 x the psi width of one stepover at each edge."""
    s, c = math.sin(p.delta), math.cos(p.delta)
    rho = _rho(np.array([domain.phi_min, domain.phi_max]), p)
    res = []
    for edge in (domain.psi_min, domain.psi_max):
        w = stepover_for_scallop(R, h, _kappa1(edge, rho, p.beta))
        res.append(_OVERRUN_MARGIN * float(np.max(w * s / (rho * c * abs(math.sin(edge))))))
    o_lo, o_hi = res
    inner = min(abs(domain.psi_min), abs(domain.psi_max))
    if p.psi_sign > 0 and o_lo > 0.5 * inner:
        o_lo = 0.5 * inner
        warnings.warn(f"overrun below psi_min clamped to {o_lo:.4g} rad to stay off the singular edge psi = 0; "
                      "the strip along that edge may keep a higher scallop", DesignWarning, stacklevel=3)
    if p.psi_sign < 0 and o_hi > 0.5 * inner:
        o_hi = 0.5 * inner
        warnings.warn(f"overrun above psi_max clamped to {o_hi:.4g} rad to stay off the singular edge psi = 0; "
                      "the strip along that edge may keep a higher scallop", DesignWarning, stacklevel=3)
    return np.array([o_lo, o_hi])


def _axis(n, t, lead, tilt):
    """Tool axis: n turned by ``lead`` toward the feed t, then by ``tilt`` toward b = n x t."""
    b = np.cross(n, t)
    return math.cos(tilt) * (math.cos(lead) * n + math.sin(lead) * t) + math.sin(tilt) * b


def _make_path(vphi, p, psi_lo, psi_hi, domain, R, lead, tilt, max_segment, reverse):
    s = math.sin(p.delta)
    ph0 = max(domain.phi_min, vphi - psi_hi / s)
    ph1 = min(domain.phi_max, vphi - psi_lo / s)
    rho0, rho1 = _rho(ph0, p), _rho(ph1, p)
    length = abs(rho1 - rho0) / abs(math.cos(p.beta))
    if length <= 1e-9 * p.rho0:
        return None
    k = max(2, int(math.ceil(length / max_segment)) + 1)
    rho = np.linspace(rho0, rho1, k)  # uniform surface arc length: ds = |d rho| / cos(beta) on a log spiral
    phi = np.log(rho / p.rho0) / (s / math.tan(p.beta))
    phi[0], phi[-1] = ph0, ph1
    if reverse:
        phi, rho = phi[::-1], rho[::-1]
    g = outward_geometry(np.full_like(phi, vphi), phi, p)
    feed = g["r_phi"] / np.linalg.norm(g["r_phi"], axis=-1, keepdims=True)
    if reverse:
        feed = -feed
    n = g["n_out"]
    axis = _axis(n, feed, lead, tilt)
    center = g["r"] + R * n
    return CuttingPath(
        varphi=float(vphi), phi=phi, psi=g["psi"], surface=g["r"], normal=n, feed=feed, center=center,
        tip=center - R * axis, axis=axis, arc_length=np.abs(rho - rho[0]) / abs(math.cos(p.beta)),
    )


def plan_toolpath(flank: FlankLike, domain, tool_radius: float, scallop_height: float, *, lead: float = 0.0,
                  tilt: float = 0.0, max_segment: float = 1.0, overrun: bool = True, zigzag: bool = False,
                  max_paths: int = 20000) -> ToolPath:
    """Ball-end passes along the lengthwise lines of curvature with a guaranteed scallop height.

    Parameters
    ----------
    flank : FlankLike
        ``rho0`` (float, mm), ``base_cone_angle`` (float, rad), ``spiral_angle`` (float, rad).
    domain : ParallelogramDomain
        Flank domain; its sign of psi selects the convex or concave branch.
    tool_radius : float, mm
        Ball radius R > 0; on a concave flank R < 1/|kappa| of the most concave curvature, else GeometryError.
    scallop_height : float, mm
        Largest scallop height allowed, 0 < h < R.
    lead, tilt : float, rad
        Tool-axis strategy: the axis is the outward normal turned by ``lead`` toward the feed direction, then by
        ``tilt`` sideways toward n_out x feed; |lead|, |tilt| < pi/3. (0, 0) gives the normal itself. With a ball
        end the axis changes neither the cut surface nor the ball centre, only the tip point and the reach.
    max_segment : float, mm
        Largest surface arc between consecutive points of a pass.
    overrun : bool
        Run the passes past the root and top edges (psi_min, psi_max) by 1.25 stepover widths along the analytic
        continuation of the flank, so the strips along those edges also meet the scallop height. Off: passes end
        on the edges and the edge strips can keep up to about 4x the scallop height.
    zigzag : bool
        Reverse every other pass (heel to toe) instead of cutting all passes toe to heel.
    max_paths : int
        Refuse plans with more passes than this (DesignError).

    Returns
    -------
    ToolPath

    Notes
    -----
    Passes: varphi = const curves, ds = |d rho| / cos(beta). Between passes varphi_a and varphi_b, for every shared
    phi the surface arc across is rho cos(delta)/sin(delta) |cos psi_a - cos psi_b| (integral of |r_varphi|,
    docs/theory/logspiral.md, Eqs. (S3)-(S8) E). The next pass is the farthest one for which that arc stays below the
    exact stepover of
    :func:`~spiralbevel.manufacturing.scallop.stepover_for_scallop` for the most convex profile curvature kappa1 of
    the strip, at every one of 257 phi samples (brentq on varphi). The lengthwise curvature kappa2 enters only the
    gouge check. Global interference with the neighbouring tooth is not checked.
    """
    p = check_flank(flank, domain)
    R = _check_positive(tool_radius, "tool_radius", "mm")
    h = _check_positive(scallop_height, "scallop_height", "mm")
    if h >= R:
        raise DesignError.single("scallop_height", scallop_height, f"0 < value < tool_radius = {R:g}", "mm")
    lead, tilt = _check_angle(lead, "lead"), _check_angle(tilt, "tilt")
    max_segment = _check_positive(max_segment, "max_segment", "mm")
    if isinstance(max_paths, bool) or not isinstance(max_paths, (int, np.integer)) or max_paths < 2:
        raise DesignError([Problem("max_paths", max_paths, "an integer >= 2", "-")])
    o = _overrun(p, domain, R, h) if overrun else np.zeros(2)
    psi_lo, psi_hi = domain.psi_min - o[0], domain.psi_max + o[1]
    _gouge_check(p, psi_lo, psi_hi, domain, R)
    _scallop_limit_check(p, psi_lo, psi_hi, domain, R, h)
    varphis = _march(p, psi_lo, psi_hi, domain, R, h, int(max_paths))
    paths: list = []
    kept: list = []
    for vphi in varphis:
        path = _make_path(vphi, p, psi_lo, psi_hi, domain, R, lead, tilt, max_segment, zigzag and len(paths) % 2)
        if path is not None:
            paths.append(path)
            kept.append(vphi)
    pred = []
    for a, b in zip(kept[:-1], kept[1:]):
        arc, kappa = _pair_strip(a, b - a, p, psi_lo, psi_hi, domain)
        pred.append(float(np.max(scallop_for_stepover(R, arc, kappa))))
    return ToolPath(paths=tuple(paths), tool_radius=R, scallop_height=h, lead=lead, tilt=tilt, side=p.side,
                    predicted_scallop=np.array(pred), overrun=o)



def follow_lines_of_curvature(surface, planned: ToolPath, *, step: float = 2e-3) -> ToolPath:
    """The passes of ``planned`` re-traced along the lengthwise lines of curvature of a modified flank.

    Parameters
    ----------
    surface : ContactSurface
        The modified flank (e.g. crowned and forging-relieved), ``evaluate(params (..., 2)) -> (points, normals)``
        in the same parameters (varphi, phi) as the flank of ``planned`` and in the frame the result is wanted in.
    planned : ToolPath
        Passes of the theoretical flank (:func:`plan_toolpath`): their start points, phi samples and spacing are kept.
    step : float, rad
        Parameter step of the generic differential geometry (:func:`spiralbevel.geometry.diffgeom.surface_geometry`).

    Returns
    -------
    ToolPath
        Same passes, re-traced: each starts at the theoretical pass's first point and follows the principal
        direction of the modified flank that is closer to r_phi, integrated over phi with the classical Runge-Kutta
        scheme on the phi samples of the pass. ``predicted_scallop`` is that of the theoretical flank (the
        modifications change the stepover by a relative amount of the order of their slope).

    Notes
    -----
    On the theoretical flank the lengthwise lines of curvature are the curves varphi = const (F = M = 0, seed 000
    §5.2), which is what the re-tracing reproduces there. On a modified flank the principal direction field is that
    of the generic differential geometry (Richardson-extrapolated derivatives of the points).
    """
    from ..geometry.diffgeom import surface_geometry

    def point(u, v):
        return surface.evaluate(np.stack(np.broadcast_arrays(u, v), -1))[0]

    def slope(u, v):
        """d varphi / d phi of the lengthwise principal direction at (u, v)."""
        n = surface.evaluate(np.stack([u, v], -1))[1]
        g = surface_geometry(point, u, v, reference=n, step=step)
        A = np.stack([g.r_u, g.r_v], -1)
        x = np.linalg.lstsq(A[0], g.e2[0], rcond=None)[0] if A.ndim == 2 else None
        if x is None:
            x = np.einsum("mij,mj->mi", np.linalg.pinv(A), g.e2)
            return x[:, 0] / x[:, 1]
        return x[0] / x[1]

    paths = []
    for p in planned.paths:
        phi = np.asarray(p.phi, float)
        vphi = np.empty_like(phi)
        vphi[0] = p.varphi
        for i in range(len(phi) - 1):
            h = phi[i + 1] - phi[i]
            u, v = np.array([vphi[i]]), np.array([phi[i]])
            k1 = slope(u, v)
            k2 = slope(u + 0.5 * h * k1, v + 0.5 * h)
            k3 = slope(u + 0.5 * h * k2, v + 0.5 * h)
            k4 = slope(u + h * k3, v + h)
            vphi[i + 1] = vphi[i] + h * (k1 + 2 * k2 + 2 * k3 + k4)[0] / 6.0
        r, n = surface.evaluate(np.stack([vphi, phi], -1))
        t = np.gradient(r, axis=0)
        t /= np.linalg.norm(t, axis=-1, keepdims=True)
        axis = _axis(n, t, planned.lead, planned.tilt)
        center = r + planned.tool_radius * n
        arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(r, axis=0), axis=-1))])
        paths.append(CuttingPath(varphi=float(p.varphi), phi=phi, psi=p.psi, surface=r, normal=n, feed=t,
                                 center=center, tip=center - planned.tool_radius * axis, axis=axis, arc_length=arc))
    return replace(planned, paths=tuple(paths))
