"""The default pair keeps the bearing its search verified through the point-width refit (gearset/slot_refit.py).

10/54 at beta 1.9 deg (bench/bench_robustness.py 40 1, design 31): the drive pinion candidate through the mean pitch
point (path 0 deg, blade fixed) keeps the bearing inside; against the coast pinion side its derived point width
(6.13 mm) cuts into the coast flank, and the width that fits (1.58 mm) holds only a third of the edge radius. The
flank generated with that smaller edge radius puts the contact off the flanks at 19 of 41 positions. The search
judges a candidate after the refit it will get (``gearset.refit_bearing.off_after_refit``); the whole 10/54 run
(about 20 s of CPU) is left to the bench.
"""

import math
import warnings

import pytest

from spiralbevel.conventions import Member
from spiralbevel.gearset import facemilled as gfm
from spiralbevel.gearset.refit_bearing import off_after_refit
from spiralbevel.gearset.slot_blade import _edge_limit
from spiralbevel.gearset.slot_intrusion import SLOT_FIT_MM, slot_fit
from spiralbevel.gearset.slot_refit import fit_point_widths, refit_side
from spiralbevel.generation.flank import generate_flank
from spiralbevel.io.design_file import parse_design
from spiralbevel.job.blank import blank_from_design
from spiralbevel.machine.default_cutter import EDGE_RADIUS_FILL
from spiralbevel.meshing import synthesis as syn
from spiralbevel.meshing.tca_result import ARCSEC

#: bench_robustness.py 40 1, design 31, as the bench writes it
DESIGN_10X54 = """
title = "sample"
[gear_set]
pinion_teeth = 10
gear_teeth = 54
shaft_angle = 79.000
module = 10.088
face_width = 46.459
normal_pressure_angle = 20
mean_spiral_angle = 1.944
pinion_hand = "RH"
cutter_radius = 292.34
[flank]
kind = "face-milled"
"""


def _synthesize(blank, basic, name):
    s1, s2 = gfm.PAIR_SIDES[name]
    gear, pin = basic[(Member.GEAR, s2)], basic[(Member.PINION, s1)]
    b = float(blank.b2)
    res = syn.synthesize_pinion(gear.cutter, gear.settings, blank, side=s1, eta=0.0, semi_major_axis=0.15 * b,
                                te_magnitude=8.0 * ARCSEC, approach=gfm.DEFAULT_SYNTHESIS["approach_fraction"] * b,
                                free=syn.FREE_FIXED_BLADE, pinion_cutter_hint=pin.cutter,
                                pinion_settings_hint=pin.settings)
    return res, gear, gfm.FlankSetup(Member.PINION, s1, res.pinion_cutter, res.pinion_settings, res.pinion_flank, "")


@pytest.fixture(scope="module")
def pair():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        spec = parse_design(DESIGN_10X54)
        blank = blank_from_design(spec)
        basic = gfm._basic_setups(spec, blank)
        drive, gear, drive_setup = _synthesize(blank, basic, "drive")
        _, _, coast_setup = _synthesize(blank, basic, "coast")
    return spec, blank, drive, gear, drive_setup, coast_setup


def test_the_refit_that_shrinks_the_edge_radius_moves_the_bearing_and_the_search_sees_it(pair):
    spec, blank, drive, gear, drive_setup, coast_setup = pair
    s1 = drive_setup.side
    setups = {(Member.PINION, s1): drive_setup, (Member.PINION, coast_setup.side): coast_setup}
    # as synthesized, the candidate keeps the bearing inside (what the search verified before this check)
    assert gfm.bearing_off_flank(blank, drive.pinion_flank, gear.flank) == 0
    c = drive.pinion_cutter
    new, flank = refit_side(blank, setups, Member.PINION, s1)
    # the derived width cuts into the coast flank, the refitted one passes the slot check (its tolerance; the
    # refit aims at SLOT_FIT_MM below it with the rows it solved once)
    assert slot_fit(blank, setups, Member.PINION, s1).intrusion > SLOT_FIT_MM
    assert slot_fit(blank, setups, Member.PINION, s1, new.point_width).fits
    assert new.point_width < 0.3 * c.point_width
    # the edge radius is what the narrow point holds, well below the derived one: the flank is generated again
    assert new.edge_radius == pytest.approx(EDGE_RADIUS_FILL * _edge_limit(new.point_width, c.blade_angle), rel=1e-12)
    assert new.edge_radius < 0.5 * c.edge_radius and flank is not drive.pinion_flank
    # ... and that flank is the one the refitted cutter generates with the candidate's settings (the pair reported
    # is the pair checked): a second generation, compared on the report's grid to 1e-9 mm
    again = generate_flank(new, drive.pinion_settings, blank, Member.PINION, s1)
    g1, g2 = flank.grid(9, 5, curvature=False), again.grid(9, 5, curvature=False)
    assert max(abs(float(a) - float(b)) for a, b in zip(g1.points.ravel(), g2.points.ravel())) < 1e-9
    # the contact now runs onto the regenerated fillet at the ends of the mesh cycle, and the search's judge of the
    # candidate reports the positions after the refit, not the verified 0
    off = gfm.bearing_off_flank(blank, flank, gear.flank)
    assert off > 0
    assert off_after_refit(blank, drive, gear, s1, coast_setup) == off
    # the refit the pair then gets is this one (its first pass; the coast side fits, so no second pass changes it)
    fitted = dict(setups)
    fit_point_widths(spec, blank, fitted)
    assert fitted[(Member.PINION, s1)].cutter.point_width == new.point_width
    assert math.isclose(fitted[(Member.PINION, s1)].cutter.edge_radius, new.edge_radius, rel_tol=0, abs_tol=0)
