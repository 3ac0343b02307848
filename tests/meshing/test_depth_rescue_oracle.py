"""The bearing judgement behind the default search's depth rescue (gearset/depth_rescue.py), checked by the
brute-force oracle (tests/meshing/_contact_oracle.py, independent of the library's TCA).

16/87 at beta 9.6 deg (bench/bench_robustness.py 100 2, design 22), coast side: the pinion synthesized through the
mean pitch point (path -55 deg, modified roll free) has its leading contact on the pinion's fillet/flank junction at
the start of the mesh cycle; with M 0.0755 mm below the gear's pitch line (the depth the rescue found: the mean-point
angle deviation at 0.8 of the 0.05 deg check) the leading contact is a surface contact inside both flanks at every
position. The oracle finds the same leading contact as the TCA at the cycle ends, where the edge was.
"""

import math
import warnings

import numpy as np
import pytest

from _contact_oracle import Oracle

from spiralbevel.conventions import Member
from spiralbevel.meshing import synthesis as syn
from spiralbevel.meshing.generated_surface import phased_for_pair
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_result import ARCSEC, ContactStatus

DESIGN = """
title = "sample"
[gear_set]
pinion_teeth = 16
gear_teeth = 87
shaft_angle = 66.706
module = 1.723
face_width = 24.312
normal_pressure_angle = 20
mean_spiral_angle = 9.614
pinion_hand = "LH"
cutter_radius = 61.48
[flank]
kind = "face-milled"
"""

#: depth (mm) of M below the gear's pitch line that the default search's rescue chose for the coast side (above)
DEPTH_MM = 0.0755
#: positions (of 41) compared with the oracle: the start of the cycle, where the pitch-point pinion touched its
#: fillet (positions 1 and 2), the mean contact, and the end of the cycle
POSITIONS = np.array([0, 1, 2, 3, 20, 39, 40])
#: the oracle's own accuracy is about 1e-5 arcsec (tests/meshing/test_tca_oracle.py); measured here: below 2e-6
TOL_ARCSEC = 1e-4


def _box(flank):
    """Parameter box (2, 2) of the phased surface's real flank, from the flank's grid, widened by 2 %."""
    g = flank.flank.grid(31, 15, curvature=False)
    p0 = flank.cutter_angle(g.theta, g.psi_c)
    lo, hi = np.array([p0.min(), g.psi_c.min()]), np.array([p0.max(), g.psi_c.max()])
    d = 0.02 * (hi - lo)
    return np.stack([lo - d, hi + d], 1)


def _lead_deviation(c1, c2, kin, res, idx):
    """TCA minus oracle leading contact (arcsec) at positions idx (as test_tca_oracle.py)."""
    from spiralbevel.meshing.misalignment import Misalignment

    o = Oracle(c1, c2, _box(c1), _box(c2), kin.z1, kin.z2, Misalignment().axes(kin.shaft_angle))
    P = np.asarray(res.pairs)
    phi = res.phi1[idx][:, None] + 2 * np.pi * P / kin.z1
    p2e, _ = o.first_touch(phi.ravel(), res.drive_sign, (-kin.z1 / kin.z2 * phi.ravel(), c1.reference_params,
                                                          c2.reference_params))
    p2 = p2e.reshape(phi.shape) + 2 * np.pi * P / kin.z2
    lead = np.max(np.where(np.isfinite(p2), -res.drive_sign * p2, -np.inf), axis=1)
    return (-res.drive_sign * res.phi2[idx] - lead) / ARCSEC


def _coast_pair(depth):
    from spiralbevel.gearset import facemilled as gfm
    from spiralbevel.io.design_file import parse_design
    from spiralbevel.job.blank import blank_from_design

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        spec = parse_design(DESIGN)
        blank = blank_from_design(spec)
        basic = gfm._basic_setups(spec, blank)
    s1, s2 = gfm.PAIR_SIDES["coast"]
    gear, pin = basic[(Member.GEAR, s2)], basic[(Member.PINION, s1)]
    b = float(blank.b2)
    res = syn.synthesize_pinion(gear.cutter, gear.settings, blank, side=s1, eta=math.radians(-55.0),
                                semi_major_axis=0.15 * b, te_magnitude=8.0 * ARCSEC,
                                approach=gfm.DEFAULT_SYNTHESIS["approach_fraction"] * b, free=syn.FREE_MODIFIED_ROLL,
                                depth=depth, pinion_cutter_hint=pin.cutter, pinion_settings_hint=pin.settings)
    c1, c2 = phased_for_pair(res.pinion_flank, gear.flank)
    return c1, c2, BevelPairKinematics(blank.Sigma, blank.z1, blank.z2)


@pytest.mark.parametrize("depth, inside", [(0.0, False), (DEPTH_MM, True)])
def test_leading_contact_at_the_cycle_ends_matches_brute_force(depth, inside):
    c1, c2, kin = _coast_pair(depth)
    res = solve_tca(c1, c2, kin, n_positions=41, start=np.r_[c1.reference_params, c2.reference_params, 0.0])
    edge = res.status == ContactStatus.EDGE
    if inside:
        assert not edge.any() and np.all(np.isfinite(res.te)), np.flatnonzero(edge)
    else:   # the pitch-point pinion: its fillet junction leads at the start of the cycle
        kinds = {e[0]: e[2:] for e in res.edges}
        assert edge[1] and kinds[1] == ("pinion", "fillet"), kinds
    d = _lead_deviation(c1, c2, kin, res, POSITIONS)
    assert np.all(np.isfinite(d)) and np.max(np.abs(d)) <= TOL_ARCSEC, (POSITIONS, d, res.status[POSITIONS])
