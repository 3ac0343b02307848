"""Hypoid pair kinematics (spiralbevel.meshing.hypoid_kinematics): the intersecting-axes pair at E = 0, the ISO 23509
Method 1 pitch point in the pair frame, the sign of the offset, the instantaneous screw axis, misalignments on top."""

import math
import warnings

import numpy as np
import pytest
from scipy.optimize import least_squares

from spiralbevel.conventions import Hand
from spiralbevel.design.blank import BlankInput, compute_blank
from spiralbevel.errors import DesignError
from spiralbevel.meshing.contact_problem import ContactProblem
from spiralbevel.meshing.hypoid_kinematics import HypoidPairKinematics, pair_offset
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.misalignment import Misalignment
from _hypoid_sample2 import SAMPLE2

R = math.radians
# ISO 23509 Annex F.3 Sample 2 (Method 1)


def _blank(**changes):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")      # Sample 2's own face width warning
        return compute_blank(BlankInput(**{**SAMPLE2, **changes}))


@pytest.mark.parametrize("shaft", [90.0, 75.0, 105.0])
def test_zero_offset_is_the_intersecting_pair(shaft):
    bevel = BevelPairKinematics(R(shaft), 14, 39)
    hyp = HypoidPairKinematics(R(shaft), 14, 39)
    rng = np.random.default_rng(3)
    r, phi = rng.normal(scale=60.0, size=(20, 3)), rng.normal(size=20)
    # round-off: the same cross products grouped differently (|r| ~ 100 mm)
    np.testing.assert_allclose(hyp.relative_velocity(r), bevel.relative_velocity(r), rtol=0, atol=1e-12)
    np.testing.assert_allclose(hyp.to_gear(r, phi), bevel.to_gear(r, phi), rtol=0, atol=1e-12)
    np.testing.assert_array_equal(hyp.to_fixed_pinion(r, phi), bevel.to_fixed_pinion(r, phi))
    assert hyp.pitch_angle_pinion == bevel.pitch_angle_pinion
    n = rng.normal(size=(20, 3))
    np.testing.assert_array_equal(hyp.meshing_willis_form(r, n), bevel.meshing_willis_form(r, n))
    point, direction, pitch = hyp.screw_axis()
    np.testing.assert_allclose(point, 0.0, atol=1e-14)
    np.testing.assert_allclose(direction, bevel.pitch_line, atol=1e-15)
    assert abs(pitch) < 1e-14
    mis = Misalignment(pinion_axial=0.3, gear_axial=-0.2, offset=0.1, shaft_angle=0.002)
    for got, ref in zip(hyp.axes(mis), mis.axes(R(shaft))):       # bit for bit: the TCA sees the same assembly
        np.testing.assert_array_equal(got, ref)


def test_contact_problem_places_a_crossed_pair():
    hyp = HypoidPairKinematics(R(90.0), 13, 42, offset=-15.0, pinion_apex=1.2, gear_apex=-1.6)

    class Surface:
        def evaluate(self, q):
            return np.zeros(q.shape[:-1] + (3,)), np.zeros(q.shape[:-1] + (3,))

    mis = Misalignment(offset=0.5, pinion_axial=0.1)
    cp = ContactProblem(Surface(), Surface(), hyp, mis, scale=100.0)
    a1, o1, a2, o2, _ = cp.axes
    np.testing.assert_allclose(o1, [0.0, -14.5, 1.3], atol=1e-15)       # E + dE along +y, t1 + dA1 along a1
    np.testing.assert_allclose(o2, -1.6 * a2, atol=1e-15)
    # without an axes() method the misalignment alone places the pair, as before
    cp0 = ContactProblem(Surface(), Surface(), BevelPairKinematics(R(90.0), 13, 42), mis, scale=100.0)
    for got, ref in zip(cp0.axes, mis.axes(R(90.0))):
        np.testing.assert_array_equal(got, ref)


def _pitch_point(kin, blank):
    """The point where the two mean pitch circles (member frames: radius Rm sin(delta) at axial Rm cos(delta)) meet
    in the pair frame, by least squares over the two circle angles."""
    a1, o1, a2, o2, B2 = kin.axes()

    def circle(t, o, Rm, d, B):
        return o + B @ np.array([Rm * math.sin(d) * math.cos(t), Rm * math.sin(d) * math.sin(t), Rm * math.cos(d)])

    def res(x):
        return circle(x[0], o1, blank.Rm1, blank.delta1, np.eye(3)) - circle(x[1], o2, blank.Rm2, blank.delta2, B2)

    sols = [least_squares(res, [t1, t2], xtol=1e-15, ftol=1e-15, gtol=1e-15)
            for t1 in np.linspace(-3, 3, 5) for t2 in np.linspace(-3, 3, 5)]
    best = min(sols, key=lambda s: s.cost)
    return circle(best.x[0], o1, blank.Rm1, blank.delta1, np.eye(3)), math.sqrt(2 * best.cost)


