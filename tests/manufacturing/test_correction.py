"""Sensitivity matrix and corrective machine settings on the seed 001 flanks (round trips with known errors)."""

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.errors import ConvergenceError, DesignError
from spiralbevel.generation import generate_flank
from spiralbevel.machine import seed001_blank, seed001_settings
from spiralbevel.manufacturing.correction import (DEFAULT_PARAMETERS, PARAMETERS, apply_changes, correct_settings,
                                                  sensitivity_matrix)
from spiralbevel.manufacturing.measurement import measure_deviation, measurement_grid

KEYS = [(Member.GEAR, Side.CONVEX), (Member.PINION, Side.CONCAVE)]
ALL = tuple(PARAMETERS)
TRUE = {"radial_setting": 0.05, "cradle_angle": np.radians(0.01), "machine_root_angle": np.radians(-0.02)}


@pytest.fixture(scope="module")
def setup():
    b, table = seed001_blank(), seed001_settings()
    out = {}
    for key in KEYS:
        c, s = table[key]
        g = measurement_grid(generate_flank(c, s, b, *key))
        out[key] = (c, s, b, g, sensitivity_matrix(c, s, b, *key, g, parameters=ALL))
    return out


def _measured(c, s, b, key, g, changes):
    """The 'measured' part: cut with changed settings, measured on the nominal grid along the nominal normals."""
    return measure_deviation(generate_flank(*apply_changes(c, s, changes), b, *key), g)


@pytest.mark.parametrize("key", KEYS)
def test_sensitivity_matches_one_sided_recomputation(setup, key):
    """Central differences with re-location at the same (axial, radius) vs an independent measurement of flanks
    regenerated with one-sided changes h and 2h (normal-line intersection), Richardson-extrapolated to O(h^2)."""
    c, s, b, g, J = setup[key]
    for k, name in enumerate(ALL):
        h = 2 * PARAMETERS[name][3]
        d1 = _measured(c, s, b, key, g, {name: h}).ravel() / h
        d2 = _measured(c, s, b, key, g, {name: 2 * h}).ravel() / (2 * h)
        scale = np.max(np.abs(J[:, k]))
        assert scale > 0
        e1 = np.max(np.abs(d1 - J[:, k]))
        e2 = np.max(np.abs(2 * d1 - d2 - J[:, k]))
        assert e1 < 2e-3 * scale, name  # plain one-sided: O(h) error (measured <= 1e-3 relative)
        # extrapolated one-sided, O(h^2): agrees far better (exactly linear settings: to round-off)
        assert e2 < max(1e-2 * e1, 1e-8 * scale), name


@pytest.mark.parametrize("key", KEYS)
def test_sliding_base_equals_point_radius_on_straight_blade(setup, key):
    """Physics: moving the work toward the cutter by X_B shifts the straight-blade cone along its axis, the same
    surface as a point-radius change of s X_B tan(alpha) (s = +1 outer, -1 inner blade). The columns are parallel,
    and correct_settings must flag one of the two as not identifiable."""
    c, s, b, g, J = setup[key]
    jx, jr = J[:, ALL.index("sliding_base")], J[:, ALL.index("point_radius")]
    np.testing.assert_allclose(jx, c.sign * np.tan(c.blade_angle) * jr, rtol=1e-6)
    d = _measured(c, s, b, key, g, {"sliding_base": 0.02})
    res = correct_settings(c, s, b, *key, g, d, parameters=("radial_setting", "sliding_base", "point_radius"),
                           iterations=1)
    assert res.rank == 2 and len(res.not_identifiable) == 1
    assert res.not_identifiable[0] in ("sliding_base", "point_radius")
    assert res.condition_number > 1e8
    assert res.rms_after < 1e-3 * res.rms_before


@pytest.mark.parametrize("key", KEYS)
def test_round_trip_recovers_known_setting_errors(setup, key):
    c, s, b, g, J = setup[key]
    d = _measured(c, s, b, key, g, TRUE)
    names = tuple(TRUE)
    sub = J[:, [ALL.index(n) for n in names]]
    one = correct_settings(c, s, b, *key, g, d, parameters=names, iterations=1, sensitivity=sub)
    for n in names:  # one linear step: a few per cent (measured: <= 0.25 %)
        assert abs(one.identified[n] / TRUE[n] - 1) < 0.02, n
    assert one.rms_after < one.rms_before / 100
    assert one.rank == 3 and not one.not_identifiable and 50 < one.condition_number < 500
    two = correct_settings(c, s, b, *key, g, d, parameters=names, iterations=2, sensitivity=sub)
    for n in names:  # one chord Gauss-Newton step on the regenerated flank removes the nonlinearity
        assert abs(two.identified[n] / TRUE[n] - 1) < 1e-4, n
    assert two.rms_after < one.rms_after / 100
    # closed loop: the machine keeps its error; cutting with the corrected settings gives the nominal flank back
    c_new, s_new = apply_changes(two.cutter, two.settings, TRUE)
    after = measure_deviation(generate_flank(c_new, s_new, b, *key), g)
    assert np.sqrt(np.mean(after ** 2)) < 1e-3 * two.rms_before
    np.testing.assert_allclose(s_new.radial_setting, s.radial_setting, atol=1e-5)


