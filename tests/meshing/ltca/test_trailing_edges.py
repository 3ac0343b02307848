"""Trailing edge contacts in the loaded TCA (ISO 23509 Sample 2 hypoid, the bundled example's drive side).

The unloaded TCA follows an edge contact only where it leads; on the exit side of this drive flank the surface
contact of a pair runs off its flank while another pair leads, and the TCA leaves that pair without contact. Under
load the leading pair lags by about 25 arcsec and the exiting pair, whose real flanks trail by only 5 to 20 arcsec
there, touches along its edge. Without those contacts the loaded TE jumped by 6 arcsec at the pair handover (one
pair suddenly carrying the whole load). Checked against the brute-force oracle (tests/meshing/_contact_oracle.py):
the first touch of the real flanks of every pair, independent of the TCA and of the edge solver."""

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.ltca import ltca_model
from spiralbevel.meshing.ltca.trailing import follow_trailing_edges
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_result import ARCSEC, ContactStatus

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _contact_oracle import Oracle, first_touch_phi2, grid_box  # noqa: E402

#: agreement of the followed edge contacts with the oracle: both solve the touch to 1e-10 mm; the oracle's zooming
#: grids locate the first touch to about 1e-3 arcsec (as in tests/meshing/test_hypoid_tca.py)
TOL_ARCSEC = 0.1
TORQUE = 8e4  # N mm, the example's [ltca] torque


@pytest.fixture(scope="module")
def case():
    from spiralbevel.gearset.gearset import GearSet

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")      # Sample 2's own face width warning
        gs = GearSet.from_design("iso23509_sample2_hypoid")
        pair = gs.pair("drive")
    c1, c2, kin = pair.pinion, pair.gear, pair.kinematics
    tca = solve_tca(c1, c2, kin, n_positions=21, start=pair.start)
    return pair, tca


def _oracle_te(pair, tca, idx):
    """TE (arcsec) of the first touch of the real flanks of every pair at the positions ``idx``, by the oracle:
    relative to the TCA's pair 0 (a surface contact over the whole cycle), whose TE the oracle reproduces."""
    c1, c2, kin = pair.pinion, pair.gear, pair.kinematics
    o = Oracle(c1, c2, grid_box(c1), grid_box(c2), kin.z1, kin.z2, kin.axes(None))
    P = np.asarray(tca.pairs)
    p2 = first_touch_phi2(o, tca, idx)
    j0 = int(np.flatnonzero(P == 0)[0])
    # te = drive (-(phi2 - phi20) - ...): at one position the TE differences are -drive x the phi2 differences
    return tca.te_pairs[idx, j0][:, None] / ARCSEC - tca.drive_sign * (p2 - p2[:, j0:j0 + 1]) / ARCSEC


IDX = np.array([2, 3, 5, 10])   # the exit of pair +1 (lost by the TCA) and the mean position


@pytest.fixture(scope="module")
def oracle_te(case):
    return _oracle_te(*case, IDX)


def test_the_tca_leaves_the_exiting_pair_without_contact(case):
    """The premise: the unloaded TCA does not follow the trailing edge contact of pair +1."""
    _, tca = case
    j = int(np.flatnonzero(np.asarray(tca.pairs) == 1)[0])
    assert np.all(tca.status_pairs[IDX[:3], j] == ContactStatus.NO_CONTACT)


def test_followed_edge_contacts_are_the_real_first_touch(case, oracle_te):
    pair, tca = case
    t2, followed = follow_trailing_edges(ContactProblem(pair.pinion, pair.gear, pair.kinematics, None), tca)
    ref = oracle_te
    got = t2.te_pairs[IDX] / ARCSEC
    assert np.all(followed[IDX] == (tca.status_pairs[IDX] == ContactStatus.NO_CONTACT))
    assert np.all(t2.status_pairs[followed] == ContactStatus.EDGE)
    assert np.all(np.isfinite(got)) and np.max(np.abs(got - ref)) < TOL_ARCSEC, np.round(got - ref, 4)
    # the contacts the TCA found are kept as they were
    keep = ~followed
    np.testing.assert_array_equal(t2.te_pairs[keep], np.asarray(tca.te_pairs)[keep])


@pytest.fixture(scope="module")
def rigid(case):
    pair, tca = case
    return ltca_model(pair.pinion, pair.gear, pair.kinematics, tca, rigid=True, grid=(15, 5))


def test_every_pair_within_the_loaded_lag_carries_load(case, oracle_te, rigid):
    """Complementarity against the oracle: at the loaded TE, a pair whose real flanks would overlap (its first
    touch leads the loaded TE) carries load, a pair that trails it carries none."""
    pair, tca = case
    m = rigid
    res = m.run(TORQUE, approach_target=None)
    ref = oracle_te
    for a, i in enumerate(IDX):
        for j in range(len(tca.pairs)):
            gap = ref[a, j] - res.te_loaded[i]            # > 0: the pair would overlap at the loaded lag
            if abs(gap) < 1.0:                             # too near the threshold to decide at this grid
                continue
            assert (res.load_share[i, j] > 0) == (gap > 0), (i, j, ref[a, j], res.te_loaded[i])
    # and the loaded TE has no jump at the handover: its range stays below a quarter of the unloaded one
    assert np.ptp(res.te_loaded) < 0.25 * np.ptp(tca.te_arcsec)


def test_a_lag_beyond_the_followed_window_warns(rigid):
    """Pairs are followed up to 1 % of the gear pitch behind the leading one (309 arcsec here); a torque whose lag
    exceeds that (about 25 arcsec at 80 N m, growing as T^(2/3) with rigid teeth) is flagged, not silently wrong."""
    from spiralbevel.errors import SpiralBevelWarning

    assert rigid.trailing_window == pytest.approx(0.01 * 2 * np.pi / 42)
    with pytest.warns(SpiralBevelWarning, match="trailing edge contacts"):
        rigid.run(1e7, approach_target=None)
