"""Last stage of the default bearing search: the mean contact point M moved toward the pinion's tip, as far as the
mean-point angle check allows, for every path direction whose pair had an edge contact at the mean pitch point.

When no candidate of the default synthesis keeps the bearing inside both flanks (``gearset.facemilled._candidates``),
the usual reason on a pinion with few teeth is an edge contact on the pinion's fillet near one end of the mesh
cycle: the gear addendum h_am2 is small, the pinion's generated fillet reaches up to about the gear's top, and a path
through the mean pitch point runs onto the pinion's fillet/flank junction before the contact passes to the next
pair. Moving M below the gear's pitch line (toward the middle of the working depth, i.e. up the pinion flank) moves
the whole path away from the pinion's fillet. The depth turns the pinion's mean-point angles off the design in
proportion to it (the pinion is matched to the gear at M and crowned in profile relative to it), so the depth used is
the one at which the deviation reaches ``margin`` of the check, found from one probe synthesis per direction.

16/87 at a 9.6 deg spiral angle (bench/bench_robustness.py, sample ``100 2``), coast side: every path direction
through the pitch point touches the pinion's fillet at 2 to 7 of 41 TCA positions; at -55 deg with M at 0.1 of the
middle of the working depth (0.08 mm below the pitch line) the bearing stays inside and the mean-point angles stay
0.043 deg from the design.
"""

from __future__ import annotations

from collections.abc import Callable

from ..errors import ConvergenceError, GeometryError

__all__ = ["PROBE_FRACTION", "RESCUE_SYNTHESES", "deepest_allowed_fraction", "rescue_by_depth"]

#: depth of the probe synthesis, as a fraction of the middle of the working depth below the pitch line: deep enough
#: that its mean-point deviation (a few 0.01 deg per 0.1) stands well above the fit's own (1e-6 deg), shallow enough
#: to stay on the proportional part (0.109, 0.219, 0.441 deg at 0.25, 0.5, 1.0 on the 16/87 above)
PROBE_FRACTION = 0.25

#: syntheses (probes included) this stage may add per side, two per path direction
RESCUE_SYNTHESES = 12


def deepest_allowed_fraction(probe_fraction: float, probe_deviation: float, check: float, margin: float) -> float:
    """Depth fraction at which the mean-point angle deviation, proportional to the depth, reaches ``margin`` of the
    check.

    Parameters
    ----------
    probe_fraction : float
        Depth fraction of the probe synthesis (> 0).
    probe_deviation : float, rad
        Largest deviation of the probe pinion's mean-point pressure and spiral angles from the design.
    check : float, rad
        The developed-pair check on the mean-point angles.
    margin : float
        Fraction (< 1) of the check to aim at.

    Returns
    -------
    float
        The probe's fraction when its deviation is within ``margin * check`` already, else the scaled one.
    """
    if probe_deviation <= margin * check:
        return probe_fraction
    return probe_fraction * margin * check / probe_deviation


def rescue_by_depth(pitch_offs: dict, synthesize: Callable, deviation: Callable, judge: Callable, check: float,
                    margin: float, max_syntheses: int = RESCUE_SYNTHESES) -> int:
    """Synthesize each path direction again with M below the pitch line, fewest edge positions first, until one
    pair keeps the bearing inside.

    Parameters
    ----------
    pitch_offs : {(float, str): int}
        TCA positions off the flanks of each converged pitch-point candidate: (path direction deg, set name) -> count.
        Candidates with no position off (nothing to rescue) are skipped; those with every position off (the flank
        does not cover the face, or the TCA fails) come last.
    synthesize : callable (eta deg, depth fraction, set name) -> SynthesisResult
        Raises ConvergenceError or GeometryError when the synthesis fails.
    deviation : callable (SynthesisResult) -> float, rad
        Largest mean-point angle deviation of the synthesized pinion from the design.
    judge : callable (SynthesisResult, depth fraction, set name) -> int
        Positions off the flanks (0: bearing inside and angles within the check; the caller keeps it as its best).
    check, margin : float
        As :func:`deepest_allowed_fraction` (rad, fraction).
    max_syntheses : int

    Returns
    -------
    int
        Number of syntheses run (converged or not).
    """
    tried = 0
    order = sorted(((off, eta, free) for (eta, free), off in pitch_offs.items() if 0 < off), key=lambda t: t[0])
    for _, eta, free in order:
        if tried + 2 > max_syntheses:
            break
        try:
            tried += 1
            probe = synthesize(eta, PROBE_FRACTION, free)
            frac = deepest_allowed_fraction(PROBE_FRACTION, deviation(probe), check, margin)
            tried += 1
            res = probe if frac == PROBE_FRACTION else synthesize(eta, frac, free)
        except (ConvergenceError, GeometryError):
            continue
        if judge(res, frac, free) == 0:
            break
    return tried

