"""The last stage of the default bearing search (gearset/depth_rescue.py): M moved toward the pinion's tip, as deep
as the mean-point angle check allows, when every candidate through the mean pitch point touches a flank edge.

16/87 at beta 9.6 deg (bench/bench_robustness.py 100 2, design 22), coast side: every path direction through the
pitch point runs onto the pinion's fillet near one end of the mesh cycle (2 to 7 of 41 TCA positions); with the
search's depth candidates the pinion's mean-point angles leave the 0.05 deg check. The rescue probes the deviation
once at a quarter of the middle of the working depth and synthesizes again at the depth where it is 0.8 of the check.
"""

import math

import pytest

from spiralbevel.conventions import Member
from spiralbevel.errors import ConvergenceError
from spiralbevel.gearset import depth_rescue as dr
from spiralbevel.gearset import facemilled as gfm
from spiralbevel.gearset.tca import run_pair_tca
from spiralbevel.generation.basic_settings_solve import flank_fit
from spiralbevel.meshing.tca_checks import parabolic_level
from _designs import DESIGN_16X87, coast_candidate_16x87
from _designs import developed as develop



def test_deepest_allowed_fraction_on_a_linear_deviation_law():
    # a deviation proportional to the depth (k per unit fraction): the scaled fraction lands on margin * check
    check, margin, k = math.radians(0.05), 0.8, math.radians(0.44)
    frac = dr.deepest_allowed_fraction(0.25, k * 0.25, check, margin)
    assert k * frac == pytest.approx(margin * check, rel=1e-12)
    # a probe already within the margin is kept as it is
    assert dr.deepest_allowed_fraction(0.25, 0.5 * margin * check, check, margin) == 0.25


class _Search:
    """Fake synthesis/judge: deviation k * fraction; only ``good`` keeps the bearing inside; ``fail`` does not
    converge."""

    def __init__(self, good, fail=()):
        self.calls, self.judged, self.good, self.fail = [], [], good, set(fail)

    def synthesize(self, eta, frac, free):
        self.calls.append((eta, frac, free))
        if eta in self.fail:
            raise ConvergenceError("no", 1, 1.0, None)
        return (eta, frac, free)

    @staticmethod
    def deviation(res):
        return math.radians(0.4) * res[1]

    def judge(self, res, frac, free):
        self.judged.append(res)
        return 0 if res[0] == self.good else 3


def test_rescue_tries_the_fewest_edge_positions_first_and_stops_at_the_first_inside():
    offs = {(0.0, "offset"): 5, (-55.0, "modified-roll"): 2, (40.0, "offset"): 0, (70.0, "offset"): 41,
            (-40.0, "offset"): 3}
    s = _Search(good=-40.0, fail=(-55.0,))
    check = math.radians(0.05)
    n = dr.rescue_by_depth(offs, s.synthesize, s.deviation, s.judge, check, 0.8)
    # -55 (2 off) first, fails to converge; then -40 (3 off): probe, scaled synthesis, inside -> stop; 0 deg (5 off)
    # is not tried; 40 deg (already inside) is not a candidate; 70 deg (41: no flank that meshes) would come last
    assert [c[0] for c in s.calls] == [-55.0, -40.0, -40.0]
    assert n == 3
    frac = s.judged[-1][1]
    assert s.deviation(s.judged[-1]) == pytest.approx(0.8 * check, rel=1e-12) and frac < dr.PROBE_FRACTION


def test_rescue_keeps_to_its_budget():
    offs = {(float(e), "offset"): 1 + i for i, e in enumerate((0, 20, -20, 40, -40, 55, -55))}
    s = _Search(good=None)
    assert dr.rescue_by_depth(offs, s.synthesize, s.deviation, s.judge, math.radians(0.05), 0.8, 5) == 4
    assert len(s.calls) == 4


@pytest.fixture(scope="module")
def developed():
    return develop(DESIGN_16X87)


def test_pitch_point_candidate_touches_the_pinion_fillet():
    # the reason for the rescue: the coast candidate with the fewest edge positions through the pitch point
    # (path -55 deg, modified roll free) runs onto the pinion's fillet
    blank, gear, res = coast_candidate_16x87()
    assert 0 < gfm.bearing_off_flank(blank, res.pinion_flank, gear.flank) < gfm._CHECK_POSITIONS


def test_rescued_coast_pair_meets_the_developed_pair_checks(developed):
    spec, blank, setups, synth = developed
    s1, s2 = gfm.PAIR_SIDES["coast"]
    pinion, gear = setups[(Member.PINION, s1)], setups[(Member.GEAR, s2)]
    # bearing inside both flanks: the search's 41-position TCA and the job's 21-position TCA of the report grids
    assert gfm.bearing_off_flank(blank, pinion.flank, gear.flank) == 0
    grids = {k: st.flank.grid(9, 5, curvature=False) for k, st in setups.items()}
    _, section, _ = run_pair_tca(blank, setups, grids, n_positions=21)
    sec = section["coast"]
    assert sec["edge_contact_positions_deg"] == [] and sec["no_contact_positions_deg"] == []
    # M moved off the pitch point (the deviation is nonzero), within the 0.05 deg check; 0.004 deg as
    # test_default_bearing_search.py: the curvature of the deviation's law over the depth
    f = flank_fit(blank, pinion.flank)
    dev = math.degrees(max(abs(f.pressure_angle - f.pressure_angle_design),
                           abs(f.spiral_angle - f.spiral_angle_design)))
    assert dev == pytest.approx(gfm.DEFAULT_DEPTH_ANGLE_MARGIN * gfm.CHECK_ANGLE_DEG, abs=0.004)
    assert dev <= gfm.CHECK_ANGLE_DEG
    # at the design TE level, and the TCA shows it (the acceptance's 10 %)
    assert synth["coast"].summary()["te_magnitude_arcsec"] == pytest.approx(8.0, rel=1e-9)
    level = parabolic_level([math.radians(p) for p in sec["pinion_rotation_deg"]], sec["transmission_error_arcsec"],
                            spec.gear_set.pinion_teeth)
    assert level == pytest.approx(8.0, rel=0.10)
