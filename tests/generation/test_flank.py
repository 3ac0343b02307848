"""Generated flanks: equation of meshing, cutter surface, junction, hand, seed 001 reference figures, errors."""

import math
from types import SimpleNamespace

import numpy as np
import pytest
from _chain import chain
from conftest import CASES, basic_flank

from spiralbevel.conventions import Hand, Member, Side
from spiralbevel.errors import DesignError, GeometryError
from spiralbevel.generation import generate_flank


@pytest.mark.parametrize("member,side", CASES)
def test_grid_shape_and_meshing(member, side):
    fl = basic_flank(member, side)
    g = fl.grid(9, 7, n_fillet=4)
    assert g.points.shape == (9, 11, 3) and g.normals.shape == (9, 11, 3)
    assert g.fillet[:, :3].all() and not g.fillet[:, 3:].any()
    np.testing.assert_allclose(np.linalg.norm(g.normals, axis=-1), 1.0, atol=1e-14)
    assert np.all(np.abs(fl.meshing_residual(g.u, g.theta, g.psi_c)) <= 1e-10)
    assert np.all(g.points[..., 2] > 0)
    # clipped to the blank: toe and heel rows on R = Ri, Re; last row on the face cone
    ol = fl.outline
    R, h = ol.Rh(g.axial, g.radius)
    np.testing.assert_allclose(R[0], ol.Ri, atol=1e-9)
    np.testing.assert_allclose(R[-1], ol.Re, atol=1e-9)
    np.testing.assert_allclose(h[:, -1], ol.h_face(R[:, -1]), atol=1e-9)
    assert np.all(np.diff(h[:, 4:], axis=1) > 0)          # root -> top
    np.testing.assert_array_equal(g.points[:, 3], g.points[:, 4])   # junction row repeated
    assert np.all(np.diff(R, axis=0) > 0)                  # toe -> heel
    # basic settings put the root apex at the pitch apex (machine centre): the cutter tip generates the cone of root
    # angle through the apex, h = -R tan(theta_f)
    np.testing.assert_allclose(h[:, 0], -R[:, 0] * np.tan(ol.delta - ol.delta_f), atol=1e-9)


@pytest.mark.parametrize("member,side", CASES)
@pytest.mark.parametrize("extra", [{}, {"modified_roll": (0.03, -0.2)}, {"blank_offset_poly": (0.4, 1.5)},
                                   {"blank_offset": 0.7, "sliding_base": 0.05, "machine_centre_to_back": 0.3}])
def test_points_on_cutter_and_meshing_by_independent_chain(member, side, extra):
    """Each generated point is the cutter point (u, theta) at cradle angle psi_c (independent chain with an explicit
    hand sign), and n . dr/dpsi_c = 0 for the family of cutter surfaces (complex-step derivative)."""
    fl = basic_flank(member, side, **extra)
    g = fl.grid(5, 4, n_fillet=3)
    hs = fl.hand.sign
    worst_pos = worst_mesh = 0.0
    for u, th, ps, p, n in zip(g.u.ravel(), g.theta.ravel(), g.psi_c.ravel(), g.points.reshape(-1, 3),
                               g.normals.reshape(-1, 3)):
        r, nh = chain(u, th, ps, fl.cutter, fl.settings, hs)
        worst_pos = max(worst_pos, np.abs(r - p).max())
        np.testing.assert_allclose(-fl.cutter.sign * nh, n, atol=1e-12)     # outward = -s n_h
        h = 1e-20
        dr = chain(u, th, complex(ps, h), fl.cutter, fl.settings, hs)[0].imag / h
        worst_mesh = max(worst_mesh, abs(dr @ nh) / np.linalg.norm(dr))
    assert worst_pos < 1e-10
    assert worst_mesh < 1e-10


@pytest.mark.parametrize("member,side", CASES[1:3])
def test_blade_and_fillet_join_with_continuous_normals(member, side):
    fl = basic_flank(member, side)
    g = fl.grid(7, 5, n_fillet=4)
    np.testing.assert_array_equal(g.points[:, 3], g.points[:, 3])
    _, uj = fl.cutter.fillet_range
    psi = g.psi_c[:, 3]
    below, above = fl.evaluate(uj - 1e-9, psi), fl.evaluate(uj + 1e-9, psi)
    np.testing.assert_allclose(below.points, above.points, atol=1e-7)
    np.testing.assert_allclose(below.normals, above.normals, atol=1e-7)
    # the fillet bends the other way in profile: concave root fillet (k1 < 0) of about -1/rho_h at its middle
    mid = fl.evaluate(uj - 0.7, psi)
    assert np.all(mid.k1 < 0)


def test_hand_of_generated_members(blank):
    # docs/conventions.md: RH <=> tooth trace turns positively about +z from toe to heel
    for member, side in CASES:
        mp = basic_flank(member, side, blank).mean_point()
        assert mp.hand_sign == Hand(getattr(blank, f"hand{member.index}")).sign


@pytest.mark.parametrize("member,side", [(Member.GEAR, Side.CONVEX), (Member.PINION, Side.CONCAVE)])
def test_left_hand_is_mirror_of_right_hand(blank, member, side):
    i = member.index
    other = SimpleNamespace(**{**vars(blank), f"hand{i}": Hand(getattr(blank, f"hand{i}")).opposite})
    a, b = basic_flank(member, side, blank).grid(6, 5, 3), basic_flank(member, side, other).grid(6, 5, 3)
    M = np.array([1.0, -1.0, 1.0])
    np.testing.assert_allclose(b.points, a.points * M, atol=1e-10)
    np.testing.assert_allclose(b.normals, a.normals * M, atol=1e-12)
    np.testing.assert_allclose(b.k1, a.k1, rtol=1e-9)
    np.testing.assert_allclose(b.k2, a.k2, rtol=1e-9)
    np.testing.assert_allclose(b.e1, a.e1 * M, atol=1e-9)
    np.testing.assert_allclose(np.cross(b.e1, b.e2), b.normals, atol=1e-12)


