"""The candidate search of the default synthesis, one pinion side at one TE level: the local syntheses over path
directions, depths of the mean contact point and sets of solved settings (``DEFAULT_CANDIDATES``, the other sets, the
depth rescue), and the TCA count of positions off the flanks that judges each candidate and selects the pinion flank
(:func:`bearing_off_flank`). The sides, the TE levels and the report of what was chosen are
:mod:`~spiralbevel.gearset.default_synthesis`'s."""

from __future__ import annotations

import math

import numpy as np

from ..conventions import Member
from ..errors import ConvergenceError, DesignError, GeometryError
from ..meshing.tca_result import ARCSEC
from .flank_checks import CHECK_ANGLE_DEG
from .flank_setup import FlankSetup

#: path directions (deg, on the gear from the profile direction) the default synthesis tries in turn, per side, until
#: the TCA keeps the bearing inside both flanks: a path across the profile suits most designs; when the mean point is
#: near a tooth top (a small gear addendum), a path turned toward the lengthwise direction keeps the contact off it
DEFAULT_PATH_DIRECTIONS = (0.0, -20.0, 20.0, -40.0, 40.0, -55.0, 55.0)

#: depth of the mean contact point M below the gear's pitch line, as a fraction of the offset (h_am1 - h_am2)/2 of the
#: middle of the working depth from it: 0 (the mean pitch point) first, then M moved half way toward the middle of
#: the working depth (on a pinion with few teeth the gear addendum is small and a bearing through the pitch point
#: runs onto the gear's top edge before the transfer point)
DEFAULT_DEPTH_FRACTIONS = (0.0, 0.5)

#: M below the pitch line turns the synthesized pinion's mean-point pressure angle off the design in proportion to
#: the depth (the pinion is matched to the gear at M and crowned in profile relative to it: -0.035, -0.070,
#: -0.117 deg at 0.6, 1.2, 2.0 mm on a 12/54 pinion at beta 4.9 deg): a depth candidate whose mean-point angles miss
#: the check (``CHECK_ANGLE_DEG``) is synthesized once more with its depth scaled down to this fraction of the
#: depth at which the deviation would reach the check
DEFAULT_DEPTH_ANGLE_MARGIN = 0.8

#: path directions (deg) turned farther toward the lengthwise direction, tried by the face-milled default after
#: ``DEFAULT_PATH_DIRECTIONS`` at the mean pitch point: at a large spiral angle a path within 55 deg of the profile
#: direction can reach the gear's top edge at one end of the mesh cycle and the pinion's fillet at the other, while
#: a path at 70 deg crosses less of the profile per mesh cycle (bench/bench_robustness.py)
DEFAULT_LENGTHWISE_DIRECTIONS = (-70.0, 70.0)

#: (path direction deg, depth fraction) of the default synthesis, in the order tried; at most
#: ``DEFAULT_MAX_SYNTHESES`` local syntheses per side (failed ones included) bound the search
DEFAULT_CANDIDATES = tuple((eta, frac) for frac in DEFAULT_DEPTH_FRACTIONS
                           for eta in (DEFAULT_PATH_DIRECTIONS + DEFAULT_LENGTHWISE_DIRECTIONS if not frac
                                       else DEFAULT_PATH_DIRECTIONS[:3]))
DEFAULT_MAX_SYNTHESES = 16

#: when none of ``DEFAULT_CANDIDATES`` keeps the bearing inside both flanks, each path direction at the mean pitch
#: point is synthesized again with the sets of solved settings not tried for it yet (``synthesis.free``: offset,
#: modified roll, fixed blade), at most this many more syntheses per side: the seven mean-point conditions fix the
#: pinion flank to second order at M, the set of free settings shapes it away from M, and with it where the contact
#: runs near the ends of the mesh cycle (38/92 at beta 30.5 deg, coast: with the blank offset free every direction
#: touches the pinion's fillet at 2 to 13 of 41 positions, with the modified roll free the path at -40 deg stays
#: inside, bench/bench_robustness.py seed 2; 34/194 at beta 6.2 deg, seed 1: no pinion flank of the first set that
#: converges covers the face at 8 arcsec, one of another set does, where the TE level was halved before)
DEFAULT_OTHER_SET_SYNTHESES = 18

_ALL_DIRECTIONS = DEFAULT_PATH_DIRECTIONS + DEFAULT_LENGTHWISE_DIRECTIONS

