"""Multi-point control of a hypoid pair (spiralbevel.meshing.synthesis.hypoid_multipoint) on ISO 23509 Sample 2: the
drive pinion by hypoid local synthesis (eta = 6 deg, a = 3.7 mm, 6 arcsec), its blank offset varied with the cradle
angle so that the TE follows the predesigned fourth-order CMC (seed 001 Steps 1-4) at control points, in the
crossed-axes pair frame.

Independent checks: the TE at the control points is measured again by the TCA engine (``solve_tca``, the contact of
the two generated flanks in the offset assembly of ``HypoidPairKinematics.axes``, not the compiled 6 x 6 systems), the
TCA of the controlled pair agrees with the brute-force oracle (tests/meshing/_contact_oracle.py), the pair of the
opposite hands is the mirror image, and with zero offset the hypoid path reproduces the spiral bevel control."""

import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from spiralbevel._core.multipoint_newton import _lu_step
from spiralbevel.conventions import Member, Side
from spiralbevel.design.blank import BlankInput, compute_blank
from spiralbevel.meshing.hypoid_kinematics import HypoidPairKinematics
from spiralbevel.meshing.hypoid_pair import hypoid_basic_flanks
from spiralbevel.meshing.motion_curves import seed001_cmc
from spiralbevel.meshing.synthesis.cmc_design import active_range
from spiralbevel.meshing.synthesis.hypoid_local import HypoidSynthesis, synthesize_hypoid_pinion
from spiralbevel.meshing.synthesis.hypoid_multipoint import (as_multipoint_synthesis, hypoid_multipoint_control,
                                                             hypoid_multipoint_tca, multipoint_surfaces)
from spiralbevel.meshing.synthesis.multipoint import multipoint_control
from spiralbevel.meshing.tca_result import ARCSEC

sys.path.insert(0, str(Path(__file__).parents[1]))
sys.path.insert(0, str(Path(__file__).parents[2]))
from _contact_oracle import Oracle, grid_box, lead_deviation  # noqa: E402
from _hypoid_sample2 import SAMPLE2  # noqa: E402

R = math.radians
ETA, A, TE = R(6.0), 3.7, 6.0 * ARCSEC
Z1 = SAMPLE2["z1"]
T = 2 * math.pi / Z1
N_POS = 25                                   # TCA positions: x = -T/2 + k T/24
GRID = np.linspace(-T / 2, T / 2, N_POS)
TOL = 1e-9                                   # tol_abs of Eq. (17), rad (the default of multipoint_control)


def _synthesis(hand="LH"):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")      # Sample 2's own face width warning
        blank = compute_blank(BlankInput(**SAMPLE2, hand1=hand))
    flanks = hypoid_basic_flanks(blank)
    c, s, _, _ = flanks[(Member.PINION, Side.CONCAVE)]
    return synthesize_hypoid_pinion(flanks[(Member.GEAR, Side.CONVEX)][2], c, s, blank, side=Side.CONCAVE, eta=ETA,
                                    semi_major_axis=A, te_magnitude=TE)


@pytest.fixture(scope="module")
def synth():
    return _synthesis()


@pytest.fixture(scope="module")
def cmc():
    return seed001_cmc(TE, Z1)


@pytest.fixture(scope="module")
def controlled(synth, cmc):
    lo, hi = active_range(as_multipoint_synthesis(synth))
    x = GRID[(GRID >= lo) & (GRID <= hi)][::3]           # control points on the TCA grid
    r = hypoid_multipoint_control(synth, cmc, x, interpolation="spline")
    return r, hypoid_multipoint_tca(r, n_positions=N_POS)


def test_control_point_te_equals_the_design_curve(controlled, synth):
    r, tca = controlled
    assert synth.kinematics.offset != 0.0 and r.synthesis.mean.kinematics is synth.kinematics
    assert r.control_points.size >= 4 and r.control_points.min() < 0 < r.control_points.max()
    assert np.all(r.control_point_errors <= TOL)         # measured by ContactProblem on the regenerated flank
    assert r.offsets[r.mean_index] == r.law.base == synth.pinion_settings.blank_offset
    np.testing.assert_allclose(r.law(r.psi_c1), r.offsets, atol=1e-13)
    d = r.offset_increments
    assert 0 < np.max(np.abs(d)) < 1e-2                  # a few um (1.5 um measured): a correction, not a new design
    # the TCA engine over the whole cycle (three pairs, real flanks) meets the curve at the control points
    x = tca.phi1 - tca.phi1_mean
    k0 = list(tca.pairs).index(0)
    idx = [int(np.argmin(np.abs(x - c))) for c in r.control_points]
    np.testing.assert_allclose(x[idx], r.control_points, atol=1e-15)
    np.testing.assert_allclose(tca.te_pairs[idx, k0], r.target, atol=TOL)