@pytest.mark.parametrize("a, z1, z2, beta", [(15.0, 13, 42, 50.0), (-15.0, 13, 42, 50.0), (25.0, 11, 41, 45.0)])
def test_pitch_point_relations(a, z1, z2, beta):
    """At the pitch point of the Method 1 blank placed in the pair frame: the pitch cones touch (common normal), the
    relative velocity lies in their tangent plane along a tooth trace with spiral angles beta_m1 and beta_m2 on the
    two cones, the trace has the wheel's hand and the pinion's, and w1 r1 cos(beta1) = w2 r2 cos(beta2)."""
    blank = _blank(a=a, z1=z1, z2=z2, beta_m=R(beta))
    kin = HypoidPairKinematics.from_blank(blank)
    a1, o1, a2, o2, _ = kin.axes()
    P, gap = _pitch_point(kin, blank)
    assert gap < 1e-9                       # mm: the circles of the blank's cone distances and apexes meet
    g1, g2 = (P - o1) / np.linalg.norm(P - o1), (P - o2) / np.linalg.norm(P - o2)
    N1 = np.cross(g1, np.cross(P - o1, a1))
    N2 = np.cross(g2, np.cross(P - o2, a2))
    N1, N2 = N1 / np.linalg.norm(N1), N2 / np.linalg.norm(N2)
    assert np.linalg.norm(np.cross(N1, N2)) < 1e-12
    v = kin.relative_velocity(P)
    t = v / np.linalg.norm(v)
    assert abs(t @ N1) < 1e-12
    assert math.acos(abs(t @ g1)) == pytest.approx(blank.beta_m1, abs=1e-11)
    assert math.acos(abs(t @ g2)) == pytest.approx(blank.beta_m2, abs=1e-11)
    assert blank.beta_m1 - blank.beta_m2 == pytest.approx(blank.zeta_mp, abs=1e-12)
    # hands: the tooth trace from toe to heel turns positively about the member axis on a right-hand member
    for g, o, axis, hand in ((g1, o1, a1, blank.hand1), (g2, o2, a2, blank.hand2)):
        tt = t if t @ g > 0 else -t
        assert np.sign(np.cross(P - o, tt) @ axis) == Hand(hand).sign
    # equal normal velocities across the trace in the pitch plane (the ratio relation of the pitch point)
    r1, r2 = np.linalg.norm(np.cross(a1, P - o1)), np.linalg.norm(np.cross(a2, P - o2))
    assert r1 * math.cos(blank.beta_m1) * z2 / z1 == pytest.approx(r2 * math.cos(blank.beta_m2), rel=1e-12)


def test_offset_sign_pinned_by_the_hand():
    """The opposite offset E places the same blank with the trace of the opposite hand: E's sign is not free."""
    blank = _blank()
    kin = HypoidPairKinematics.from_blank(blank)
    assert kin.offset == pair_offset(15.0, Hand.RIGHT) == -15.0 and blank.hand2 is Hand.RIGHT
    flipped = HypoidPairKinematics(kin.shaft_angle, kin.z1, kin.z2, offset=-kin.offset, pinion_apex=kin.pinion_apex,
                                   gear_apex=kin.gear_apex)
    P, gap = _pitch_point(flipped, blank)
    a1, o1, a2, o2, _ = flipped.axes()
    v = flipped.relative_velocity(P)
    t = v if v @ (P - o2) > 0 else -v
    assert gap < 1e-9 and np.sign(np.cross(P - o2, t) @ a2) == -Hand.RIGHT.sign


def test_screw_axis_velocity_is_along_the_axis():
    kin = HypoidPairKinematics.from_blank(_blank())
    point, d, pitch = kin.screw_axis()
    w = np.linalg.norm(kin.relative_angular_velocity())
    for s in (-50.0, 0.0, 80.0):
        v = kin.relative_velocity(point + s * d)
        np.testing.assert_allclose(v, pitch * w * d, atol=1e-12)
    # off the axis the velocity has a component across it
    assert np.linalg.norm(np.cross(kin.relative_velocity(point + [0.0, 0.0, 10.0]), d)) > 1.0


def test_intersecting_only_methods_refuse_an_offset():
    kin = HypoidPairKinematics(R(90.0), 13, 42, offset=5.0)
    with pytest.raises(DesignError, match="offset"):
        kin.pitch_line  # noqa: B018
    with pytest.raises(DesignError, match="offset"):
        kin.meshing_willis_form(np.ones(3), np.ones(3))
    with pytest.raises(DesignError, match="pinion_apex"):
        HypoidPairKinematics(R(90.0), 13, 42, pinion_apex=float("nan"))
