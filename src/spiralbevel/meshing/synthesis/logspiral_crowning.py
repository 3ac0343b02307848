"""A mismatched log-spiral pair by local synthesis: pinion crowning from targets at the mean point.

The exactly conjugate log-spiral pair (seed 000; seed 002 theorem) is in line contact, with zero transmission error,
and is therefore sensitive to misalignment (seed 000, conclusions). Here the pinion flank is crowned by a quadratic
displacement along its outward normal in its own parameters (varphi, phi),

    w = -(c00 dvarphi^2 + 2 c01 dvarphi dphi + c11 dphi^2),     (dvarphi, dphi) from the mean point,

and the three coefficients are chosen from the engineer's three targets at the mean point, in the spirit of Litvin's
local synthesis: the direction eta of the contact path on the pinion flank, the semi-major axis a of the contact
ellipse for an elastic approach, and the level of a parabolic transmission error over one mesh cycle.

**Why crowning and not a base-cone or spiral mismatch.** A base-cone mismatch and a spiral mismatch are two scalars;
they change the flank everywhere (its profile and lengthwise shape over the whole face) and couple the three targets
non-linearly, so three targets cannot be met independently. A quadratic crowning has exactly three coefficients, each
target fixes one combination of them in closed form, and the gear stays the exact conjugate flank (its tooling is
unchanged); it is also what a forged or 5-axis-milled flank can carry directly, since neither process is tied to a
generating machine.

**Closed form (the synthesis).** For the conjugate pair the instantaneous contact line is the curve varphi = const of
the pinion (the planar log spiral in the plane of action), and it moves by d varphi = -d phi1 when the pinion turns
(the rolling plane is fixed in space). On the line varphi = varphi_m + D the crowned pinion touches the gear where w is
largest: dphi* = -(c01 / c11) D and w* = -(c00 - c01^2 / c11) D^2. Hence

* path direction: the path tangent is r_varphi + q r_phi with q = -c01 / c11, and tan(eta) = q (r_phi . t_l) /
  (r_varphi . t_p) with t_p (root to top) and t_l (toe to heel) of :func:`~.mean_contact.path_reference`;
* TE: the gear lags by |w*| / l2 (l2 the gear's moment arm of the normal), so the parabolic TE reaches
  TE_level = (c00 - c01^2 / c11) (pi / z1)^2 / l2 at the ends of the cycle;
* ellipse: the relative curvature tensor (t_p, t_l basis) is K = diag(k1_1 + k1_2, k2_1 + k2_2) + 2 [[c00 / A^2,
  c01 / (A B)], [c01 / (A B), c11 / B^2]], with A = r_varphi . t_p, B = r_phi . t_l and k the principal curvatures of
  pinion and gear (convex positive; the lengthwise sum vanishes for the conjugate pair). The semi-major axis is
  a = sqrt(2 approach / lambda_min(K)); lambda_min grows monotonically with c11, which is found by root bracketing.

The TCA of the crowned pair checks all three independently (tests/meshing/test_logspiral_crowning.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ...conventions import Member, Side
from ...errors import DesignError, Problem
from ..contact_surface import NormalDeviation, quadratic_crowning
from ..tca_surfaces import LogSpiralSurface
from .mean_contact import path_reference

__all__ = ["LogSpiralCrowning", "design_logspiral_crowning", "logspiral_contact_surface", "crowned_contact_surface",
           "SumDeviation"]


@dataclass(frozen=True)
class LogSpiralCrowning:
    """Crowning of the pinion flank of a log-spiral pair (see the module docstring).

    Attributes
    ----------
    side : Side
        Pinion flank crowned (the gear flank of the other side meets it).
    center : (2,) float, rad
        (varphi, phi) of the pinion mean point: the untouched point.
    coeffs : (3,) float, mm/rad^2
        (c00, c01, c11) of w = -(c00 dvarphi^2 + 2 c01 dvarphi dphi + c11 dphi^2).
    path_direction, semi_major_axis, te_level, approach : float
        The targets: eta (rad), a (mm), TE at the cycle ends (rad of gear rotation), elastic approach (mm).
    relative_curvatures : (2,) float, 1/mm
        Eigenvalues of K at the mean point, ascending.
    gear_lever : float, mm
        l2, the gear's moment arm of the contact normal at the mean point.
    """

    side: Side
    center: np.ndarray
    coeffs: np.ndarray
    path_direction: float
    semi_major_axis: float
    te_level: float
    approach: float
    relative_curvatures: np.ndarray
    gear_lever: float

    def deviation(self):
        """``deviation(params) -> (w, grad)`` for :class:`~spiralbevel.meshing.contact_surface.NormalDeviation`."""
        return quadratic_crowning(self.center, self.coeffs)

    def predicted_semi_axes(self) -> np.ndarray:
        """(major, minor) semi-axes in mm of the contact ellipse at the mean point, from K."""
        return np.sqrt(2.0 * self.approach / self.relative_curvatures)


def _check_targets(semi_major_axis, path_direction, te_level, approach):
    problems = []

    def real(x):
        return isinstance(x, (int, float, np.floating)) and not isinstance(x, bool) and math.isfinite(x)

    if not (real(semi_major_axis) and 0.0 < semi_major_axis <= 50.0):
        problems.append(Problem("semi_major_axis", semi_major_axis, "0 < value <= 50", "mm"))
    if not (real(path_direction) and abs(path_direction) < 0.5 * math.pi):
        problems.append(Problem("path_direction", path_direction, "-pi/2 < value < pi/2", "rad"))
    if not (real(te_level) and 0.0 < te_level < 0.01):
        problems.append(Problem("te_level", te_level, "0 < value < 0.01", "rad"))
    if not (real(approach) and 0.0 < approach <= 0.1):
        problems.append(Problem("approach", approach, "0 < value <= 0.1", "mm"))
    if problems:
        raise DesignError(problems)


def logspiral_contact_surface(pair, member: Member, side: Side) -> LogSpiralSurface:
    """The placed flank of a designed log-spiral pair as a TCA contact surface, parameters (varphi, phi) in rad."""
    f = pair.flank(member, side)
    d = f.domain
    return LogSpiralSurface(rho0=f.surface.rho0, delta=f.surface.base_cone_angle, beta=f.surface.spiral_angle,
                            azimuth=f.rotation, psi_range=(d.psi_min, d.psi_max), phi_range=(d.phi_min, d.phi_max),
                            reference_params=tuple(pair.mean_parameters(member, side)))


def design_logspiral_crowning(pair, side: Side = Side.CONVEX, *, semi_major_axis: float, path_direction: float,
                              te_level: float, approach: float = 0.00635) -> LogSpiralCrowning:
    """Crowning coefficients of the pinion flank that meet the three mean-point targets.

    Parameters
    ----------
    pair : LogSpiralPair
        A designed conjugate pair (:func:`~spiralbevel.design.logspiral_pair.design_logspiral_pair`).
    side : Side
        Pinion flank to crown; it meshes with the gear flank ``side.mate``.
    semi_major_axis : float, mm
        Target semi-major axis a of the contact ellipse at the mean point.
    path_direction : float, rad
        Target eta of the contact path on the pinion flank: the path tangent is cos(eta) t_p + sin(eta) t_l, t_p from
        root to top, t_l from toe to heel (positive eta leans the path toward the heel as it climbs the profile).
    te_level : float, rad
        Target |TE| of gear rotation at the ends of the cycle phi1 - phi1_mean = +-pi/z1 (parabolic TE, 0 at the mean
        point).
    approach : float, mm
        Elastic approach of the ellipse (0.00635 mm, the usual marking-compound value).

    Returns
    -------
    LogSpiralCrowning

    Raises
    ------
    DesignError
        Targets out of range, or an ellipse that no crowning with this TE level and path can give (the major axis
        asked for is shorter than the one of the relieved profile direction alone).
    """
    _check_targets(semi_major_axis, path_direction, te_level, approach)
    side = Side(side)
    q1 = np.array(pair.mean_parameters(Member.PINION, side))
    g1 = pair.mean_point(Member.PINION, side)
    g2 = pair.mean_point(Member.GEAR, side.mate)
    surf = pair.flank(Member.PINION, side).surface
    geo = surf.evaluate(*q1)  # unrotated: the tangents only need the pinion's own frame
    r_a = geo.e1 * math.sqrt(float(geo.E))  # r_varphi = |r_varphi| e1 (FlankGeometry: e1 = r_varphi / |r_varphi|)
    r_b = math.copysign(math.sqrt(float(geo.G)), surf.spiral_angle) * geo.e2  # r_phi; e2 points toe -> heel
    t_p, t_l = path_reference(geo.point, geo.normal, (0.0, 0.0, 1.0), pair.pinion.pitch_angle)
    A, B = float(r_a @ t_p), float(r_b @ t_l)
    q = math.tan(path_direction) * A / B
    # gear moment arm of the normal at the mean point (gear member frame: axis +z)
    lever = abs(float(np.cross([0.0, 0.0, 1.0], g2.point) @ g2.normal))
    z1 = pair.pinion.teeth
    D = te_level * lever / (math.pi / z1) ** 2
    k_across = float(g1.k1 + g2.k1)
    k_along = float(g1.k2 + g2.k2)
    lam_target = 2.0 * approach / semi_major_axis**2

    def K(c11):
        c01 = -q * c11
        c00 = D + q * q * c11
        return np.array([[k_across + 2 * c00 / A**2, 2 * c01 / (A * B)],
                         [2 * c01 / (A * B), k_along + 2 * c11 / B**2]])

    def f(c11):
        return float(np.linalg.eigvalsh(K(c11))[0]) - lam_target

    hi = 1.0
    while f(hi) < 0:
        hi *= 4.0
        if hi > 1e12:
            raise DesignError.single(
                "semi_major_axis", semi_major_axis, f"> {math.sqrt(2 * approach / (f(hi) + lam_target)):.4g}", "mm",
                "no lengthwise crowning reaches so short an ellipse with this path direction and TE level")
    lo = 0.0
    if f(lo) > 0:
        raise DesignError.single("semi_major_axis", semi_major_axis, "a longer ellipse", "mm",
                                 "the conjugate pair's relative curvature already gives a shorter one")
    c11 = brentq(f, lo, hi, xtol=1e-14 * hi, rtol=1e-13)
    c01 = -q * c11
    c00 = D + q * q * c11
    lam = np.linalg.eigvalsh(K(c11))
    return LogSpiralCrowning(side, q1, np.array([c00, c01, c11]), float(path_direction), float(semi_major_axis),
                             float(te_level), float(approach), lam, lever)


class SumDeviation:
    """Sum of deviation functions for :class:`~spiralbevel.meshing.contact_surface.NormalDeviation`.

    Parameters
    ----------
    *parts : callable
        Each ``params (..., 2) -> (w (...) mm, grad (..., 2) mm/rad)``.
    """

    def __init__(self, *parts):
        self.parts = parts

    @property
    def quadratic(self):
        """``(centre, coefficients)`` when the sum is one
        :func:`~spiralbevel.meshing.contact_surface.quadratic_crowning` (0 + w is w: the same values), else None;
        read by ``NormalDeviation.jet`` for the compiled crowned flank."""
        return getattr(self.parts[0], "quadratic", None) if len(self.parts) == 1 else None

    def __call__(self, params):
        w, g = 0.0, 0.0
        for p in self.parts:
            a, b = p(params)
            w, g = w + np.asarray(a, float), g + np.asarray(b, float)
        return w, g


def crowned_contact_surface(pair, crowning: LogSpiralCrowning | None, relief=None,
                            side: Side = Side.CONVEX) -> object:
    """The pinion flank of ``crowning.side`` as a TCA contact surface, crowned and optionally forging-relieved.

    Parameters
    ----------
    pair : LogSpiralPair
    crowning : LogSpiralCrowning or None
        None: no crowning (a relieved conjugate flank).
    relief : callable, optional
        A further deviation ``params -> (w, grad)`` in the same parameters (for example the forging relief,
        :meth:`spiralbevel.manufacturing.forging.ForgingRelief.contact_deviation`).
    side : Side
        Pinion flank when ``crowning`` is None.

    Returns
    -------
    ContactSurface
        The base :class:`LogSpiralSurface` when neither is given, else a
        :class:`~spiralbevel.meshing.contact_surface.NormalDeviation` of it.
    """
    side = crowning.side if crowning is not None else Side(side)
    base = logspiral_contact_surface(pair, Member.PINION, side)
    parts = [p for p in ((crowning.deviation() if crowning is not None else None), relief) if p is not None]
    if not parts:
        return base
    return NormalDeviation(base, SumDeviation(*parts))
