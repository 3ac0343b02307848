"""Loaded TCA of a hypoid pair (ISO 23509 Sample 2, pinion by hypoid local synthesis) in the crossed-axes frame, with
contact flattening only (rigid teeth, no FE compliance): the unloaded limit is the TCA, the contact forces balance
the torque about the hypoid wheel axis at every position, and the loaded TE and the pressure grow with the torque."""

import math

import numpy as np
import pytest

from spiralbevel.meshing.hypoid_pair import hypoid_basic_flanks
from spiralbevel.meshing.ltca import ltca_model
from spiralbevel.meshing.synthesis.hypoid_local import tca_surfaces
from spiralbevel.meshing.tca import solve_tca
from _hypoid_sample2 import sample2_blank, sample2_concave_pinion

R = math.radians


@pytest.fixture(scope="module")
def model():
    blank = sample2_blank()
    flanks = hypoid_basic_flanks(blank)
    syn = sample2_concave_pinion(blank, flanks, R(40.0), 4.5, 8.0 * math.pi / 648000.0)
    c1, c2, start = tca_surfaces(syn)
    tca = solve_tca(c1, c2, syn.kinematics, n_positions=11, start=start)
    return syn, tca, ltca_model(c1, c2, syn.kinematics, tca, rigid=True, grid=(15, 5))


def test_small_torque_gives_the_tca(model):
    syn, tca, m = model
    np.testing.assert_array_equal(m.gear_origin, syn.kinematics.gear_origin)      # the hypoid assembly
    res = m.run(1e-3, approach_target=None)
    assert np.max(np.abs(res.te_loaded - tca.te_arcsec)) < 1e-3


def test_torque_balance_about_the_hypoid_wheel_axis(model):
    _, _, m = model
    T = 1e5                                                                    # N mm
    res = m.run(T, approach_target=None)
    for i in range(len(res.force)):
        n = np.array([m.positions[i].pairs[j].normal for j in res.pair_of_point[i]])
        h = np.abs(np.einsum("ni,i->n", np.cross(res.points[i] - m.gear_origin, n), m.gear_axis))
        assert np.all(res.force[i] >= 0)
        assert abs(res.force[i] @ h - T) < 1e-9 * T


def test_loaded_te_and_pressure_grow_with_torque(model):
    _, _, m = model
    a, b = m.run(1e5, approach_target=None), m.run(4e5, approach_target=None)
    assert np.all(b.te_loaded < a.te_loaded)
    assert b.peak_pressure > a.peak_pressure
