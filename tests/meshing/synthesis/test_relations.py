"""Mean contact point, Litvin's three relations (round trip through the analysis form), TE conversion, errors."""

import math

import numpy as np
import pytest
from _synth_common import ARCSEC, TE
from hypothesis import given, settings
from hypothesis import strategies as st

from spiralbevel.conventions import Member, Side
from spiralbevel.errors import ConvergenceError, DesignError, GeometryError
from spiralbevel.generation import generate_flank
from spiralbevel.machine import Blade, HeadCutter
from spiralbevel.meshing.synthesis import (FREE_OFFSET, fit_settings, mean_contact, synthesize_pinion,
                                          te_parabola_coefficient)
from spiralbevel.meshing.synthesis._relations import (path_speed_terms, relative_curvature_from_path,
                                                     tangent_components)


@pytest.fixture(scope="module")
def mc(blank, gear_table4):
    c, s = gear_table4
    return mean_contact(generate_flank(c, s, blank, Member.GEAR, Side.CONVEX), blank)


def test_mean_contact_on_pitch_line_and_meshing(mc, blank):
    kin = mc.kinematics
    # depth 0: the gear reference point at R_m (docs/theory/generation.md, Eqs. (G10)-(G11) (#mean-point)) turned onto
    # the pitch line, |M| = R_m
    assert np.linalg.norm(mc.point) == pytest.approx(blank.Rm, abs=1e-9)
    assert np.linalg.norm(np.cross(mc.point, kin.pitch_line)) < 1e-9
    # equation of meshing of the pair (velocity form, docs/theory/gearing.md, Eqs. (M1)-(M8)) and the gear point/normal
    # mapping
    assert abs(kin.meshing_velocity_form(mc.point, mc.normal)) < 1e-10
    R = kin.gear_to_fixed(mc.phi2)
    np.testing.assert_allclose(R @ mc.gear_point, mc.point, atol=1e-12)
    np.testing.assert_allclose(R @ mc.gear_normal, -mc.normal, atol=1e-14)
    # pinion concave drives the gear when phi1 increases in this frame (seed 001 drive side)
    assert mc.drive_sign == 1
    # pinion mean point: on the pinion pitch cone at R_m, radius R_m sin(delta1)
    assert mc.pinion_radius == pytest.approx(blank.Rm * math.sin(blank.delta1), abs=1e-9)


def _analysis(mc, K, eps2):
    """Analysis direction (given both surfaces): velocities from (K1 + K2) v_r1 = b, and eps2 back from the
    derivative of the meshing equation, which is linear in eps2 (evaluated at two values)."""
    kin = mc.kinematics
    args = (mc.point, mc.normal, mc.gear_tensor, kin.angular_velocity_pinion(), kin.angular_velocity_gear(),
            kin.gear_axis)
    v12, b, c0 = path_speed_terms(*args, 0.0)
    _, _, c1 = path_speed_terms(*args, 1.0)
    n = mc.normal
    a = np.cross(n, [1.0, 0.0, 0.0])
    a /= np.linalg.norm(a)
    B = np.stack([a, np.cross(n, a)])
    v_r1 = B.T @ np.linalg.solve(B @ K @ B.T, B @ b)
    v_r2 = v_r1 + v12
    eps = -(v_r2 @ b + c0) / (c1 - c0)
    return v_r2, eps, np.linalg.eigvalsh(B @ K @ B.T)


@settings(max_examples=25, deadline=None)
@given(eta=st.floats(-1.0, 1.0), a=st.floats(1.0, 8.0), te_arcsec=st.floats(0.5, 20.0))
def test_relations_round_trip(mc, eta, a, te_arcsec):
    kin = mc.kinematics
    eps2 = -te_parabola_coefficient(te_arcsec * ARCSEC, kin.z1)
    v12, b, c = path_speed_terms(mc.point, mc.normal, mc.gear_tensor, kin.angular_velocity_pinion(),
                                 kin.angular_velocity_gear(), kin.gear_axis, eps2)
    n2 = -mc.normal
    t_p = np.cross(n2, mc.point)
    t_p /= np.linalg.norm(t_p)
    t = math.cos(eta) * t_p + math.sin(eta) * np.cross(n2, t_p)
    lam = 2 * 0.00635 / a**2
    K, v_r2, _, why = relative_curvature_from_path(mc.normal, t, v12, b, c, lam)
    assert why == ""
    v2, eps, eig = _analysis(mc, K, eps2)
    np.testing.assert_allclose(v2, v_r2, rtol=1e-9, atol=1e-9 * np.linalg.norm(v_r2))
    assert abs(v2 @ t) / np.linalg.norm(v2) == pytest.approx(1.0, abs=1e-12)
    assert eps == pytest.approx(eps2, rel=1e-8)
    assert eig[0] == pytest.approx(lam, rel=1e-10) and eig[1] > lam
    np.testing.assert_allclose(K, K.T, atol=1e-15)
    assert abs(mc.normal @ K @ mc.normal) < 1e-14


