"""Pinion machine settings that generate prescribed first- and second-order geometry at one point.

The generated pinion flank (``spiralbevel.generation``) is a black box (u, psi_c) -> point, outward normal, principal
curvatures (curvature transfer, docs/theory/generation.md, Eqs. (G13)-(G15) (#curvature-transfer)). The mean point is
generated at the cradle angle psi_c = 0 (a gauge: the
cradle angle q then places the cutter). Seven conditions, all invariant under rotation about the pinion axis (the
pinion's rotation phi10 in the pair is free): axial position and radius of the point (2), axial and radial components
of the unit normal (2), and the three components of the curvature tensor in the tangent basis of
:func:`~spiralbevel.meshing.synthesis._relations.tangent_components` (3). Unknowns: the blade parameter u of the point
and six machine/cutter quantities named by ``free``; every other setting keeps its starting value.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..._core.newton import solve_batched
from ...conventions import Member
from ...errors import ConvergenceError, DesignError, SpiralBevelError
from ...generation import generate_flank
from ...generation.meshing import Generator
from ._relations import curvature_tensor, tangent_components

import logging

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
    fp = flank.evaluate(u, psi_c)
    K = curvature_tensor(np.array([fp.k1, fp.k2]), np.stack([fp.e1, fp.e2]))
    return tangent_components(fp.points, fp.normals, K)


def fit_settings(cutter0, settings0, blank, side, target, target_nt, free=FREE_DEFAULT, tol=1e-9, max_iter=40):
    """Solve for the ``free`` quantities and the blade parameter u.

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
    cutter, settings, u, info : HeadCutter, MachineSettings, float (mm), dict (iterations, residual)
    """
    free = tuple(free)
    known = _CUTTER + _SETTINGS
    if len(free) != 6 or len(set(free)) != 6 or any(f not in known for f in free):
        raise DesignError.single("free", free, f"six distinct names from {known}", "-",
                                 "seven conditions fix six machine quantities and the blade parameter u")
    scale = float(blank.Rm)
    w = np.array([1.0, 1.0, scale, scale, scale**2, scale**2, scale**2])
    target = np.asarray(target, float)
    flank0 = generate_flank(cutter0, settings0, blank, Member.PINION, side)
    # start u: the flank point on the target circle (the cutter of the basic settings passes near it)
    try:
        u0 = float(flank0.locate(target[0], target[1], curvature=False).u)
    except SpiralBevelError:
        u0 = float(np.mean(flank0.generator.cp["u_j"])) + 2.0
    x0 = np.array([_value(cutter0, settings0, f) for f in free] + [u0])
    bad = np.full(7, 1e6)
    hand = flank0.hand

    def invariants(x):
        c, s = build(cutter0, settings0, free, x[:6])
        inv, _ = point_invariants(Generator(c, s, hand), x[6])       # the flank's kernel, without the outline
        return inv

    def newton(goal, x_start):
        def fun(x):
            try:
                return (invariants(x) - goal) * w
            except SpiralBevelError:
                return bad.copy()
        return solve_batched(fun, x_start, tol=tol, max_iter=max_iter, max_step=step)

    step = np.array([_MAX_STEP[f] for f in free] + [1.0])
    res = newton(target, x0)
    if not bool(res.converged):
        # continuation: move the goal from the start's own invariants to the target in steps (halved on failure),
        # each Newton solve starting from the previous solution
        try:
            inv0 = invariants(x0)
        except SpiralBevelError:
            inv0 = None
        if inv0 is not None:
            t, dt, x, tries = 0.0, 0.25, x0, 0
            while t < 1.0 and tries < 40:
                tries += 1
                t1 = min(1.0, t + dt)
                r = newton(inv0 + t1 * (target - inv0), x)
                _log.debug('continuation t=%.4f ok=%s x=%s', t1, bool(r.converged), r.x)
                if bool(r.converged):
                    t, x, dt = t1, r.x, min(0.5, 2.0 * dt)
                    res = r
                else:
                    dt *= 0.5
                    if dt < 1e-3:
                        break
            if t < 1.0:
                res.converged = np.asarray(False)
    if not bool(res.converged):
        raise ConvergenceError(f"pinion machine settings: Newton did not reach the synthesized geometry "
                               f"(free = {free}; scaled residual {float(res.residual):.3g})",
                               iterations=res.iterations, residual=float(res.residual), last=res.x)
    cutter, settings = build(cutter0, settings0, free, res.x[:6])
    flank = generate_flank(cutter, settings, blank, Member.PINION, side)
    _, nt = point_invariants(flank, res.x[6])
    if np.sign(nt) != np.sign(target_nt):
        raise ConvergenceError("pinion machine settings: Newton reached the mirror branch of the normal",
                               iterations=res.iterations, residual=float(res.residual), last=res.x)
    return cutter, settings, float(res.x[6]), dict(iterations=int(res.iterations), residual=float(res.residual))
