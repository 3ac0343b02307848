"""Edge radius of a synthesized pinion's cutter refitted so that its generated fillet stays below the gear's top.

The local synthesis moves the pinion's machine settings off the blank's basic ones (blank offset, machine centre to
back, ratio of roll), and with them the generated root: on a 36/61 design at a 1.1 deg spiral angle the synthesized
coast pinion's root lies 0.81 mm above the root cone at the heel. The fillet/blade junction of the generated flank
lies about rho (1 - sin alpha) above the generated root (edge radius rho, blade angle alpha: 1.1 mm for the derived
1.669 mm), so 1.9 mm above the root cone, while the gear's top reaches only the clearance c (1.16 mm) above it: the
gear's tooth meets the pinion's fillet, and the TCA shows an edge contact.

The blade surface does not depend on the edge radius (the blade is defined by its virtual sharp point:
``HeadCutter``), so the edge radius is refitted after the synthesis without changing the blade, the settings or the
mean-point fit: the largest edge radius at which the junction line lies at or below the gear's top at every face
station, times ``EDGE_RADIUS_FILL`` (the derived cutters' margin), the same search as the hypoid slot fit
(:func:`~spiralbevel.gearset.hypoid_fillet.largest_fitting_radius`). Only a derived edge radius is refitted, and
only made smaller. That bound (the gear's face cone in the plane of the axes) is conservative; where no edge radius
meets it, the largest edge radius that the pair's TCA accepts as well as a sharp blade's is taken instead
(:func:`_fit_edge_radius_by_tca`). Where a sharp blade itself leaves the gear's tip on the fillet (a synthesized blade
much steeper than the flank: its trochoidal fillet starts high), no edge radius helps and the design check
``fillet_top`` names the blank key to change.

The gear's top in the pinion's axial section: both members share the pitch generatrix, so at the cone distance R the
gear's face cone lies c(R) = h_f1(R) - h_a2(R) above the pinion's root cone, with h_f1(R) = h_fm1 + (R - R_m)
tan(theta_f1) and h_a2(R) = h_am2 + (R - R_m) tan(theta_a2) (ISO 23509 dedendum and addendum angles).

The edge radius alone does not always suffice: a blade with a sharp corner still generates a trochoidal fillet up to
its junction, and where the synthesis lifted the root, even that lies above the gear's top (11/17 at beta 21.5 deg:
junction 0.79-0.84 mm above the root cone with a sharp blade, the gear's top at 0.41 mm). :func:`lower_root` then
puts the synthesized pinion's root back on the root cone without changing its blade surface: the blade is extended
by Delta (axially) beyond its old tip and the work moved by Delta toward the cutter along the cradle axis (sliding
base + Delta). The cradle roll is a rotation about that axis, so it commutes with the translation: the generated
blade surface is the same (the old blade parameter u is u + Delta / cos(alpha) of the new cutter), and the root, the
envelope of the tip plane, moves Delta deeper. The new blade point: radius R_h - s Delta tan(alpha) (s = +1 outer,
-1 inner blade), width W - 2 Delta tan(alpha).

The same move with Delta < 0 (:func:`raise_root`, the point width kept: the cutting blade's surface does not depend on
it, and the cutter-fit refit narrows it from the derived one) shortens the blade: where the synthesis put the pinion's
cutter tip plane below the root cone (the settings that fix the flank at its mean point say nothing about the depth of
the cut; on 20/39 at beta 17.4 deg the synthesized drive side's root lies 1.17 mm below the root cone over the whole
face), the root is put back on the root cone with the blade surface, and so the mean-point fit, unchanged. A
root below the root cone misses the root-cone acceptance of the design (0.01 mm), and the cutter's opposite blade, in
the same tip plane, runs below the root of the other flank of the tooth space, whatever that flank's settings, and
cuts its fillet at every point width (:mod:`~spiralbevel.gearset.slot_check`).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..conventions import Member

__all__ = ["junction_height", "gear_top_height", "fit_pinion_edge_radius", "lower_root", "raise_root",
           "JUNCTION_STATIONS"]

#: face stations (toe to heel, both included) at which the junction line is held below the gear's top
JUNCTION_STATIONS = 7


def junction_height(flank, n_face: int = JUNCTION_STATIONS) -> np.ndarray:
    """Height (mm) of the generated fillet/blade junction line (u = u_j) above the blank's root cone at ``n_face``
    face stations evenly in cone distance from toe to heel.

    Parameters
    ----------
    flank : ToothFlank
    n_face : int

    Returns
    -------
    (n_face,) float, mm
    """
    ol, gen = flank.outline, flank.generator
    R = np.linspace(ol.Ri, ol.Re, n_face)
    mp = flank.mean_point()
    xj = flank._locator.junction(R, (mp.theta + np.pi - gen.mp["q"] + mp.psi_c, mp.psi_c))   # as ToothFlank.grid
    p = gen.evaluate_at(np.full(n_face, gen.cp["u_j"]), xj[:, 1], xj[:, 2], curvature=False).points
    Rx, h = ol.Rh(p[:, 2], np.hypot(p[:, 0], p[:, 1]))
    return h - ol.h_root(Rx)


def gear_top_height(blank, R) -> np.ndarray:
    """Height (mm) of the gear's face cone above the pinion's root cone at cone distances ``R`` (mm), (module
    docstring): the clearance, growing or shrinking along the face with theta_f1 - theta_a2.

    Parameters
    ----------
    blank : BevelBlank
    R : (n,) float, mm

    Returns
    -------
    (n,) float, mm
    """
    R = np.asarray(R, float)
    rm = float(blank.Rm)
    hf1 = float(blank.hfm1) + (R - rm) * math.tan(float(blank.delta1) - float(blank.delta_f1))
    ha2 = float(blank.ham2) + (R - rm) * math.tan(float(blank.delta_a2) - float(blank.delta2))
    return hf1 - ha2


def lower_root(blank, res, dev=None):
    """The synthesis result ``res`` with its pinion root put on the blank's root cone at the face station where it
    lies lowest (of the ``ROOT_STATIONS`` stations of the root-cone check, ``_root_heights``; nowhere below it),
    blade surface unchanged (module docstring); ``res`` itself when the root lies within ``CHECK_ROOT_MM`` of the
    root cone there, below it, or the cutter cannot be extended (the point width would vanish).

    Parameters
    ----------
    blank : BevelBlank
    res : SynthesisResult
    dev : list of float or None, mm
        ``_root_heights(res)`` when the caller has measured them already.

    Returns
    -------
    SynthesisResult
    """
    from .root_cone import CHECK_ROOT_MM

    dev = _root_heights(res) if dev is None else dev
    if not dev or min(dev) <= CHECK_ROOT_MM:
        return res
    return _move_root_onto(blank, res, min(dev), min)


def raise_root(blank, res, dev=None):
    """The synthesis result ``res`` with its pinion root put on the blank's root cone at the face station where it
    lies highest (of the ``ROOT_STATIONS`` stations of the root-cone check, ``_root_heights``; nowhere above it),
    blade surface unchanged: the blade shortened (module docstring); ``res`` itself when the root lies within
    ``CHECK_ROOT_MM`` of the root cone there, or above it. The raise lifts the fillet/blade junction with the root:
    where that brings it above both the mate's tip contact (the estimate of ``fillet_top``) and where it was, the
    edge radius is reduced to keep it there (the largest that does, times ``EDGE_RADIUS_FILL``); the blade surface
    stays the same.

    Parameters
    ----------
    blank : BevelBlank
    res : SynthesisResult
    dev : list of float or None, mm
        ``_root_heights(res)`` when the caller has measured them already.

    Returns
    -------
    SynthesisResult
    """
    from .root_cone import CHECK_ROOT_MM

    dev = _root_heights(res) if dev is None else dev
    if not dev or max(dev) >= -CHECK_ROOT_MM:
        return res
    new = _move_root_onto(blank, res, max(dev), max, keep_width=True)
    if new is res:
        return res
    return _keep_junction_below_mate_tip(blank, res, new)



def place_root(blank, res):
    """``res`` with its pinion root put on the blank's root cone: raised where it lies below it
    (:func:`raise_root`), lowered where it lies above it (:func:`lower_root`), from one measure of its heights;
    ``res`` itself where it lies on it (within ``CHECK_ROOT_MM``) or cannot be moved."""
    dev = _root_heights(res)
    new = raise_root(blank, res, dev)
    return lower_root(blank, res, dev) if new is res else new


def _move_root_onto(blank, res, h0: float, which, keep_width: bool = False):
    """``res`` with its root moved so that its station ``which`` (max: the highest, min: the lowest) of the root
    heights ``h0`` (mm) lies on the root cone (:func:`_move_root`); ``res`` itself when it cannot be moved.

    The move along the cradle axis need not be normal to the root cone (the machine root angle of a synthesized pinion
    is free): the root then moves h0 / cos(tilt) (0.016 mm above the cone after a 1.59 mm raise on a 20/20 miter with
    its slide tilted by the dedendum angle, 8.15 deg); one secant step on the measured heights puts it back (they are
    linear in the move: a parallel shift of the tip plane)."""
    from .root_cone import CHECK_ROOT_MM

    new = _move_root(blank, res, h0, keep_width=keep_width)
    if new is res:
        return res
    h1 = which(_root_heights(new) or [0.0])
    if abs(h1) > 0.5 * CHECK_ROOT_MM and abs(h1 - h0) > 1e-12:
        again = _move_root(blank, res, -h0 * h0 / (h1 - h0), keep_width=keep_width)
        if again is not res:
            new = again
    return new


def _keep_junction_below_mate_tip(blank, old, new, n_face: int = JUNCTION_STATIONS):
    """``new`` (``old`` with its root raised) with its edge radius reduced, where needed, so that the raise lifts the
    fillet/blade junction nowhere above both the mate's tip contact (``fillet_top.active_start_height``) and the
    junction of ``old``: the largest such edge radius times ``EDGE_RADIUS_FILL``; ``new`` itself when it already
    stays there or no edge radius does (the fillet-top check then speaks)."""
    from ..errors import GeometryError
    from ..generation.flank import generate_flank
    from ..machine.default_cutter import EDGE_RADIUS_FILL
    from .fillet_top import active_start_height
    from .hypoid_fillet import largest_fitting_radius

    fl = new.pinion_flank
    R = np.linspace(fl.outline.Ri, fl.outline.Re, n_face)
    try:
        mp = fl.mean_point()
        limit = np.maximum(active_start_height(blank, Member.PINION, R, abs(mp.pressure_angle), abs(mp.spiral_angle)),
                           junction_height(old.pinion_flank, n_face))
        if np.all(junction_height(fl, n_face) <= limit):
            return new
        cutter, settings, side = new.pinion_cutter, new.pinion_settings, fl.side

        def flank(r):
            return generate_flank(dataclasses.replace(cutter, edge_radius=float(r)), settings, blank, Member.PINION,
                                  side)

        rho = largest_fitting_radius(lambda r: float(np.min(limit - junction_height(flank(r), n_face))),
                                     cutter.edge_radius)
        if rho is None:
            return new
        rho *= EDGE_RADIUS_FILL
        return dataclasses.replace(new, pinion_cutter=dataclasses.replace(cutter, edge_radius=rho),
                                   pinion_flank=flank(rho))
    except GeometryError:
        return new


def _root_heights(res) -> list:
    """Heights (mm) of the synthesized pinion's root above the root cone at the ``ROOT_STATIONS`` face stations of the
    design check "root below the root cone" (:func:`~spiralbevel.gearset.root_cone.root_heights`: the cutter's tip
    line located on the equation of meshing, then Newton's method at each station; checked against a brute-force
    sweep of the tip circle in ``tests/gearset/test_root_cone.py``), the stations it reaches; empty when it reaches
    none. One measure for the placement and the check: a root placed on the root cone passes the check by
    construction. The tip line is regular also where the tip generates no enveloping root point (the root there is
    the trace of the tip circle; on 16/87, 26/61 and 30/69 of ``bench_robustness.py 100 2`` the drive cut 1.03,
    0.85 and 3.31 mm below the root cone with no enveloping root point at toe, mean or heel)."""
    from ..errors import GeometryError
    from .root_cone import root_heights

    try:
        _, h = root_heights(res.pinion_flank)
    except GeometryError:
        return []
    return [float(x) for x in h if np.isfinite(x)]


def _move_root(blank, res, delta: float, keep_width: bool = False):
    """``res`` with its pinion's tip plane moved ``delta`` mm deeper (negative: higher) along the cradle axis, the
    blade surface unchanged (module docstring); ``res`` itself when the point width would vanish or the new flank
    cannot be generated. With ``keep_width`` the point width stays (the opposite blade, which the generated flank does
    not see, moves with the point; the cutter-fit refit then narrows the width from the derived one)."""
    from ..errors import GeometryError
    from ..generation.flank import generate_flank
    from ..machine.default_cutter import EDGE_RADIUS_FILL

    cutter, settings = res.pinion_cutter, res.pinion_settings
    ta = math.tan(cutter.blade_angle)
    width = cutter.point_width if keep_width else cutter.point_width - 2.0 * delta * ta
    if width <= 0.0:
        return res
    rho_max = 0.5 * width * math.cos(cutter.blade_angle) / (1.0 - math.sin(cutter.blade_angle))   # HeadCutter's limit
    new = dataclasses.replace(cutter, point_radius=cutter.point_radius - cutter.sign * delta * ta, point_width=width,
                              edge_radius=min(cutter.edge_radius, EDGE_RADIUS_FILL * rho_max))
    st = dataclasses.replace(settings, sliding_base=settings.sliding_base + delta)
    try:
        flank = generate_flank(new, st, blank, Member.PINION, res.pinion_flank.side)
        flank.mean_point()
    except GeometryError:
        return res
    return dataclasses.replace(res, pinion_cutter=new, pinion_settings=st, pinion_flank=flank)


def fit_pinion_edge_radius(blank, res, n_face: int = JUNCTION_STATIONS):
    """The synthesis result ``res`` with its pinion cutter's edge radius refitted (module docstring), or ``res``
    itself when its fillet already stays below the gear's top. Where no edge radius keeps the junction below the
    gear's face cone, the largest that keeps the pair's TCA off the fillet as far as a sharp blade does
    (:func:`_fit_edge_radius_by_tca`), or ``res`` itself when no edge radius helps (then the TCA shows the fillet
    contact and the design check ``fillet_top`` names the blank key to change).

    Parameters
    ----------
    blank : BevelBlank
    res : SynthesisResult
    n_face : int

    Returns
    -------
    SynthesisResult
    """
    from ..errors import GeometryError
    from ..generation.flank import generate_flank
    from ..machine.default_cutter import EDGE_RADIUS_FILL
    from .hypoid_fillet import largest_fitting_radius

    cutter, settings, side = res.pinion_cutter, res.pinion_settings, res.pinion_flank.side
    R = np.linspace(res.pinion_flank.outline.Ri, res.pinion_flank.outline.Re, n_face)
    top = gear_top_height(blank, R)

    def flank(r):
        return generate_flank(dataclasses.replace(cutter, edge_radius=float(r)), settings, blank, Member.PINION, side)

    def room(r):   # > 0: the junction lies below the gear's top at every station
        return float(np.min(top - junction_height(flank(r), n_face)))

    try:
        if room(cutter.edge_radius) > 0.0:
            return res
        rho = largest_fitting_radius(room, cutter.edge_radius)
    except GeometryError:
        return res
    if rho is None:
        return _fit_edge_radius_by_tca(blank, res, flank)
    rho *= EDGE_RADIUS_FILL
    new = dataclasses.replace(cutter, edge_radius=rho)
    return dataclasses.replace(res, pinion_cutter=new, pinion_flank=flank(rho))


#: relative resolution (of the derived edge radius) of the TCA-judged edge-radius search
TCA_RADIUS_TOL = 0.01
#: TCA positions over one mesh cycle of that search: four times the default candidates' check (41), for short
#: contacts with the fillet between the check's positions (40/76 of ``bench_robustness.py 100 2``: 0.11 deg of pinion
#: roll, which 41 positions 0.225 deg apart step over); the job's short-contact detector has the last word
#: (:func:`_short_edge_contact`)
TCA_RADIUS_POSITIONS = 161


def _fit_edge_radius_by_tca(blank, res, flank):
    """``res`` with the largest edge radius (times ``EDGE_RADIUS_FILL``) at which the pair's TCA over one mesh cycle
    (``facemilled.bearing_off_flank`` at ``TCA_RADIUS_POSITIONS``) has no more positions off the flanks than with a
    sharp-cornered blade (edge radius rho0/1000), by bisection to ``TCA_RADIUS_TOL`` rho0; ``res`` itself when that is
    no fewer than with the derived edge radius rho0 (the fillet's height then does not come from the edge radius), the
    result has no gear flank, or a flank cannot be generated.

    The fallback of :func:`fit_pinion_edge_radius` where no edge radius keeps the junction below the gear's face cone
    in the plane of the axes (that bound is conservative: the gear's tip passes it in the middle of the tooth space,
    ``fillet_top``): on 40/76 at beta 6 deg of ``bench_robustness.py 100 2`` the synthesized coast pinion's sharp
    blade still generates its junction 0.12 mm above the gear's face cone, 0.02 mm above the estimate of the gear's
    tip contact, and the TCA shows the pinion's fillet at 2 of 41 positions with the derived 0.351 mm, at none from
    0.25 mm down. The blade, the settings and the mean-point fit stay as they are (module docstring).

    A radius whose pair shows an edge contact between the positions of the job's TCA (:func:`_short_edge_contact`) is
    not taken (``res`` itself): the default search then goes on to its next candidate, which may keep the bearing
    inside without it (14/48 and 16/31 of ``bench_robustness.py 100 2``).

    ``flank`` : callable edge radius (mm) -> ToothFlank with ``res``'s blade and settings.
    """
    from ..errors import ConvergenceError, GeometryError
    from ..machine.default_cutter import EDGE_RADIUS_FILL
    from .facemilled import bearing_off_flank

    gear = getattr(res, "gear_flank", None)
    if gear is None:
        return res
    rho0 = float(res.pinion_cutter.edge_radius)

    def off(r):
        # at the positions only: the finer check between them is _short_edge_contact's, once, on the radius taken
        return bearing_off_flank(blank, flank(r), gear, TCA_RADIUS_POSITIONS, between=False)

    try:
        lo = 1e-3 * rho0
        target, worst = off(lo), off(rho0)
        if target >= worst:
            return res
        hi = rho0
        while hi - lo > TCA_RADIUS_TOL * rho0:   # off(lo) <= target < off(hi)
            mid = 0.5 * (lo + hi)
            if off(mid) <= target:
                lo = mid
            else:
                hi = mid
        rho = EDGE_RADIUS_FILL * lo
        if off(rho) > target:
            rho = lo
        new = flank(rho)
        if _short_edge_contact(blank, new, gear):
            return res
    except (GeometryError, ConvergenceError):
        return res
    return dataclasses.replace(res, pinion_cutter=dataclasses.replace(res.pinion_cutter, edge_radius=rho),
                               pinion_flank=new)


#: TCA positions of the job's TCA (``job.tca.run_pair_tca``), between which ``gearset.tca.short_events`` looks
JOB_TCA_POSITIONS = 21


def _short_edge_contact(blank, pinion_flank, gear_flank) -> bool:
    """Whether the pair's TCA at the job's ``JOB_TCA_POSITIONS`` shows an edge contact, at a position or leading
    between two (``gearset.tca.short_events``): what the job's report and the robustness bench count as an edge
    contact. True also where that TCA cannot be solved."""
    from ..errors import ConvergenceError, NoContactError
    from ..meshing.pair import meshing_pair
    from ..meshing.tca import solve_tca
    from .tca import short_events

    pair = meshing_pair(pinion_flank, gear_flank, blank)
    try:
        res = solve_tca(pair.pinion, pair.gear, pair.kinematics, n_positions=JOB_TCA_POSITIONS, start=pair.start)
    except (NoContactError, ConvergenceError):
        return True
    if np.any(res.edge_contact):
        return True
    return any(e["kind"] == "edge" for e in short_events(pair, res))