def test_default_parameters_round_trip(setup):
    key = KEYS[1]
    c, s, b, g, J = setup[key]
    d = _measured(c, s, b, key, g, TRUE)
    res = correct_settings(c, s, b, *key, g, d)  # DEFAULT_PARAMETERS, 2 iterations
    assert res.parameters == DEFAULT_PARAMETERS and res.rank == len(DEFAULT_PARAMETERS)
    for n in TRUE:
        assert abs(res.identified[n] / TRUE[n] - 1) < 1e-3, n
    for n in set(DEFAULT_PARAMETERS) - set(TRUE):
        assert abs(res.identified[n]) < 1e-6, n  # no setting error where there was none
    assert res.rms_after < 1e-4 * res.rms_before


def test_noise_regularized_solution_is_stable(setup):
    """1 um measurement noise: the plain least-squares settings scatter (condition number ~600), the Tikhonov
    solution does not, and it still removes the true deviation down to the noise level."""
    key = KEYS[1]
    c, s, b, g, J = setup[key]
    d0 = _measured(c, s, b, key, g, TRUE)
    sub = J[:, [ALL.index(n) for n in DEFAULT_PARAMETERS]]
    colnorm = np.linalg.norm(sub, axis=0)
    sigma = 1e-3
    runs = {}
    for lam in (0.0, 1e-2):
        xs = []
        for seed in range(4):
            d = d0 + np.random.default_rng(seed).normal(0.0, sigma, d0.shape)
            r = correct_settings(c, s, b, *key, g, d, regularization=lam, iterations=1, sensitivity=sub)
            x = np.array([r.identified[n] for n in DEFAULT_PARAMETERS])
            xs.append(x)
            assert 0.5 * sigma < r.rms_after < 1.5 * sigma  # what is left is the noise
            true_left = d0.ravel() - sub @ x  # the deviation of the part, after the correction, without noise
            assert np.sqrt(np.mean(true_left ** 2)) < sigma
        runs[lam] = np.array(xs) * colnorm  # settings scaled to their flank effect, mm
    spread = {lam: np.max(np.ptp(v, axis=0)) for lam, v in runs.items()}
    assert spread[1e-2] < 0.1 * spread[0.0]


def test_unregularized_ill_conditioned_problem_is_reported(setup):
    """All eleven parameters (an exact dependency X_B ~ R_h, condition number ~1e11) without truncation or
    regularization: the noisy solution asks for absurd settings; the error says so and what to do."""
    key = KEYS[1]
    c, s, b, g, J = setup[key]
    d = _measured(c, s, b, key, g, TRUE) + np.random.default_rng(0).normal(0.0, 1e-3, g.shape)
    with pytest.raises(ConvergenceError, match="ill-conditioned"):
        correct_settings(c, s, b, *key, g, d, parameters=ALL, rcond=1e-15, iterations=1, sensitivity=J)
    res = correct_settings(c, s, b, *key, g, d, parameters=ALL, regularization=1e-2, iterations=1, sensitivity=J)
    assert res.rms_after < 1.5e-3 and res.condition_number > 1e8


def test_bad_input(setup):
    key = KEYS[0]
    c, s, b, g, J = setup[key]
    d = np.zeros(g.shape)
    with pytest.raises(DesignError, match="parameters"):
        sensitivity_matrix(c, s, b, *key, g, parameters=("radial_setting", "spiral_angle"))
    with pytest.raises(DesignError, match="parameters"):
        correct_settings(c, s, b, *key, g, d, parameters=("radial_setting", "radial_setting"))
    with pytest.raises(DesignError, match="measured_deviation"):
        correct_settings(c, s, b, *key, g, np.zeros((3, 3)))
    with pytest.raises(DesignError, match="regularization"):
        correct_settings(c, s, b, *key, g, d, regularization=-1.0)
    with pytest.raises(DesignError, match="iterations"):
        correct_settings(c, s, b, *key, g, d, iterations=0)
    with pytest.raises(DesignError, match="sensitivity"):
        correct_settings(c, s, b, *key, g, d, parameters=("radial_setting",), sensitivity=J)
    with pytest.raises(DesignError, match="steps"):
        sensitivity_matrix(c, s, b, *key, g, parameters=("radial_setting",), steps={"radial_setting": 0.0})