def test_te_parabola_coefficient():
    # seed 001 Table 2: 3" over one mesh cycle of the 23-tooth pinion -> -2 (3") (23/pi)^2 = -1.5591e-3 1/rad
    assert te_parabola_coefficient(TE, 23) == pytest.approx(-2 * 3 * ARCSEC * (23 / math.pi) ** 2, rel=1e-15)
    assert 0.5 * te_parabola_coefficient(TE, 23) * (math.pi / 23) ** 2 == pytest.approx(-TE, rel=1e-14)


def test_m21_prime_and_te_magnitude_agree(blank, gear_table4, synth_pos):
    c, s = gear_table4
    r = synthesize_pinion(c, s, blank, side=Side.CONCAVE, eta=synth_pos.eta, semi_major_axis=3.7,
                          m21_prime=te_parabola_coefficient(TE, 23), free=FREE_OFFSET)
    assert r.pinion_cutter.point_radius == pytest.approx(synth_pos.pinion_cutter.point_radius, rel=1e-9)
    assert r.summary()["te_magnitude_arcsec"] == pytest.approx(3.0, rel=1e-12)
    assert r.summary()["eta"] == pytest.approx(6.0, rel=1e-12)


@pytest.mark.parametrize("kw,field", [
    (dict(eta=2.0), "eta"),
    (dict(semi_major_axis=-1.0), "semi_major_axis"),
    (dict(m21_prime=-1e-3), "m21_prime/te_magnitude"),
    (dict(te_magnitude=None), "m21_prime/te_magnitude"),
    (dict(te_magnitude=-1.0), "te_magnitude"),
    (dict(approach=0.0), "approach"),
    (dict(side="sideways"), "side"),
    (dict(free=("point_radius",)), "free"),
    (dict(pinion_cutter_hint=HeadCutter(115.0, 0.4, 2.29, 1.31, Blade.INNER)), "pinion_cutter_hint.blade"),
])
def test_bad_input_is_a_design_error(blank, gear_table4, kw, field):
    c, s = gear_table4
    args = dict(side=Side.CONCAVE, eta=0.1, semi_major_axis=3.7, te_magnitude=TE)
    args.update(kw)
    with pytest.raises(DesignError) as err:
        synthesize_pinion(c, s, blank, **args)
    assert field in str(err.value)


def test_unrealisable_design_is_a_geometry_error(blank, gear_table4):
    c, s = gear_table4
    # a 0.05 mm ellipse needs a relative curvature far above what the path allows (K11 <= lam_min)
    with pytest.raises(GeometryError, match="lam_min"):
        synthesize_pinion(c, s, blank, side=Side.CONCAVE, eta=0.1, semi_major_axis=0.05, te_magnitude=TE)


def test_settings_fit_failure_is_a_convergence_error(blank, synth_pos):
    r = synth_pos
    # a profile curvature of 1/mm on the concave pinion flank is out of reach of a straight-blade cutter
    K1 = r.relative_tensor - r.mean.gear_tensor + np.outer(r.pinion_dirs[0], r.pinion_dirs[0])
    target, nt = tangent_components(r.mean.point, r.mean.normal, K1)
    with pytest.raises(ConvergenceError) as err:
        fit_settings(r.pinion_cutter, r.pinion_settings, blank, Side.CONCAVE, target, nt, FREE_OFFSET, max_iter=15)
    assert err.value.iterations > 0 and np.isfinite(err.value.residual)


def test_fit_reproduces_known_settings(blank):
    """Settings fit alone: the invariants of a pinion generated with seed 001 Table 5 settings are reached again
    from the basic settings (all six FREE_OFFSET quantities recovered to 1e-7)."""
    from spiralbevel.machine import MachineSettings, seed001_settings
    from spiralbevel.meshing.synthesis.machine_fit import point_invariants
    c5, s5 = seed001_settings()[(Member.PINION, Side.CONCAVE)]
    s5 = s5.replace(blank_offset=1.5, sliding_base=0.0, machine_centre_to_back=0.0, ratio_of_roll=3.0)
    fl = generate_flank(c5, s5, blank, Member.PINION, Side.CONCAVE)
    u = float(fl.mean_point().u)
    target, nt = point_invariants(fl, u)
    c0 = HeadCutter(115.445, math.radians(22.5), 2.29, 1.31, Blade.OUTER)
    s0 = MachineSettings.from_blank(blank, Member.PINION, Side.CONCAVE, c0)
    c, s, u1, _ = fit_settings(c0, s0, blank, Side.CONCAVE, target, nt, FREE_OFFSET)
    got = [c.point_radius, c.blade_angle, s.radial_setting, s.cradle_angle, s.ratio_of_roll, s.blank_offset, u1]
    want = [c5.point_radius, c5.blade_angle, s5.radial_setting, s5.cradle_angle, 3.0, 1.5, u]
    np.testing.assert_allclose(got, want, rtol=1e-7, atol=1e-7)
