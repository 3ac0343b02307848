"""The default synthesis' slot rule (gearset/slot_open.py, ``facemilled._candidates``) on a design of the robustness
bench whose default pair once left no tooth space that a cutter fits, judged by an independent brute-force sweep of
the cutter (tests/gearset/test_slot_check.py, ``_swept_penetration``: opposite-flank points carried into the cutter
frame over the whole generating roll, no equation of meshing, no envelope).

26/61 at beta 3.6 deg (bench_robustness.py 100 2, design 31): both pinion sides synthesized, the drive (concave)
side first against the gear; the first coast (convex) candidate that keeps the bearing inside crosses the concave
side's cutter near the toe root, so that even at 0.2 of its derived point width (the floor of the refit) the concave
cutter's opposite blade cuts into the convex flank. The drive side's settings put that cutter's tip plane 2.14 mm below
the root cone, and measured from the convex flank's root edge (slot_intrusion.py) its opposite blade cuts that flank
whatever the coast candidate: the rule then has no candidate to prefer here. The default synthesis therefore puts such
a root back on the root cone (``pinion_fillet.raise_root``), and with it every cutter of the pair fits.
"""

import importlib.util
import math
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.gearset import slot_check as sc
from spiralbevel.gearset import pinion_fillet, slot_open
from spiralbevel.io.design_file import parse_design
from spiralbevel.job import facemilled as fm
from spiralbevel.job.blank import blank_from_design

_spec = importlib.util.spec_from_file_location("_slot_check_tests", Path(__file__).with_name("test_slot_check.py"))
_tsc = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_tsc)

#: bench_robustness.py 100 2, design 31 (the sample's values as the bench writes them)
DESIGN_26X61 = """
[gear_set]
pinion_teeth = 26
gear_teeth = 61
shaft_angle = 104.021
module = 4.182
face_width = 25.765
normal_pressure_angle = 20
mean_spiral_angle = 3.586
pinion_hand = "RH"
cutter_radius = 119.43
[flank]
kind = "face-milled"
"""

PINION_SIDES = (Side.CONVEX, Side.CONCAVE)


def _develop(monkeypatch=None):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        spec = parse_design(DESIGN_26X61)
        blank = blank_from_design(spec)
        if monkeypatch is not None:      # the search without the rule and without the root raise
            monkeypatch.setattr(slot_open, "slot_closed", lambda *a, **k: False)
            monkeypatch.setattr(pinion_fillet, "raise_root", lambda blank, res, dev=None: res)
        setups = fm.setup_flanks(spec, blank)
    return blank, setups


def _at_floor(setups, side):
    """The setups with the cutter of pinion ``side`` narrowed to the refit's floor (edge radius as the point holds)."""
    st = setups[(Member.PINION, side)]
    w = slot_open.SLOT_FLOOR * st.cutter.point_width
    a = st.cutter.blade_angle      # the largest edge radius a point w wide holds: rho (1 - sin a) / cos a = w / 2
    c = replace(st.cutter, point_width=w,
                edge_radius=min(st.cutter.edge_radius, 0.45 * w * math.cos(a) / (1.0 - math.sin(a))))
    out = dict(setups)
    out[(Member.PINION, side)] = replace(st, cutter=c)
    return out


@pytest.fixture(scope="module")
def without_rule():
    mp = pytest.MonkeyPatch()
    try:
        return _develop(mp)
    finally:
        mp.undo()


def test_rejected_candidate_closes_the_slot(without_rule):
    """Without the rule the concave cutter does not fit and no point width down to the floor does, by the check
    (``slot_closed``) and by the brute-force sweep at the floor width (measured 0.35 mm into the convex flank at the
    toe root, where the check's envelope says 0.04 mm: both well above the 0.0025 mm a refit leaves)."""
    blank, setups = without_rule
    pin = {s: setups[(Member.PINION, s)] for s in PINION_SIDES}
    assert not sc.slot_fit(blank, setups, Member.PINION, Side.CONCAVE).fits
    assert slot_open.slot_closed(blank, pin, {s: slot_open.SLOT_FLOOR for s in PINION_SIDES})
    assert _tsc._swept_penetration(blank, _at_floor(setups, Side.CONCAVE), Member.PINION, Side.CONCAVE) > 0.1


