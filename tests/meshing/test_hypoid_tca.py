"""TCA of a hypoid pair (ISO 23509 Sample 2, basic settings of spiralbevel.meshing.hypoid_pair) in the crossed-axes
pair frame, against the brute-force oracle (tests/meshing/_contact_oracle.py, given the hypoid assembly axes): the
leading contact's gear rotation agrees to <= 0.1 arcsec (the oracle's own accuracy is ~1e-5 arcsec), on the drive
side (surface contact) and on the coast side (where the bearing of the unsynthesized pair runs onto a flank edge)."""

import math

import numpy as np
import pytest

from _contact_oracle import Oracle, grid_box, lead_deviation

from spiralbevel.conventions import Member, Side
from spiralbevel.meshing.hypoid_kinematics import HypoidPairKinematics
from spiralbevel.meshing.hypoid_pair import hypoid_basic_flanks, phased_for_hypoid_pair
from spiralbevel.meshing.misalignment import Misalignment
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_result import ARCSEC, ContactStatus
from _hypoid_sample2 import sample2_blank

R = math.radians
TOL_ARCSEC = 0.1


@pytest.fixture(scope="module")
def pair():
    blank = sample2_blank()
    return blank, hypoid_basic_flanks(blank), HypoidPairKinematics.from_blank(blank)


def _deviation(c1, c2, kin, res, mis, idx):
    """|lead_TCA - lead_oracle| arcsec at positions idx (lead = -drive * phi2 of the leading contact)."""
    o = Oracle(c1, c2, grid_box(c1), grid_box(c2), kin.z1, kin.z2, kin.axes(mis))
    return lead_deviation(o, res, idx) / ARCSEC


@pytest.mark.parametrize("pinion_side, mis", [(Side.CONCAVE, Misalignment()), (Side.CONVEX, Misalignment()),
                                              (Side.CONCAVE, Misalignment(offset=0.05, pinion_axial=0.03))])
def test_hypoid_tca_matches_brute_force(pair, pinion_side, mis):
    blank, flanks, kin = pair
    c1, c2 = phased_for_hypoid_pair(kin, blank, flanks[(Member.PINION, pinion_side)][2],
                                    flanks[(Member.GEAR, pinion_side.mate)][2])
    res = solve_tca(c1, c2, kin, misalignment=mis, n_positions=21,
                    start=np.r_[c1.reference_params, c2.reference_params, 0.0])
    n = len(res.phi1)
    e = np.flatnonzero(res.status == ContactStatus.EDGE)
    idx = np.unique(np.r_[np.arange(0, n, 5), e[::3]])
    d = _deviation(c1, c2, kin, res, mis, idx)
    assert np.all(np.isfinite(d)) and np.max(np.abs(d)) <= TOL_ARCSEC, (idx, np.round(d, 4))
    if mis.is_aligned:
        # the mean points meet at the pitch point at zero roll: zero transmission error there, a surface contact
        mid = n // 2
        assert res.status[mid] == ContactStatus.OK and abs(res.te_arcsec[mid]) < 1e-6
        if pinion_side is Side.CONCAVE:     # drive: a surface contact over the whole mesh cycle
            assert not e.size