#: positions of the TCA that checks the default bearing over one mesh cycle
_CHECK_POSITIONS = 41   # as the job's TCA (run_pair_tca)
#: design-file names of the sets of solved settings (``synthesis.free``) and their ``meshing.synthesis`` flags
_FREE = {"offset": "FREE_OFFSET", "modified-roll": "FREE_MODIFIED_ROLL", "fixed-blade": "FREE_FIXED_BLADE"}


def bearing_off_flank(blank, pinion_flank, gear_flank, n_positions: int = _CHECK_POSITIONS,
                      between: bool = True) -> int:
    """Number of TCA positions over one mesh cycle at which the pair's contact is not inside both flanks.

    Counts positions with no real-flank contact and positions in edge contact (the contact point beyond a flank
    boundary: tooth top, fillet, toe or heel), from the TCA's physical-contact status; ``n_positions`` when the TCA
    itself fails or the pinion flank does not cover the whole face. With ``between``, when no position is off, an
    edge contact that leads between the positions (at a tooth-pair transfer, :mod:`~spiralbevel.gearset.transfer_check`)
    counts its finer positions in steps of the TCA (at least 1).
    """
    from ..errors import NoContactError
    from ..meshing.pair import meshing_pair
    from ..meshing.tca import solve_tca

    try:   # the synthesized flank must cover the whole face (the grid of the report, the CAD and the TCA outline)
        pinion_flank.grid(9, 5, curvature=False)
    except GeometryError:
        return n_positions
    pair = meshing_pair(pinion_flank, gear_flank, blank)
    try:
        res = solve_tca(pair.pinion, pair.gear, pair.kinematics, n_positions=n_positions, start=pair.start)
    except (NoContactError, ConvergenceError):
        return n_positions
    off = int(np.sum(~np.isfinite(res.te) | res.edge_contact))
    if off == 0 and between:   # a short edge contact between the positions, at a tooth-pair transfer
        from .transfer_check import FACTOR, short_edge_positions

        off = -(-short_edge_positions(pair, res) // FACTOR)    # finer positions in steps (>= 1 if any)
    return off


def _angle_deviation(blank, flank) -> float:
    """Largest deviation (rad) of the flank's mean-point pressure and spiral angles from the design."""
    from ..generation.basic_settings_solve import flank_fit

    f = flank_fit(blank, flank)
    return max(abs(f.pressure_angle - f.pressure_angle_design), abs(f.spiral_angle - f.spiral_angle_design))


def _angles_hit(blank, flank) -> bool:
    """True when the flank's mean-point pressure and spiral angles are within the developed-pair check
    (``CHECK_ANGLE_DEG``) of the design."""
    return _angle_deviation(blank, flank) <= math.radians(CHECK_ANGLE_DEG)

#: the default synthesis keeps a pinion blade angle within this many degrees of the pinion's basic one: the seven
#: mean-point conditions also have solutions far from the blank's settings (a 46 deg blade on a 21 deg design at a
#: 10 deg spiral angle, where the modified-roll set is nearly singular); at a large spiral angle a path turned 55 deg
#: from the profile direction legitimately moves the blade by 9 deg (bench/bench_robustness.py, seed 1)
DEFAULT_MAX_BLADE_CHANGE_DEG = 15.0


def _require_near_branch(res, pin):
    """ConvergenceError when the synthesized pinion blade angle is more than ``DEFAULT_MAX_BLADE_CHANGE_DEG`` from
    the pinion's basic one (the fit reached a far branch)."""
    d = math.degrees(res.pinion_cutter.blade_angle - pin.cutter.blade_angle)
    if abs(d) > DEFAULT_MAX_BLADE_CHANGE_DEG:
        raise ConvergenceError(f"pinion machine settings: the fit reached a far branch (blade angle "
                               f"{math.degrees(res.pinion_cutter.blade_angle):.2f} deg, {d:+.2f} deg from the basic "
                               f"{math.degrees(pin.cutter.blade_angle):.2f} deg; free = {res.free})",
                               iterations=res.iterations, residual=res.residual, last=None)


def _root_on_cone(flank) -> bool:
    """True when the flank's generated root lies nowhere more than ``CHECK_ROOT_MM`` below the root cone (the design
    check ``gearset.root_cone``, 11 face stations)."""
    from .root_cone import root_cone

    try:
        return not root_cone(flank).below
    except (GeometryError, DesignError):
        return False


#: rank (positions off the flanks) of a default candidate that keeps the bearing inside but closes the tooth space
#: (gearset/slot_open.py): after every candidate that keeps the bearing inside with the slot open, before any with a
#: position off the flanks, so that when no candidate opens the slot the one taken without the rule is taken
SLOT_CLOSED_RANK = 0.5


def _candidates(sy, blank, gear, pin, s1, te, syn, default, max_syntheses, refit=False, max_other=0, slot=(None, None),
                raised=None):
    """The local syntheses of one pinion side at the TE level ``te`` (arcsec): the design file's path direction, or
    for the default synthesis the first of ``DEFAULT_CANDIDATES`` whose pair keeps the bearing inside both flanks
    over the whole mesh cycle (TCA: real contact, no edge, at every position); if none does, the one with the fewest
    positions off the flank. At most ``max_syntheses`` syntheses (failed ones included) for the default.

    A default depth candidate (M below the pitch line) whose pinion misses the mean-point angle check is synthesized
    once more at its depth scaled to ``DEFAULT_DEPTH_ANGLE_MARGIN`` of the depth at which it would reach the check
    (the deviation is proportional to the depth). When still no candidate keeps the bearing inside, each path
    direction at the pitch point is synthesized with the sets of solved settings not tried for it yet, at most
    ``max_other`` more syntheses (``DEFAULT_OTHER_SET_SYNTHESES``).

    With ``refit``, a default candidate whose bearing leaves the flanks at some position gets its pinion's root put
    back on the root cone (:func:`~spiralbevel.gearset.pinion_fillet.lower_root`) and its derived edge radius
    refitted to keep the generated fillet below the gear's top
    (:func:`~spiralbevel.gearset.pinion_fillet.fit_pinion_edge_radius`), both with the blade surface unchanged;
    kept when the TCA then has fewer positions off the flanks.

    With ``slot`` = (the other pinion side's final FlankSetup, {Side: floor}) (the side synthesized last), a default
    candidate that keeps the bearing inside but leaves a tooth space that no cutter fits down to the floor of its point
    width (:func:`~spiralbevel.gearset.slot_open.slot_closed`) ranks ``SLOT_CLOSED_RANK``: the search goes on, and
    takes it only when no later candidate keeps the bearing inside with the slot open (only a candidate that would
    end the search is checked: one check per side).

    Returns (best, tried, last error): best = (positions off the flank, SynthesisResult, free set name) or None.
    """
    from .pinion_fillet import fit_pinion_edge_radius, lower_root, place_root
    from .refit_bearing import off_after_refit
    from .slot_open import slot_closed

    slot_other, floors = slot

    hint = pin.source.startswith("basic settings solved")   # start from the pinion's solved basic settings
    # the design file's set of solved settings first; for the default synthesis the other sets after it
    names = [sy.free] + ([f for f in _FREE if f != sy.free] if default else [])
    cands = DEFAULT_CANDIDATES if default else ((sy.path_direction, 0.0),)
    mid = 0.5 * (float(blank.ham1) - float(blank.ham2))     # middle of the working depth below the pitch line
    best, spare, tried, last = None, None, 0, None
    done = set()    # (path direction, depth fraction, set name) synthesized, converged or not
    pitch_offs: dict = {}   # (path direction, set name): positions off the flanks, M at the pitch point

    def synthesize(eta, frac, free):
        nonlocal tried
        tried += 1
        done.add((eta, frac, free))
        res = syn.synthesize_pinion(
            gear.cutter, gear.settings, blank, side=s1, eta=math.radians(eta),
            semi_major_axis=sy.semi_major_axis, te_magnitude=te * ARCSEC,
            approach=sy.approach, free=getattr(syn, _FREE[free]), depth=frac * mid,
            pinion_cutter_hint=pin.cutter if hint else None,
            pinion_settings_hint=pin.settings if hint else None)
        if default:
            _require_near_branch(res, pin)
        if default and refit and floors is not None and floors[s1] < 1.0:
            # a cutter tip plane below the root cone raised onto it, one above it (the free settings moved it: 1.85 mm
            # on 17/24 of bench_robustness.py 100 2) lowered onto it, blade extended, point narrower (pinion_fillet.py)
            new = place_root(blank, res)
            up = res.pinion_settings.sliding_base - new.pinion_settings.sliding_base
            if up > 0.0 and raised is not None:   # {id: (result, mm raised)} for the report's source line
                raised[id(new)] = (new, up)
            res = new
        return res

    def judge(res, frac, free, eta=None):
        """Positions off the flanks of a default candidate (after the fillet retry), kept as best or spare."""
        nonlocal best, spare
        off = bearing_off_flank(blank, res.pinion_flank, gear.flank)
        if refit and 0 < off < _CHECK_POSITIONS:   # an edge contact: the root back on the root cone, a smaller
            res2 = fit_pinion_edge_radius(blank, lower_root(blank, res))    # fillet; kept if it helps
            off2 = off if res2 is res else bearing_off_flank(blank, res2.pinion_flank, gear.flank)
            # (the root put on the root cone at toe, mean and heel can dip below it between them: not kept then)
            if off2 < off and _root_on_cone(res2.pinion_flank):
                res, off = res2, off2
        # M off the pitch point moves the pinion's mean-point angles off the design (by a few 0.01 deg): such a
        # candidate is taken only when it keeps the bearing inside the flanks and the angles within the check
        if frac and off == 0 and not _angles_hit(blank, res.pinion_flank):
            off = _CHECK_POSITIONS
        if off == 0 and slot_other is not None and slot_closed(
                blank, {s1: FlankSetup(Member.PINION, s1, res.pinion_cutter, res.pinion_settings, res.pinion_flank, ""),
                        slot_other.side: slot_other}, floors, finished=slot_other.side):
            off = SLOT_CLOSED_RANK
        if off == 0 and slot_other is not None and floors[s1] < 1.0:
            off = off_after_refit(blank, res, gear, s1, slot_other)
        if not frac and eta is not None:
            pitch_offs[(eta, free)] = off
        # a depth candidate is kept only with the bearing inside; one that closes the tooth space (SLOT_CLOSED_RANK)
        # also counts, so that, as for a pitch-point one, it is taken when no candidate opens the slot
        # (16/87 of bench/bench_robustness.py 100 2: the coast rescue at -55 deg is inside but closes the space at
        # the toe, where the drive cut's tip runs 1.03 mm below the root cone; the pitch-point -55 deg with 2 of 41
        # positions on the pinion's fillet was taken instead)
        if (best is None or off < best[0]) and (off < 1 or not frac):
            best = (off, res, free)
        elif spare is None or off < spare[0]:
            spare = (off, res, free)
        return off

    for eta, frac in cands:
        if frac and not mid:
            continue
        res = None
        for k, free in enumerate(names):
            if default and tried >= max_syntheses:
                break
            try:
                res = synthesize(eta, frac, free)
                break
            except (ConvergenceError, GeometryError) as err:
                # the default tries the next set of settings, then the next candidate; a given
                # [synthesis] section gets its own error
                if not default and (k == len(names) - 1 or not isinstance(err, ConvergenceError)):
                    raise
                last = err
                if k == len(names) - 1 or not isinstance(err, ConvergenceError):
                    break
        if res is None:
            if default and tried >= max_syntheses:
                break
            continue
        names = [free] + [f for f in names if f != free]     # the set that worked first for the next candidates
        if not default:
            return (0, res, free), tried, last
        if frac:   # M as deep as the mean-point check allows (DEFAULT_DEPTH_ANGLE_MARGIN)
            try:
                dev = _angle_deviation(blank, res.pinion_flank)
            except (ConvergenceError, GeometryError):
                dev = 0.0
            if dev > math.radians(CHECK_ANGLE_DEG):
                frac *= DEFAULT_DEPTH_ANGLE_MARGIN * math.radians(CHECK_ANGLE_DEG) / dev
                try:
                    res = synthesize(eta, frac, free)
                except (ConvergenceError, GeometryError) as err:
                    last = err
                    continue
        if judge(res, frac, free, eta) == 0 or tried >= max_syntheses:
            break
    if default and (best is not None or spare is not None) and (best is None or best[0] > 0):
        # no candidate kept the bearing inside: the other sets of solved settings at the mean pitch point
        # (DEFAULT_OTHER_SET_SYNTHESES); a local synthesis fixes the pinion to second order at M only, and the free
        # settings shape the rest of its flank, which decides where the contact runs at the ends of the mesh cycle
        budget = tried + max_other
        for eta in _ALL_DIRECTIONS:
            for free in names:
                if (eta, 0.0, free) in done or tried >= budget:
                    continue
                try:
                    res = synthesize(eta, 0.0, free)
                except (ConvergenceError, GeometryError) as err:
                    last = err
                    continue
                if judge(res, 0.0, free, eta) == 0:
                    return best, tried, last
    if default and mid > 0 and pitch_offs and (best is None or best[0] > 0):
        # still an edge contact: M toward the pinion's tip, as deep as the angle check allows (gearset/depth_rescue.py)
        from .depth_rescue import rescue_by_depth

        rescue_by_depth(pitch_offs, synthesize, lambda r: _angle_deviation(blank, r.pinion_flank), judge,
                        math.radians(CHECK_ANGLE_DEG), DEFAULT_DEPTH_ANGLE_MARGIN)
    return (best if best is not None else spare), tried, last