def test_controlled_tca_matches_brute_force(controlled):
    r, res = controlled
    pin, gear, _ = multipoint_surfaces(r)
    kin = r.synthesis.mean.kinematics

    o = Oracle(pin, gear, grid_box(pin), grid_box(gear), kin.z1, kin.z2, kin.axes())
    idx = np.array([0, 3, N_POS // 2, N_POS - 8])      # 0: the end of the cycle
    d = lead_deviation(o, res, idx) / ARCSEC
    # the oracle's own accuracy is ~1e-5 arcsec (tests/meshing/test_hypoid_tca.py); 0.1 arcsec as there
    assert np.all(np.isfinite(d)) and np.max(np.abs(d)) <= 0.1, np.round(d, 5)


def test_mirror_of_hands(synth, cmc):
    """Right-hand pinion, left-hand wheel (E = +a): the mirror image y -> -y turns both rotations the other way, so the
    pair controlled to CMC(-x) at the points -x_k has the same blank offsets at the mirrored points."""
    other = _synthesis("RH")
    assert other.kinematics.offset == -synth.kinematics.offset != 0.0
    x = np.array([-0.12, 0.08])
    a = hypoid_multipoint_control(synth, cmc, x, interpolation="polynomial")
    b = hypoid_multipoint_control(other, lambda v: cmc(-np.asarray(v)), -x, interpolation="polynomial")
    np.testing.assert_allclose(b.control_points[::-1], -a.control_points, atol=0)
    # both syntheses agree to ~1e-9 mm in the settings (test_hypoid_synthesis.py), the offsets then to ~1e-10 mm
    np.testing.assert_allclose(b.offsets[::-1], a.offsets, atol=1e-8)
    np.testing.assert_allclose(b.target[::-1], a.target, atol=1e-15)
    assert np.all(a.control_point_errors <= TOL) and np.all(b.control_point_errors <= TOL)
    _check_universal_generator(a)


def _check_universal_generator(r):
    """The polynomial law is the universal generator's vertical motion: the controlled pinion generated by
    ``UniversalGenerator`` (a second parametrization: 4 x 4 chain, complex-step derivative) with the law's
    coefficients as vertical-motion polynomial passes through the control-point contacts of the flank."""
    from spiralbevel.machine.universal import UniversalGenerator, UniversalSettings

    fl = r.pinion_flank
    us = UniversalSettings.from_machine_settings(r.pinion_settings)
    assert len(us.vertical_motion) == r.control_points.size - 1 and any(us.vertical_motion)
    u, psi = r.pinion_params[:, 0], r.pinion_params[:, 1]
    ref = fl.evaluate(u, psi, curvature=False)
    got = UniversalGenerator(fl.cutter, us, fl.hand).evaluate(u, psi)
    # both solve the equation of meshing to round-off: measured ~1e-12 mm apart
    np.testing.assert_allclose(got.points, ref.points, rtol=0, atol=1e-9)
    np.testing.assert_allclose(got.normals, ref.normals, rtol=0, atol=1e-9)


def test_zero_offset_reproduces_the_spiral_bevel_control(synth_pos):
    """The seed 001 pair through the hypoid path (a HypoidSynthesis with HypoidPairKinematics at E = 0, through
    ``as_multipoint_synthesis``): the same control to round-off."""
    kin = synth_pos.mean.kinematics
    hyp = HypoidSynthesis(
        pinion_cutter=synth_pos.pinion_cutter, pinion_settings=synth_pos.pinion_settings,
        pinion_flank=synth_pos.pinion_flank, gear_flank=synth_pos.gear_flank,
        kinematics=HypoidPairKinematics(kin.shaft_angle, kin.z1, kin.z2, offset=0.0),
        point=synth_pos.mean.point, normal=synth_pos.mean.normal, phi1_mean=synth_pos.phi1_mean,
        phi2_mean=synth_pos.phi2_mean, pinion_params=synth_pos.pinion_params, relative_tensor=np.eye(3),
        semi_axes=np.ones(2), eta=0.0, path_gear=np.zeros(3), path_speed=0.0, m21_prime=0.0, approach=0.0,
        drive_sign=synth_pos.mean.drive_sign, iterations=0, residual=0.0)
    np.testing.assert_array_equal(as_multipoint_synthesis(hyp).mean.gear_params, synth_pos.mean.gear_params)
    cmc = seed001_cmc(3.0 * ARCSEC, kin.z1)
    x = np.array([-0.08, 0.06])
    a = multipoint_control(synth_pos, cmc, x, interpolation="polynomial")
    b = hypoid_multipoint_control(hyp, cmc, x, interpolation="polynomial")
    # round-off: the same compiled systems with o1 = o2 = 0 (measured: identical bits)
    np.testing.assert_allclose(b.offsets, a.offsets, rtol=0, atol=1e-13)
    np.testing.assert_allclose(b.psi_c1, a.psi_c1, rtol=0, atol=1e-14)
    np.testing.assert_allclose(b.phi2, a.phi2, rtol=0, atol=1e-14)
    np.testing.assert_allclose(b.control_point_errors, a.control_point_errors, rtol=0, atol=1e-15)


def test_compiled_lu_step_solves_the_system():
    """The 6 x 6 elimination of the compiled Newton against numpy (pivoting needed: a zero leading entry)."""
    rng = np.random.default_rng(7)
    for _ in range(20):
        J = rng.normal(size=(6, 6))
        J[0, 0] = 0.0
        F = rng.normal(size=6)
        dx = np.empty(6)
        _lu_step(J.copy(), F.copy(), dx)
        np.testing.assert_allclose(dx, -np.linalg.solve(J, F), rtol=0, atol=1e-10 * np.linalg.cond(J))

