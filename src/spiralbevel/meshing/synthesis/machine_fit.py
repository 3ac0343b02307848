"""Pinion machine settings that generate prescribed first- and second-order geometry at one point.

The generated pinion point at the cradle angle psi_c = 0 (a gauge: the cradle angle q then places the cutter) is
evaluated by the compiled residual of :mod:`spiralbevel._core.settings_fit`: point, outward normal and their
derivatives from the compiled first-order jet of the generated flank in the (phi, psi_c) chart, the curvature tensor
from them by Weingarten's relation (the same tensor as the curvature transfer of docs/theory/generation.md, Eqs.
(G13)-(G15) (#curvature-transfer), which the tests compare), and solved by a compiled Newton. Seven conditions, all
invariant under rotation about the pinion axis (the pinion's rotation phi10 in the pair is free): axial position and
radius of the point (2), axial and radial components of the unit normal (2), and the three components of the curvature
tensor in the tangent basis of :func:`~spiralbevel.meshing.synthesis._relations.tangent_components` (3). Unknowns: the
cutter angle theta of the point (its blade parameter u follows from the equation of meshing) and six machine/cutter
quantities named by ``free``; every other setting keeps its starting value.
"""

from __future__ import annotations

import dataclasses
import logging
import math

import numpy as np

from ..._core.continuation import arclength_continuation
from ..._core import blade_locate as _bl
from ..._core import generation_blade_jet as _bj
from ..._core import settings_fit as _sf
from ...conventions import TOL, Hand, Member
from ...errors import ConvergenceError, DesignError, GeometryError, SpiralBevelError
from ...generation import generate_flank
from ...generation.meshing import Generator
from ._relations import curvature_tensor, tangent_components

_log = logging.getLogger(__name__)

__all__ = ["FREE_DEFAULT", "FREE_OFFSET", "FREE_MODIFIED_ROLL", "FREE_FIXED_BLADE", "fit_settings", "point_invariants"]

FREE_OFFSET = ("point_radius", "blade_angle", "radial_setting", "cradle_angle", "ratio_of_roll", "blank_offset")
"""Default set, Litvin's choice without modified roll: cutter point radius and blade angle, S_r, q, m_1c and the blank
offset E_m1 are solved; gamma_m1 = pinion root angle, X_B1 = X_D1 = 0 (the root cone touches the cradle plane at the
machine centre, so the cutter tip generates the blank's root), no modified roll."""

FREE_MODIFIED_ROLL = ("point_radius", "blade_angle", "radial_setting", "cradle_angle", "ratio_of_roll",
                      "modified_roll")
"""As ``FREE_OFFSET`` with the modified roll 2C in place of the blank offset (E_m1 = 0)."""

FREE_FIXED_BLADE = ("point_radius", "radial_setting", "cradle_angle", "ratio_of_roll", "blank_offset",
                    "machine_centre_to_back")
"""The blade angle is kept at the starting cutter's (e.g. seed 001 Table 5: 21 deg 10'); E_m1 and X_D1 solved."""

FREE_DEFAULT = FREE_OFFSET

_CUTTER = ("point_radius", "blade_angle")
_SETTINGS = ("radial_setting", "cradle_angle", "machine_root_angle", "machine_centre_to_back", "sliding_base",
             "blank_offset", "ratio_of_roll", "modified_roll")
# damping of the Newton steps (mm, rad, -): far-off iterates would leave the flank
_MAX_STEP = dict(point_radius=5.0, blade_angle=0.02, radial_setting=5.0, cradle_angle=0.05, machine_root_angle=0.01,
                 machine_centre_to_back=1.0, sliding_base=1.0, blank_offset=5.0, ratio_of_roll=0.1, modified_roll=0.1)
_MAX_STEP_THETA = 0.05   # rad, the point's cutter angle
# a failed evaluation (no generated point) as a residual: large, finite, so that a step into it is shortened
_BAD = 1e6
# corrector tolerance along the continuation path, relative to the largest scaled residual of the start: the path
# only has to be followed, not solved to the end tolerance (which the evaluation noise of the curvatures, about
# 1e-7 in scaled units, would not always allow)
_PATH_TOL = 1e-6
# relative step of the central-difference Jacobian: about eps^(1/3), where truncation (h^2) and rounding (eps / h)
# errors balance
_REL_STEP = 6e-6
# the start's location on the target circle: Newton step caps (rad) in (phi, psi_c) and the cutter-angle window about
# the reference angle, as the flank's blade locator (generation/locate_blade.py)
_LOCATE_STEP = np.array([0.05, 0.05])
_LOCATE_PHI_SPAN = 0.75


