"""Local synthesis of a hypoid pinion (spiralbevel.meshing.synthesis.hypoid_local) on ISO 23509 Sample 2, checked by
the TCA of the synthesized pair in the crossed-axes frame (an independent solve of the contact of the two generated
flanks, with their own curvatures) and the brute-force oracle."""

import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.design.blank import BlankInput, compute_blank
from spiralbevel.meshing.generated_surface import GeneratedSurface
from spiralbevel.meshing.hypoid_kinematics import HypoidPairKinematics
from spiralbevel.meshing.hypoid_pair import hypoid_basic_flanks
from spiralbevel.meshing.kinematics import BevelPairKinematics
from spiralbevel.meshing.synthesis._relations import path_speed_terms
from spiralbevel.meshing.synthesis.hypoid_local import hypoid_path_terms, synthesize_hypoid_pinion
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_result import ARCSEC, ContactStatus

sys.path.insert(0, str(Path(__file__).parents[1]))
from _contact_oracle import Oracle, grid_box, lead_deviation  # noqa: E402
from _hypoid_sample2 import SAMPLE2, sample2_blank

R = math.radians
ETA, A, TE = R(6.0), 3.7, 6.0 * ARCSEC          # design path direction, semi-major axis (mm), TE magnitude (rad)


@pytest.fixture(scope="module")
def synthesized():
    blank = sample2_blank()
    flanks = hypoid_basic_flanks(blank)
    out = {}
    for side in (Side.CONCAVE, Side.CONVEX):
        c, s, _, _ = flanks[(Member.PINION, side)]
        syn = synthesize_hypoid_pinion(flanks[(Member.GEAR, side.mate)][2], c, s, blank, side=side, eta=ETA,
                                       semi_major_axis=A, te_magnitude=TE)
        c1, c2 = GeneratedSurface(syn.pinion_flank, syn.phi1_mean), GeneratedSurface(syn.gear_flank, syn.phi2_mean)
        res = solve_tca(c1, c2, syn.kinematics, n_positions=41,
                        start=np.r_[c1.reference_params, c2.reference_params, 0.0])
        out[side] = (blank, syn, c1, c2, res)
    return out