def test_seed001_gear_table4_mean_point(gear_t4):
    """seed 001 Tables 1 and 4 (gear, inner blade, modified blade angle 23 deg 50'): mean pitch point."""
    mp = gear_t4.mean_point()
    # Table 1: mean spiral angle 30 deg; measured 29.997 deg (Table 4 is rounded: ratio 1.06, X_B = -0.051)
    assert math.degrees(mp.spiral_angle) == pytest.approx(30.0, abs=0.05)
    # normal pressure angle: nominal blade angle 22 deg 30' on the pitch cone (the 1 deg 20' blade-angle
    # modification compensates the dedendum angle, theta_f2 sin(beta) = 1.24 deg); measured 22.63 deg
    assert math.degrees(mp.pressure_angle) == pytest.approx(22.5, abs=0.2)
    # against the cradle (root) plane it is the cutter's blade angle 23 deg 50' (measured 23.857 deg)
    assert math.degrees(mp.pressure_angle_root) == pytest.approx(23 + 50 / 60, abs=0.05)
    assert mp.hand_sign == -1                                 # gear is LH (Table 1)
    assert mp.k1 > 0 and mp.k2 > 0                            # convex flank
    # docs/theory/generation.md, Eqs. (G10)-(G11) (#mean-point): |r| = mean cone distance at the pitch point
    assert np.linalg.norm(mp.point) == pytest.approx(115.9511, abs=1e-9)


def test_seed001_table5_pinion(pinion_t5):
    mp = pinion_t5.mean_point()
    # Table 5 pinion (outer blade 22 deg 30', E_m1 = 34.197 mm): spiral angle 30.13 deg, pressure angle 22.75 deg
    # (the design 22 deg 30' of Table 1 plus the curvature of generation on the root plane; tests/machine/
    # test_seed001_reading.py compares it with the gear)
    assert math.degrees(mp.spiral_angle) == pytest.approx(30.0, abs=0.25)
    assert math.degrees(mp.pressure_angle) == pytest.approx(22.5, abs=0.3)
    assert mp.hand_sign == 1 and mp.k2 < 0                    # RH, concave lengthwise
    g = pinion_t5.grid(7, 5, 3)
    assert np.all(np.abs(pinion_t5.meshing_residual(g.u, g.theta, g.psi_c)) <= 1e-10)


@pytest.mark.parametrize("member,side", CASES)
def test_basic_settings_mean_point(blank, member, side):
    mp = basic_flank(member, side, blank).mean_point()
    # crown-gear triangle at A = Rm cos(theta_f) with beta_m = 30 deg: spiral angle on the pitch cone within 0.25 deg
    assert math.degrees(mp.spiral_angle) == pytest.approx(30.0, abs=0.25)
    # the pitch point is generated on the instantaneous axis (pitch-line roll): there the flank normal is the blade
    # normal, at exactly the blade angle to the cradle plane = the root-angle cone through the point
    assert mp.pressure_angle_root == pytest.approx(math.radians(22.5), abs=1e-9)


def test_grid_refinement_converges(blank):
    fl = basic_flank(Member.GEAR, Side.CONCAVE, blank)

    def area(n):
        P = fl.grid(n, n, curvature=False).points
        a = np.cross(P[1:, 1:] - P[:-1, :-1], P[:-1, 1:] - P[1:, :-1])
        return 0.5 * np.linalg.norm(a, axis=-1).sum()
    A = [area(n) for n in (5, 9, 17, 33)]
    d = np.abs(np.diff(A))
    rates = d[:-1] / d[1:]
    assert np.all(rates > 3.0)                  # second-order convergence of the polyhedral area (ratio 4)
    assert d[-1] / A[-1] < 1e-4


def test_boundary_closes(blank):
    b = basic_flank(Member.PINION, Side.CONVEX, blank).boundary(9)
    np.testing.assert_allclose(b["toe"][0], b["root"][0], atol=1e-12)
    np.testing.assert_allclose(b["heel"][-1], b["top"][-1], atol=1e-12)
    assert b["root"].shape == (9, 3)


def test_errors(blank):
    with pytest.raises(GeometryError):                          # cutter cannot reach the blank
        basic_flank(Member.GEAR, Side.CONVEX, blank, radial_setting=400.0).grid(5, 5)
    # settings of a crown-gear triangle for a mean point at cone distance 200 mm: the flank misses the face width
    A, rc, b = 200.0, 114.3, math.radians(30)
    S, q = math.hypot(A - rc * math.sin(b), rc * math.cos(b)), math.atan2(rc * math.cos(b), A - rc * math.sin(b))
    with pytest.raises(GeometryError, match="face width"):
        basic_flank(Member.GEAR, Side.CONVEX, blank, radial_setting=S, cradle_angle=q).grid(5, 5)
    fl = basic_flank(Member.GEAR, Side.CONVEX, blank)
    with pytest.raises(DesignError, match="cutter.blade"):
        generate_flank(fl.cutter, fl.settings, blank, Member.GEAR, Side.CONCAVE)
    with pytest.raises(DesignError, match="n_face"):
        fl.grid(1, 5)
    with pytest.raises(GeometryError):
        fl.locate(100.0, 500.0)