def _value(cutter, settings, name):
    if name in _CUTTER:
        return float(getattr(cutter, name))
    if name == "modified_roll":
        return float(settings.modified_roll[0]) if settings.modified_roll else 0.0
    return float(getattr(settings, name))


def build(cutter, settings, names, values):
    """Cutter and settings with the named quantities replaced (``modified_roll`` means its 2C term)."""
    ck, sk = {}, {}
    for name, v in zip(names, values):
        if name in _CUTTER:
            ck[name] = float(v)
        elif name == "modified_roll":
            rest = tuple(settings.modified_roll[1:])
            sk[name] = (float(v),) + rest
        else:
            sk[name] = float(v)
    return dataclasses.replace(cutter, **ck), settings.replace(**sk)


def point_invariants(flank, u, psi_c=0.0):
    """Invariants (7,) and tangential normal component of a generated point (see ``tangent_components``).

    ``flank`` is a ``ToothFlank`` or its ``Generator`` (anything with ``evaluate(u, psi_c) -> FlankPoints``).
    """
    return _invariants(flank.evaluate(u, psi_c))


def _invariants(fp):
    K = curvature_tensor(np.array([fp.k1, fp.k2]), np.stack([fp.e1, fp.e2]))
    return tangent_components(fp.points, fp.normals, K)


def blade_point(generator, theta):
    """Generated point (``FlankPoints``) at the cradle angle psi_c = 0 and the cutter angle ``theta`` (rad, relative
    to the cutter's position, as ``FlankPoints.theta``), in the (phi, psi_c) chart; ``GeometryError`` where the blade
    does not generate a point there (the chart's singular set)."""
    fp = generator.evaluate_blade(float(theta) + np.pi - generator.mp["q"], 0.0)
    if not np.isfinite(fp.u):
        raise GeometryError.single("theta", float(theta), "a cutter angle at which the blade generates a point", "rad")
    return fp


def fit_settings(cutter0, settings0, blank, side, target, target_nt, free=FREE_DEFAULT, tol=1e-9, max_iter=40):
    """Solve for the ``free`` quantities and the cutter angle of the point.

    Parameters
    ----------
    cutter0 : HeadCutter
        Starting cutter (its blade must cut ``side``).
    settings0 : MachineSettings
        Starting settings; quantities not in ``free`` keep their values.
    blank : ISO 23509 blank.
    side : Side
        Pinion side.
    target : (7,) float
        Invariants to reach (mm, mm, -, -, 1/mm, 1/mm, 1/mm).
    target_nt : float
        Tangential normal component (only its sign is used, to reject the mirror branch).
    free : tuple of str
        Six names from ``point_radius, blade_angle, radial_setting, cradle_angle, machine_root_angle,
        machine_centre_to_back, sliding_base, blank_offset, ratio_of_roll, modified_roll``.

    Returns
    -------
    cutter, settings, u, info : HeadCutter, MachineSettings, float (mm), dict
        ``u`` is the blade parameter of the point; ``info``: ``theta`` (rad, its cutter angle at psi_c = 0, as
        ``FlankPoints.theta``), ``iterations``, ``residual`` and ``method`` (``"newton"`` or ``"arclength"``).

    Notes
    -----
    The seventh unknown is the point's cutter angle theta at psi_c = 0, its blade parameter u following from the
    equation of meshing (the (phi, psi_c) chart, ``Generator.evaluate_blade``). The (u, psi_c) chart would do at
    most spiral angles, but it folds inside the face at low ones (docs/conventions.md, "Fold of generation"): there
    the point of a given u at psi_c = 0 ceases to exist along the way to the target, which stalled the solve.

    The start's cutter angle is that of the flank point on the target circle (one compiled locator solve, else the
    flank's table locator). Newton's method (compiled, central-difference Jacobian, steps capped per unknown) from the
    start first; if it fails, pseudo-arclength continuation
    (:func:`~spiralbevel._core.continuation.arclength_continuation`) of the homotopy that moves the goal linearly
    from the start's own invariants to the target; it follows the solution curve through turning points, where a
    continuation in the goal alone stalls.

    Below the fillet junction the residual keeps the straight (or arc) blade extended, as the chart's blade
    parameter does: continuous for iterates that pass there; the solution itself lies on the blade.
    """
    free = tuple(free)
    known = _CUTTER + _SETTINGS
    if len(free) != 6 or len(set(free)) != 6 or any(f not in known for f in free):
        raise DesignError.single("free", free, f"six distinct names from {known}", "-",
                                 "seven conditions fix six machine quantities and the cutter angle of the point")
    scale = float(blank.Rm)
    w = np.array([1.0, 1.0, scale, scale, scale**2, scale**2, scale**2])
    target = np.asarray(target, float)
    flank0 = generate_flank(cutter0, settings0, blank, Member.PINION, side)
    hand = flank0.hand
    # start: the cutter angle of the flank point on the target circle (the cutter of the basic settings passes near
    # it), else the blade junction's at psi_c = 0
    theta0 = _start_on_circle(flank0.generator, target[0], target[1])
    if theta0 is None:
        try:
            theta0 = float(flank0.locate(target[0], target[1], curvature=False).theta)
        except SpiralBevelError:
            theta0 = float(flank0.evaluate(flank0.generator.cp["u_j"], 0.0, curvature=False).theta)
    x0 = np.array([_value(cutter0, settings0, f) for f in free] + [theta0])
    kin = _kernel_inputs(cutter0, settings0, hand, free)

    def residual(x, goal):
        f = np.empty(7)
        _sf.residual(*kin, np.asarray(x, float), np.asarray(goal, float), w, f)
        return f

    step = np.array([_MAX_STEP[f] for f in free] + [_MAX_STEP_THETA])
    x, ok, iterations, resid = _sf.newton(*kin, x0, target, w, step, tol, max_iter, _REL_STEP)
    ok, iterations, resid, method = bool(ok), int(iterations), float(resid), "newton"
    if not ok:
        inv0 = np.empty(7)
        if _sf.invariants(*kin, x0, inv0)[0]:
            arc = arclength_continuation(lambda x, t: residual(x, inv0 + t * (target - inv0)), x0, step, tol=tol,
                                         path_tol=_PATH_TOL * max(1.0, float(np.max(np.abs((target - inv0) * w)))))
            _log.debug("arclength continuation: reached t = %.4f in %d steps, %d turning points, converged %s",
                       arc.t, arc.steps, arc.turning_points, arc.converged)
            if arc.converged:
                x, ok, iterations, resid, method = arc.x, True, arc.steps, arc.residual, "arclength"
            else:
                resid = float(arc.residual)
    if not ok:
        raise ConvergenceError(f"pinion machine settings: Newton did not reach the synthesized geometry "
                               f"(free = {free}; scaled residual {resid:.3g})",
                               iterations=iterations, residual=resid, last=x)
    cutter, settings = build(cutter0, settings0, free, x[:6])
    _, nt, u = _sf.invariants(*kin, x, np.empty(7))
    if np.sign(nt) != np.sign(target_nt):
        raise ConvergenceError("pinion machine settings: Newton reached the mirror branch of the normal",
                               iterations=iterations, residual=resid, last=x)
    return cutter, settings, float(u), dict(theta=float(x[6]), iterations=iterations, residual=resid,
                                            method=method)


