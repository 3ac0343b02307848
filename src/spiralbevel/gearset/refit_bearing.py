"""The default pair keeps the bearing that its search verified through the point-width refit.

The refit (:func:`~spiralbevel.gearset.slot_refit.fit_point_widths`) narrows a derived point width that cuts into
the other flank of its tooth space; when the narrower point holds a smaller edge radius only, the flank is generated
again, its fillet reaches elsewhere, and the contact at the ends of the mesh cycle can run onto it (10/54 of
bench/bench_robustness.py 40 1, drive: 6.13 -> 1.55 mm, edge radius 3.35 -> 1.05 mm, 19 of 41 positions on the
pinion's fillet, where the search had verified 0). The default synthesis therefore judges a candidate of the pinion
side synthesized last after the refit it will get (:func:`off_after_refit`), and checks each side again once the
pair is refitted (:func:`keep_verified_bearings`).
"""

from __future__ import annotations

import warnings

from ..conventions import Member
from ..errors import DesignError, DesignWarning, GeometryError

__all__ = ["off_after_refit", "keep_verified_bearings"]


def off_after_refit(blank, res, gear, s1, other) -> int:
    """Positions off the flanks of a candidate pinion side after the point-width refit it will get against the other
    pinion side (:func:`~spiralbevel.gearset.slot_refit.refit_side`).

    Parameters
    ----------
    blank : BevelBlank
    res : SynthesisResult
        The candidate (its pinion cutter, settings and flank).
    gear : FlankSetup
        The mating gear side.
    s1 : Side
        The candidate's pinion side.
    other : FlankSetup
        The other pinion side, final.

    Returns
    -------
    int
        0 when the refit keeps the candidate's flank (the point width fits, the narrower point holds its edge radius,
        or no width fits: the slot rule and the check judge that); else the TCA positions off the flanks
        (:func:`~spiralbevel.gearset.facemilled.bearing_off_flank`) of the flank generated with the smaller edge
        radius.
    """
    from .facemilled import FlankSetup, bearing_off_flank
    from .slot_refit import refit_side

    setups = {(Member.PINION, s1): FlankSetup(Member.PINION, s1, res.pinion_cutter, res.pinion_settings,
                                              res.pinion_flank, ""),
              (Member.PINION, other.side): other}
    try:
        got = refit_side(blank, setups, Member.PINION, s1)
    except (GeometryError, DesignError):
        return 0                      # the slot check reports it; the bearing of this flank is the one verified
    if got is None or got[1] is res.pinion_flank:
        return 0
    return bearing_off_flank(blank, got[1], gear.flank)


def keep_verified_bearings(spec, blank, sy, basic, verified, out, synth):
    """The default pair after the point-width refit keeps the bearing that its search verified.

    The refit (:func:`~spiralbevel.gearset.slot_refit.fit_point_widths`) regenerates a flank whose narrower point
    holds a smaller edge radius only; its fillet then reaches elsewhere and can take the contact at the ends of the
    mesh cycle. The side synthesized last was judged after the refit it gets (:func:`off_after_refit`); the one before
    it could not be (the other pinion side was not final yet), nor a gear flank the refit regenerated. Each default
    side whose pinion or gear flank the refit regenerated is checked again; when more TCA positions leave the
    flanks than the search verified, that side is synthesized again against the final flanks (the other pinion side
    and the gear as refitted), its candidates judged after their own refit, and the pair refitted; kept when it has
    fewer positions off the flanks.

    Parameters
    ----------
    spec : DesignFile
    blank : BevelBlank
    sy : SynthesisSpec
        The default synthesis (``facemilled.effective_synthesis``).
    basic, verified, out : {(Member, Side): FlankSetup}
        The basic setups, the setups the search verified (before the refit) and the refitted ones.
    synth : {side name: SynthesisResult}

    Returns (setups, synthesis results): ``out`` and ``synth``, or the copies with a side synthesized again.
    """
    from ..errors import SpiralBevelError
    from .facemilled import PAIR_SIDES, bearing_off_flank, synthesize_sides
    from .slot_check import fit_point_widths

    for name in sy.sides:
        s1, s2 = PAIR_SIDES[name]
        kp, kg = (Member.PINION, s1), (Member.GEAR, s2)
        if name not in synth or (out[kp].flank is verified[kp].flank and out[kg].flank is verified[kg].flank):
            continue
        off = bearing_off_flank(blank, out[kp].flank, out[kg].flank)
        if off <= bearing_off_flank(blank, verified[kp].flank, verified[kg].flank):
            continue
        setups = dict(out)
        setups[kp] = basic[kp]
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", DesignWarning)    # said once already, by the first search
                new, res = synthesize_sides(spec, blank, setups, sy.model_copy(update={"sides": (name,)}))
        except SpiralBevelError:
            continue
        out2, synth2 = dict(out), dict(synth)
        out2.update(new)
        synth2.update(res)
        fit_point_widths(spec, blank, out2, synth2)
        if bearing_off_flank(blank, out2[kp].flank, out2[kg].flank) < off:
            out, synth = out2, synth2
    return out, synth
