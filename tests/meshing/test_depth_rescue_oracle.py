"""The bearing judgement behind the default search's depth rescue (gearset/depth_rescue.py), checked by the
brute-force oracle (tests/meshing/_contact_oracle.py, independent of the library's TCA).

16/87 at beta 9.6 deg (bench/bench_robustness.py 100 2, design 22), coast side: the pinion synthesized through the
mean pitch point (path -55 deg, modified roll free) has its leading contact on the pinion's fillet/flank junction at
the start of the mesh cycle; with M 0.0755 mm below the gear's pitch line (the depth the rescue found: the mean-point
angle deviation at 0.8 of the 0.05 deg check) the leading contact is a surface contact inside both flanks at every
position. The oracle finds the same leading contact as the TCA at the cycle ends, where the edge was.
"""


import numpy as np
import pytest

from _contact_oracle import Oracle, grid_box, lead_deviation
from _designs import coast_candidate_16x87

from spiralbevel.meshing.generated_surface import phased_for_pair
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_result import ARCSEC, ContactStatus


#: depth (mm) of M below the gear's pitch line that the default search's rescue chose for the coast side (above)
DEPTH_MM = 0.0755
#: positions (of 41) compared with the oracle: the start of the cycle, where the pitch-point pinion touched its
#: fillet (positions 1 and 2), the mean contact, and the end of the cycle
POSITIONS = np.array([0, 1, 2, 3, 20, 39, 40])
#: the oracle's own accuracy is about 1e-5 arcsec (tests/meshing/test_tca_oracle.py); measured here: below 2e-6
TOL_ARCSEC = 1e-4


def _lead_deviation(c1, c2, kin, res, idx):
    """TCA minus oracle leading contact (arcsec) at positions idx (as test_tca_oracle.py)."""
    from spiralbevel.meshing.misalignment import Misalignment

    o = Oracle(c1, c2, grid_box(c1), grid_box(c2), kin.z1, kin.z2, Misalignment().axes(kin.shaft_angle))
    return lead_deviation(o, res, idx) / ARCSEC


def _coast_pair(depth):
    blank, gear, res = coast_candidate_16x87(depth)
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