def test_path_terms_reduce_to_the_intersecting_axes_form():
    rng = np.random.default_rng(5)
    kin0 = BevelPairKinematics(R(90.0), 13, 42)
    hyp = HypoidPairKinematics(R(90.0), 13, 42)
    for _ in range(3):
        r, n = rng.normal(scale=50.0, size=3), rng.normal(size=3)
        n /= np.linalg.norm(n)
        K2 = rng.normal(scale=0.02, size=(3, 3))
        K2 = K2 + K2.T
        ref = path_speed_terms(r, n, K2, kin0.angular_velocity_pinion(), kin0.angular_velocity_gear(),
                               kin0.gear_axis, 0.3)
        got = hypoid_path_terms(r, n, K2, hyp, 0.3)
        for g, e in zip(got, ref):
            np.testing.assert_allclose(g, e, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("side", [Side.CONCAVE, Side.CONVEX])
def test_synthesized_pinion_meets_the_wheel_at_the_pitch_point(synthesized, side):
    blank, syn, _, _, res = synthesized[side]
    assert syn.pinion_settings.blank_offset != 0.0             # a hypoid pinion: solved with a blank offset
    p = syn.pinion_flank.evaluate(*syn.pinion_params, curvature=False)
    c, s = math.cos(syn.phi1_mean), math.sin(syn.phi1_mean)
    Rz = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    o1 = syn.kinematics.axes()[1]
    np.testing.assert_allclose(o1 + Rz @ p.points, syn.point, atol=1e-8)
    np.testing.assert_allclose(Rz @ p.normals, syn.normal, atol=1e-9)
    mid = len(res.phi1) // 2
    assert res.status[mid] == ContactStatus.OK and abs(res.te_arcsec[mid]) < 1e-6


@pytest.mark.parametrize("side", [Side.CONCAVE, Side.CONVEX])
def test_tca_has_the_designed_te_curvature_and_ellipse(synthesized, side):
    _, syn, _, _, res = synthesized[side]
    mid = len(res.phi1) // 2
    h = res.phi1[mid + 1] - res.phi1[mid]
    te = res.te_arcsec[mid - 2:mid + 3] * ARCSEC
    d2 = (-te[0] + 16 * te[1] - 30 * te[2] + 16 * te[3] - te[4]) / (12 * h * h)
    assert syn.m21_prime == pytest.approx(-2 * TE * (13 / math.pi) ** 2, rel=1e-14)
    assert d2 == pytest.approx(syn.m21_prime, rel=0.01)          # measured ~1e-4: the fit is to 1e-9
    # TCA's ellipse from the two flanks' own curvatures at the contact: a = 3.7 mm
    assert res.semi_axes[mid, 0] == pytest.approx(A, rel=1e-5)
    # the design TE level: the parabola's depth at half a mesh cycle, measured as the mean of the two sides at a
    # quarter cycle (the cubic term of the TE cancels): within 10 %
    q = len(res.phi1) // 4
    quarter = 0.5 * (res.te_arcsec[mid - q] + res.te_arcsec[mid + q]) * ARCSEC
    x = res.phi1[mid + q] - res.phi1[mid]
    assert quarter / (x / (math.pi / 13)) ** 2 == pytest.approx(-TE, rel=0.10)


def test_synthesized_tca_matches_brute_force(synthesized):
    _, syn, c1, c2, res = synthesized[Side.CONCAVE]
    kin = syn.kinematics

    o = Oracle(c1, c2, grid_box(c1), grid_box(c2), kin.z1, kin.z2, kin.axes())
    idx = np.arange(0, len(res.phi1), 8)
    d = lead_deviation(o, res, idx) / ARCSEC
    assert np.all(np.isfinite(d)) and np.max(np.abs(d)) <= 0.1, np.round(d, 5)


@pytest.mark.parametrize("side", [Side.CONCAVE, Side.CONVEX])
def test_synthesized_pinion_keeps_the_design_angles(synthesized, side):
    """The synthesized pinion passes through the pitch point with the wheel's normal: its own mean point (R_m1 on its
    pitch cone) keeps the design spiral and pressure angles."""
    from spiralbevel.machine.default_cutter import design_pressure_angle

    blank, syn, _, _, _ = synthesized[side]
    mp = syn.pinion_flank.mean_point()
    # the mean point is located to ~1e-10 mm and the fit reaches M to 1e-9: ~1e-7 deg measured
    assert math.degrees(abs(mp.spiral_angle - blank.beta_m1)) < 1e-5
    assert math.degrees(abs(mp.pressure_angle - design_pressure_angle(blank, Member.PINION, side))) < 1e-5


def test_mirror_of_hands():
    """The pair of the opposite hands (right-hand pinion, left-hand wheel, E = +a) is the mirror image: the same
    synthesized settings and the same transmission error, run backwards (the mirror y -> -y turns both rotations
    the other way: the positions phi1 of one pair are -phi1 of the other)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        blanks = [compute_blank(BlankInput(**SAMPLE2, hand1=h)) for h in ("LH", "RH")]
    out = []
    for blank in blanks:
        flanks = hypoid_basic_flanks(blank)
        c, s, _, _ = flanks[(Member.PINION, Side.CONCAVE)]
        syn = synthesize_hypoid_pinion(flanks[(Member.GEAR, Side.CONVEX)][2], c, s, blank, eta=ETA,
                                       semi_major_axis=A, te_magnitude=TE)
        c1, c2 = GeneratedSurface(syn.pinion_flank, syn.phi1_mean), GeneratedSurface(syn.gear_flank, syn.phi2_mean)
        res = solve_tca(c1, c2, syn.kinematics, n_positions=11,
                        start=np.r_[c1.reference_params, c2.reference_params, 0.0])
        out.append((syn, res))
    (a, ra), (b, rb) = out
    assert a.kinematics.offset == -b.kinematics.offset != 0.0
    np.testing.assert_allclose(b.point * [1, -1, 1], a.point, atol=1e-9)
    for key in ("radial_setting", "cradle_angle", "ratio_of_roll", "blank_offset"):
        assert getattr(b.pinion_settings, key) == pytest.approx(getattr(a.pinion_settings, key), rel=1e-8, abs=1e-9)
    np.testing.assert_allclose(rb.te_arcsec[::-1], ra.te_arcsec, atol=1e-6, equal_nan=True)