def test_default_pair_raises_the_drive_root_and_every_cutter_fits(without_rule):
    """The default synthesis (the rule and the root raise): the drive side is the same candidate as without them,
    its settings those of the candidate but the sliding base, moved by the depth at which the candidate cut the root
    below the root cone (2.14 mm, its root deviation; the blade shortened, ``pinion_fillet.raise_root``). With the
    root on the root cone the drive cutter's opposite blade no longer runs below the convex flank's root, and after the
    refit every cutter of the pair fits by the check, and the brute-force sweep agrees (below). This test once
    asserted the opposite: before the raise, the drive cutter cut the convex flank's root edge and fillet at every
    point width whatever the coast candidate (0.399 mm at the floor width by the check and the sweep), and the rule
    had nothing to rank (``test_rejected_candidate_closes_the_slot`` keeps that pair)."""
    from spiralbevel.generation.basic_settings_solve import root_deviation

    blank, setups = _develop()
    checks = sc.slot_checks(blank, setups)
    for k, res in checks.items():
        assert not isinstance(res, Exception) and res.fits, k
    _, old = without_rule
    k = (Member.PINION, Side.CONCAVE)
    new, raw = setups[k], old[k]
    depth = max(d for d in root_deviation(raw.flank) if d is not None)
    assert replace(new.settings, sliding_base=raw.settings.sliding_base) == raw.settings
    delta = new.settings.sliding_base - raw.settings.sliding_base
    # the raise is the depth of the tip line; root_deviation samples the fillet 2e-4 rho above the tip
    # (generation/basic_settings_solve.py), so the two agree to 1e-3 mm
    assert depth < -2.0 and delta == pytest.approx(depth, abs=1e-3)
    assert f"root raised {-delta:.3f} mm onto the root cone" in new.source
    assert abs(checks[k].tip_height) < 0.01
    # the brute-force sweep finds no cut beyond its resolution: its points on the convex flank lie ~0.05 mm apart
    # (tests/gearset/test_slot_check.py); measured 0.023 mm against the check's 0.0025 mm, where before the raise it
    # found 0.399 mm at the floor width
    assert _tsc._swept_penetration(blank, setups, *k) < 0.05


def test_clearance_side_does_not_decide_the_fit(without_rule):
    """A single-sided pinion blade (docs/report.md, "Spread blades or single-sided blades?") has its clearance corner
    where the spread-blade model has the opposite blade's tip, with a clearance side of the blade designer's choosing.
    The brute-force sweep at the floor width, with the clearance side at the convex flank's blade angle and turned
    by -5 deg (its edge radius as that point holds), finds a collision with both (measured 0.427 and 0.457 mm at the
    face station where the check finds the deepest cut, at the convex flank's root edge and fillet; the convex pinion's
    root now lowered onto the root cone): the tip corner, which runs below the convex flank's root, decides that the
    blade cuts; the clearance side changes only how deep (by 0.03 mm here)."""
    blank, setups = without_rule
    st = _at_floor(setups, Side.CONCAVE)
    b = st[(Member.PINION, Side.CONVEX)]
    depth = []
    val, _, _, _, (under, _, _) = sc.intrusion_field(blank, st, Member.PINION, Side.CONCAVE, with_root_edge=True)
    station = int(np.argmax(np.maximum(val.max(1), under.max(1))))      # the same face station for both runs
    for turn in (0.0, -5.0):
        a = b.cutter.blade_angle + math.radians(turn)   # edge radius as the turned blade's point holds (_at_floor)
        rho = min(b.cutter.edge_radius, 0.45 * b.cutter.point_width * math.cos(a) / (1.0 - math.sin(a)))
        st[(Member.PINION, Side.CONVEX)] = replace(b, cutter=replace(b.cutter, blade_angle=a, edge_radius=rho))
        depth.append(_tsc._swept_penetration(blank, st, Member.PINION, Side.CONCAVE, station=station))
    assert min(depth) > 0.3