def _start_on_circle(gen, axial, radius):
    """Cutter angle theta (rad, as ``FlankPoints.theta``) of the blade point on the circle (axial, radius) mm, by
    the compiled Newton of the flank locator (``_core.blade_locate``) from the reference angle at psi_c = 0 (where
    the cutter circle crosses the root line: the middle of the locator's start table); None where that single start
    does not reach a blade point inside the locator's window (the caller then locates with the whole table)."""
    psi_ref = 0.0
    phi_ref = float(gen.reference_angle(psi_ref))
    prm = _bj.parameters(gen.cp, gen.mp, False, 0.0)
    x, u, conv, _ = _bl.locate_axial_radius(prm, np.array([[phi_ref, psi_ref]]), np.array([float(axial)]),
                                            np.array([float(radius)]), TOL.newton_abs * 10, TOL.max_iter,
                                            _LOCATE_STEP)
    phi, psi, u = float(x[0, 0]), float(x[0, 1]), float(u[0])
    if not (conv[0] and u >= gen.cp["u_j"] - 1e-9):
        return None
    d = math.remainder(phi - float(gen.reference_angle(psi)), 2.0 * math.pi)
    if abs(d) > _LOCATE_PHI_SPAN:
        return None
    return phi - (math.pi - gen.mp["q"] + psi)


def _kernel_inputs(cutter0, settings0, hand, free):
    """(prm0, cut, codes) of the compiled residual (``_core.settings_fit``) around the starting cutter and settings
    (a free modified roll gets a first roll coefficient to solve, 0 = none)."""
    if "modified_roll" in free and not settings0.modified_roll:
        settings0 = settings0.replace(modified_roll=(0.0,))
    g = Generator(cutter0, settings0, hand)
    prm0 = _bj.parameters(g.cp, g.mp, g.hand is Hand.RIGHT, 0.0)
    cut = np.array([g.cp["s"], g.cp["rho_f"], g.cp["rp"], g.cp["up"], float(cutter0.point_width)])
    codes = np.array([_sf.CODES[f] for f in free], np.int64)
    return prm0, cut, codes
