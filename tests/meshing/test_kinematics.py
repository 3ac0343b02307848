"""Bevel-pair kinematics: validation, pitch cones, frames and the two forms of the meshing equation."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from spiralbevel._core.rotations import rot_axis, rot_y, rot_z
from spiralbevel.errors import DesignError
from spiralbevel.meshing.kinematics import BevelPairKinematics

angles = st.floats(-10.0, 10.0, allow_nan=False)
shafts = st.floats(0.2, 2.9, allow_nan=False)
teeth = st.integers(5, 80)


@pytest.mark.parametrize(
    "kwargs, field",
    [
        (dict(shaft_angle=0.0, z1=10, z2=30), "shaft_angle"),
        (dict(shaft_angle=np.pi, z1=10, z2=30), "shaft_angle"),
        (dict(shaft_angle=float("nan"), z1=10, z2=30), "shaft_angle"),
        (dict(shaft_angle="90", z1=10, z2=30), "shaft_angle"),
        (dict(shaft_angle=1.0, z1=0, z2=30), "z1"),
        (dict(shaft_angle=1.0, z1=10, z2=2.5), "z2"),
        (dict(shaft_angle=1.0, z1=True, z2=30), "z1"),
    ],
)
def test_bad_input_names_field_value_range(kwargs, field):
    with pytest.raises(DesignError) as err:
        BevelPairKinematics(**kwargs)
    assert err.value.problems[0].field == field
    assert "allowed" in str(err.value)


def test_frozen():
    kin = BevelPairKinematics(np.pi / 2, 23, 65)
    with pytest.raises(AttributeError):
        kin.z1 = 3


def test_pitch_angle_reference_23_65():
    # docs/theory/logspiral.md, Eq. (S2) (#surface) design example: Z 23/65, S = 90 deg -> g1 = 19.4861295725 deg (10
    # digits printed)
    kin = BevelPairKinematics(np.pi / 2, 23, 65)
    assert np.degrees(kin.pitch_angle_pinion) == pytest.approx(19.4861295725, abs=1e-10)


@settings(max_examples=40, deadline=None)
@given(shafts, teeth, teeth)
def test_pitch_cones_roll(shaft, z1, z2):
    kin = BevelPairKinematics(shaft, z1, z2)
    g1, g2 = kin.pitch_angle_pinion, kin.pitch_angle_gear
    assert g1 + g2 == pytest.approx(shaft, abs=1e-14)
    # rolling: sin g1 / sin g2 = z1 / z2 (second method: the law of sines of the pitch cones)
    assert np.sin(g1) / np.sin(g2) == pytest.approx(z1 / z2, rel=1e-13)
    p = kin.pitch_line
    assert np.dot(p, kin.pinion_axis) == pytest.approx(np.cos(g1), abs=1e-14)
    assert np.dot(p, kin.gear_axis) == pytest.approx(np.cos(g2), abs=1e-14)
    # equal velocities of both members along the pitch line: v(12) = 0 there
    w1, w2 = kin.angular_velocity_pinion(1.7), kin.angular_velocity_gear(1.7)
    assert np.allclose(np.cross(w1, 50 * p), np.cross(w2, 50 * p), atol=1e-12)
    assert np.allclose(kin.relative_velocity(50 * p, 1.7), 0.0, atol=1e-12)
    # w(12) = (w1 cos g1 + w2 cos g2) p (docs/theory/gearing.md, Eqs. (M1)-(M2))
    w12 = kin.relative_angular_velocity(1.7)
    assert np.allclose(w12, 1.7 * (np.cos(g1) + z1 / z2 * np.cos(g2)) * p, atol=1e-13)


@settings(max_examples=30, deadline=None)
@given(shafts, teeth, teeth, angles)
def test_transforms_are_rotations_and_match_conventions(shaft, z1, z2, phi1):
    kin = BevelPairKinematics(shaft, z1, z2)
    phi2 = kin.gear_angle(phi1)
    assert phi2 == pytest.approx(-z1 / z2 * phi1)
    for R in (kin.pinion_to_fixed(phi1), kin.gear_to_fixed(phi2), kin.pinion_to_gear(phi1)):
        assert np.allclose(R @ R.T, np.eye(3), atol=1e-14)
        assert np.linalg.det(R) == pytest.approx(1.0, abs=1e-13)
    # second method: R(a2, phi2) R_y(S) = R_y(S) R_z(phi2), since a2 = R_y(S) e_z
    assert np.allclose(kin.gear_to_fixed(phi2), rot_y(shaft) @ rot_z(phi2), atol=1e-14)
    assert np.allclose(kin.gear_to_fixed(phi2) @ [0, 0, 1], kin.gear_axis, atol=1e-14)
    assert np.allclose(kin.pinion_to_gear(phi1), kin.gear_to_fixed(phi2).T @ kin.pinion_to_fixed(phi1),
                       atol=1e-14)
    # the mapping of the brief/docs/theory/gearing.md, Eqs. (M1)-(M8): R_y(-S) R(a2, (z1/z2) phi1) R(a1, phi1)
    assert np.allclose(kin.pinion_to_gear(phi1),
                       rot_y(-shaft) @ rot_axis(kin.gear_axis, z1 / z2 * phi1) @ rot_axis([0, 0, 1], phi1),
                       atol=1e-14)


def test_pitch_line_in_member_frames():
    # docs/conventions.md: at phi2 = 0 the pitch line is (-sin g2, 0, cos g2) in the gear frame
    kin = BevelPairKinematics(np.radians(75.0), 17, 41)
    g2 = kin.pitch_angle_gear
    assert np.allclose(kin.gear_to_fixed(0.0).T @ kin.pitch_line, [-np.sin(g2), 0, np.cos(g2)], atol=1e-15)
    assert np.allclose(kin.pinion_to_fixed(0.0).T @ kin.pitch_line, kin.pitch_line, atol=1e-15)


def test_member_velocities_are_derivatives_of_the_transforms():
    # w(1), w(2) are the angular velocities of phi1 -> R(a1, phi1), phi1 -> R(a2, phi2(phi1)) R_y(S) (omega1 = 1)
    kin = BevelPairKinematics(np.radians(105.0), 12, 31)
    r_member = np.array([10.0, -20.0, 80.0])
    phi1, h = 0.3, 1e-6
    for to_fixed, w in (
        (lambda a: kin.pinion_to_fixed(a), kin.angular_velocity_pinion()),
        (lambda a: kin.gear_to_fixed(kin.gear_angle(a)), kin.angular_velocity_gear()),
    ):
        vel = (to_fixed(phi1 + h) @ r_member - to_fixed(phi1 - h) @ r_member) / (2 * h)
        assert np.allclose(vel, np.cross(w, to_fixed(phi1) @ r_member), atol=1e-7)


@settings(max_examples=40, deadline=None)
@given(shafts, teeth, teeth, angles,
       st.lists(st.floats(-100, 100, allow_nan=False), min_size=6, max_size=6))
def test_velocity_form_equals_willis_form(shaft, z1, z2, phi1, xs):
    kin = BevelPairKinematics(shaft, z1, z2)
    r = np.array(xs[:3])
    n = np.array(xs[3:]) + np.array([0.3, -0.2, 1.0])
    n = n / np.linalg.norm(n)
    g1, g2 = kin.pitch_angle_pinion, kin.pitch_angle_gear
    # n . v(12) with v(12) = v(1) - v(2) built from the member velocities (seed 002 Eqs. 7-9,
    # docs/theory/gearing.md#conjugacy)
    v1 = np.cross(kin.angular_velocity_pinion(2.0), r)
    v2 = np.cross(kin.angular_velocity_gear(2.0), r)
    lhs = np.dot(n, v1 - v2)
    assert kin.meshing_velocity_form(r, n, 2.0) == pytest.approx(lhs, abs=1e-10)
    # = (w1 cos g1 + w2 cos g2) det[r, n, p]
    w12 = 2.0 * (np.cos(g1) + z1 / z2 * np.cos(g2))
    det = np.linalg.det(np.stack([r, n, kin.pitch_line]))
    assert kin.meshing_willis_form(r, n) == pytest.approx(det, abs=1e-10)
    assert lhs == pytest.approx(w12 * det, abs=1e-9)
    # in pinion member coordinates: f(r1, n1, phi1) = det[R r1, R n1, p]
    R = kin.pinion_to_fixed(phi1)
    f = kin.meshing_function(R.T @ r, R.T @ n, phi1)
    assert f == pytest.approx(det, abs=1e-10)
