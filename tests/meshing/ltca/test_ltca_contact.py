"""Loaded contact through the full loaded-TCA pipeline (TCA -> contact_positions -> run_ltca) with rigid teeth
(``rigid=True``: the contact flattening of the half-space term alone, no FE tooth bending), on the seed 001 pair
with the synthesized pinion (real flanks with their edges):

* at a position where one pair carries the load, the peak pressure matches Hertz (Johnson, Contact Mechanics,
  Eqs. (4.37)-(4.41)) for that contact's relative curvatures and that pair's normal force, within 5 %;
* refining the potential-contact grid 21 x 7 -> 41 x 15 -> 81 x 31 converges (< 3 % between the two finest);
* the loaded TE tends to the unloaded TE (that of TCA) as the torque tends to 0;
* an edge contact of TCA carries load, on the flank side of the edge only.
"""

import dataclasses

import numpy as np
import pytest

from _meshing_helpers import seed001_synthesized_pair

from spiralbevel.meshing.ellipse import hertz_peak_pressure
from spiralbevel.meshing.ltca import contact_modulus, ltca_model
from spiralbevel.meshing.ltca.ltca import ContactPosition
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_result import ContactStatus

TORQUE = 50e3  # N mm, about the approach torque of this pair (47.5 N m)


@pytest.fixture(scope="module")
def pair_tca():
    c1, c2, kin = seed001_synthesized_pair()
    tca = solve_tca(c1, c2, kin, n_positions=21, start=np.r_[c1.reference_params, c2.reference_params, 0.0])
    return c1, c2, kin, tca


def _single(model, i, j):
    """The model reduced to position i with pair j alone (the others out of mesh): a one-pair contact."""
    pos = model.positions[i]
    pairs = [pc if q == j else None for q, pc in enumerate(pos.pairs)]
    return dataclasses.replace(model, positions=[ContactPosition(pos.pinion_angle, pairs)])


def test_single_pair_peak_pressure_is_hertz_and_converges(pair_tca):
    c1, c2, kin, tca = pair_tca
    i = len(tca.phi1) // 2
    j = int(tca.pair[i])
    assert tca.status[i] == ContactStatus.OK
    estar = contact_modulus()
    errs, peaks = [], []
    for grid in ((21, 7), (41, 15), (81, 31)):
        model = _single(ltca_model(c1, c2, kin, tca, rigid=True, grid=grid), i, j)
        r = model.run(TORQUE, approach_target=None)
        assert r.load_share[0, j] == pytest.approx(1.0)
        p0, _ = hertz_peak_pressure(tca.relative_curvatures[i], r.pair_force[0, j], estar)
        peaks.append(float(r.max_pressure[0]))
        errs.append(peaks[-1] / p0 - 1.0)
    # Hertz within 5 % on the two finer grids (21 x 7 puts 3.5 cells across the contact width: about 7 %)
    assert max(abs(e) for e in errs[1:]) < 0.05, errs
    # grid convergence: the change between the two finest grids is below 3 % and smaller than the change before
    d1, d2 = abs(peaks[1] / peaks[0] - 1), abs(peaks[2] / peaks[1] - 1)
    assert d2 < 0.03 and d2 < d1, (peaks, d1, d2)


def test_rigid_loaded_te_tends_to_unloaded_te(pair_tca):
    """rigid=True: loaded TE -> unloaded TE as T -> 0, and the unloaded TE is the TCA's. (At loads whose contact is
    smaller than one cell the discrete approach is linear in the load, not Hertz's T^(2/3).)"""
    c1, c2, kin, tca = pair_tca
    model = ltca_model(c1, c2, kin, tca, rigid=True)
    lo, hi = model.run(1.0, approach_target=None), model.run(1e3, approach_target=None)
    np.testing.assert_allclose(lo.te_unloaded, tca.te_arcsec, atol=1e-9)
    d_lo = np.max(np.abs(lo.te_loaded - lo.te_unloaded))
    d_hi = np.max(np.abs(hi.te_loaded - hi.te_unloaded))
    assert 0 < d_lo < 1e-3  # arcsec at 1 N mm
    assert d_hi / d_lo > 100.0  # 1000 x the torque: at least (1000)^(2/3) x the deflection


def test_edge_contact_carries_load_on_the_flank_side(pair_tca):
    """At a position where TCA reports an edge contact (the gear's top edge on the pinion flank), the loaded contact
    is there, and every loaded potential-contact point lies on both real flanks."""
    c1, c2, kin, tca = pair_tca
    i = int(np.flatnonzero(tca.status == ContactStatus.EDGE)[0])
    j = int(tca.pair[i])
    model = _single(ltca_model(c1, c2, kin, tca, rigid=True, grid=(41, 15)), i, j)
    r = model.run(TORQUE, approach_target=None)
    assert r.pair_force[0, j] > 0 and r.load_share[0, j] == pytest.approx(1.0)
    # the potential-contact points beyond the edge (no tooth surface there) were dropped, and the load sits on the
    # points kept
    n_grid = 41 * 15
    assert 0 < len(r.points[0]) < n_grid
    assert np.sum(r.force[0] > 0) >= 3
