"""Misalignments (seed 001 §4.1; docs/conventions.md "Misalignments"): sign conventions pinned on the assembly, and
the TCA response checked against an independent first-order estimate."""

import numpy as np
import pytest

from spiralbevel.errors import DesignError
from spiralbevel.meshing.contact_surface import NormalDeviation, quadratic_crowning
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.misalignment import Misalignment
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair

S = np.pi / 2


def _axis_distance(p1, a1, p2, a2):
    c = np.cross(a1, a2)
    return abs((p2 - p1) @ c) / np.linalg.norm(c)


def test_signs_of_the_assembly():
    a1, o1, a2, o2, _ = Misalignment(pinion_axial=0.1).axes(S)
    np.testing.assert_allclose(o1, [0, 0, 0.1])  # pinion away from the apex along +a1
    a1, o1, a2, o2, _ = Misalignment(gear_axial=0.1).axes(S)
    np.testing.assert_allclose(o2, 0.1 * a2)  # gear away from the apex along +a2
    np.testing.assert_allclose(a2, [1, 0, 0], atol=1e-15)
    a1, o1, a2, o2, _ = Misalignment(offset=0.2).axes(S)
    assert _axis_distance(o1, a1, o2, a2) == pytest.approx(0.2, abs=1e-15)  # axes cross at |dE|
    np.testing.assert_allclose(o1, [0, 0.2, 0])  # pinion axis shifted along +y = a1 x a2
    a1, o1, a2, o2, B2 = Misalignment(shaft_angle=0.01).axes(S)
    assert np.arccos(a1 @ a2) == pytest.approx(S + 0.01, abs=1e-14)  # shaft angle S + dg
    np.testing.assert_allclose(B2 @ [0, 0, 1], a2, atol=1e-15)  # gear member axis maps to the misaligned a2


def test_misalignment_validation():
    with pytest.raises(DesignError, match="offset"):
        Misalignment(offset=float("nan"))
    with pytest.raises(DesignError, match="shaft_angle"):
        Misalignment(shaft_angle=1.0)


@pytest.fixture(scope="module")
def setup():
    pair = conjugate_logspiral_pair()
    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    crowned = NormalDeviation(pair.pinion, quadratic_crowning(pair.pinion.reference_params, (0.5, 0.0, 5.0)))
    ref = solve_tca(crowned, pair.gear, kin, n_positions=3)
    return pair, kin, crowned, ref


def _start(ref):
    return np.r_[ref.params1[1, 1], ref.params2[1, 1], ref.phi2_pairs[1, 1]]


@pytest.mark.parametrize("mis", [Misalignment(pinion_axial=0.01), Misalignment(gear_axial=0.01),
                                 Misalignment(offset=0.01), Misalignment(shaft_angle=1e-4)])
def test_gear_rotation_matches_first_order_gap_estimate(setup, mis):
    """At phi1 = phi10 a rigid displacement d of the pinion (or -d of the gear) changes the gap along the contact
    normal n1 by d.n1; the gear closes it by turning d phi2 with d phi2 (a2 x r).n1 = d.n1 (first order; the shift
    of the contact point changes the gap only at second order)."""
    pair, kin, crowned, ref = setup
    r = ref.point_fixed[1, 1]
    n1 = ref.normal_fixed[1, 1]
    a2 = np.array([np.sin(S), 0, np.cos(S)])
    d = mis.pinion_axial * np.array([0, 0, 1.0]) + mis.offset * np.array([0, 1.0, 0])
    d = d - mis.gear_axial * a2 - mis.shaft_angle * np.cross([0, 1.0, 0], r)
    predicted = (d @ n1) / (np.cross(a2, r) @ n1)
    res = solve_tca(crowned, pair.gear, kin, misalignment=mis, n_positions=3, start=_start(ref))
    got = res.phi2_mean - ref.phi2_mean
    assert got == pytest.approx(predicted, rel=2e-2)


def test_pinion_axial_displacement_moves_contact_lengthwise_and_in_profile(setup):
    """Delta A1 > 0 (pinion moved along +a1, away from the apex). On the convex pinion flank the outward normal
    leans away from the apex (n . r/|r| = sin(beta) > 0, docs/theory/logspiral.md, Eq. (S2) (#surface)) more than the
    pressure angle tilts it toward
    the apex, so n1 . a1 > 0: the flank is pushed into the gear flank and the gear advances (on the opposite flank
    the lengthwise component changes sign and the gear lags: together the backlash grows). The mean contact on the
    pinion moves toward the heel (larger cone distance) and toward the pinion root (smaller psi), i.e. both along the
    face and along the profile; the lengthwise shift is the larger one."""
    pair, kin, crowned, ref = setup
    res = solve_tca(crowned, pair.gear, kin, misalignment=Misalignment(pinion_axial=0.05), n_positions=3,
                    start=_start(ref))
    assert ref.normal_fixed[1, 1] @ [0, 0, 1.0] > 0
    assert ref.drive_sign * -(res.phi2_mean - ref.phi2_mean) > 0  # gear ahead in its driven direction
    q0, q = ref.params1[1, 1], res.params1[1, 1]
    sd = np.sin(pair.pinion.delta)
    d_len = np.linalg.norm(res.point1[1, 1]) - np.linalg.norm(ref.point1[1, 1])  # along the face, mm
    d_psi = (q[0] - q[1]) * sd - (q0[0] - q0[1]) * sd
    d_prof = abs(d_psi) * np.linalg.norm(ref.point1[1, 1])  # along the profile (arc on the sphere), mm
    assert d_len > 0.01  # toward the heel
    assert d_psi < 0  # toward the root cone (psi_range[0])
    assert d_len > d_prof


def test_shaft_angle_error_moves_contact_along_the_profile(setup):
    """A shaft-angle error is a rotation of the gear about an axis through the common apex: for these spherical
    involute (log-spiral) flanks the mean contact stays on its sphere |r| = const to first order and moves along
    the profile."""
    pair, kin, crowned, ref = setup
    res = solve_tca(crowned, pair.gear, kin, misalignment=Misalignment(shaft_angle=1e-3), n_positions=3,
                    start=_start(ref))
    dr = np.linalg.norm(res.point1[1, 1]) - np.linalg.norm(ref.point1[1, 1])
    dp = np.linalg.norm(res.point1[1, 1] - ref.point1[1, 1])
    assert dp > 0.01
    assert abs(dr) < 1e-3 * dp
