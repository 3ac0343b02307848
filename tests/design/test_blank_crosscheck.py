"""Closed forms of the blank checked by independent constructions (plane geometry, numerical root finding)."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from spiralbevel.design.blank import compute_blank
from spiralbevel.design.blank_checks import top_land
from spiralbevel.design.blank_input import BlankInput
from spiralbevel.design.blank_thickness import (
    chordal_values,
    spiral_angle_at,
    tip_thickness,
    undercut_limit_depth,
)
from spiralbevel.errors import GeometryError

R = math.radians
SAMPLE1 = dict(z1=14, z2=39, de2=176.893, b=25.4, beta_m=R(35.0), rc0=114.3, c_ham=0.24737, k_t=0.0915, jen=0.127)


def _blank(**kw):
    return compute_blank(BlankInput(**{**SAMPLE1, **kw}))


# ---------------------------------------------------------------- spiral angle of the circular tooth trace
def _spiral_angle_by_construction(r, rm, beta_m, rc0):
    """Crown-plane construction: circle of radius rc0 through P = (Rm, 0) whose tangent at P makes beta_m with the
    radius; intersect with the circle |x| = r by root finding; measure the tangent/radius angle there."""
    t_p = np.array([math.cos(beta_m), math.sin(beta_m)])  # tangent at P
    n_p = np.array([-t_p[1], t_p[0]])  # toward the cutter centre
    centre = np.array([rm, 0.0]) + rc0 * n_p
    phi_p = math.atan2(-centre[1], rm - centre[0])  # polar angle of P seen from the centre

    def point(phi):
        return centre + rc0 * np.array([math.cos(phi), math.sin(phi)])

    # walk from P along +t_p (|x| grows) for the heel, along -t_p for the toe; first crossing of |x| = r
    ccw = np.array([-math.sin(phi_p), math.cos(phi_p)])  # d(point)/d(phi) direction at P
    sgn = (1.0 if np.dot(ccw, t_p) > 0 else -1.0) * (1.0 if r > rm else -1.0)
    f = lambda d: np.linalg.norm(point(phi_p + sgn * d)) - r  # noqa: E731
    grid = np.linspace(0.0, math.pi, 2001)
    vals = np.array([f(d) for d in grid])
    i = int(np.nonzero(np.sign(vals[1:]) != np.sign(vals[0]))[0][0])
    d = brentq(f, grid[i], grid[i + 1], xtol=1e-15)
    phi = phi_p + sgn * d
    x = point(phi)
    tangent = np.array([-math.sin(phi), math.cos(phi)])
    cosang = abs(np.dot(tangent, x / np.linalg.norm(x)))
    return math.asin(math.sqrt(max(0.0, 1 - cosang**2)))


@pytest.mark.parametrize("r,rm,beta,rc0", [(93.97, 81.27, R(35), 114.3), (68.57, 81.27, R(35), 114.3),
                                           (134.45, 115.95, R(30), 114.3), (97.45, 115.95, R(30), 114.3),
                                           (60.0, 50.0, R(20), 40.0)])
def test_spiral_angle_formula_equals_circle_construction(r, rm, beta, rc0):
    assert spiral_angle_at(r, rm, beta, rc0) == pytest.approx(_spiral_angle_by_construction(r, rm, beta, rc0),
                                                              abs=1e-10)


def test_rc0_bound_for_the_heel_is_sharp():
    bl = _blank()
    rm, re, sb = bl.Rm, bl.Re2, math.sin(bl.beta_m2)
    lim = (re * re - rm * rm) / (2 * (re - rm * sb))
    assert spiral_angle_at(re, rm, bl.beta_m2, lim * (1 + 1e-9)) is not None
    assert spiral_angle_at(re, rm, bl.beta_m2, lim * (1 - 1e-6)) is None
    with pytest.raises(GeometryError, match="rc0"):
        _blank(rc0=lim * 0.99, taper="uniform")


# ---------------------------------------------------------------- cones in the axial plane
@pytest.mark.parametrize("taper", ["duplex", "trl", "standard", "uniform"])
@pytest.mark.parametrize("k", [1, 2])
def test_face_and_root_cone_lines_by_plane_geometry(taper, k):
    """Heel and toe tip/root points built in the axial plane (z along the axis from the apex, r radial): the lines
    through them must have the face/root angles, cut the axis at -tzF / -tzR, and give dae/2, dai/2 and txo."""
    bl = _blank(taper=taper)
    g = lambda n: getattr(bl, f"{n}{k}")  # noqa: E731
    delta = g("delta")
    pitch = np.array([math.cos(delta), math.sin(delta)])  # (z, r) unit vector of the pitch generator
    normal = np.array([-math.sin(delta), math.cos(delta)])  # outward (toward the tips)
    tip_e, tip_i = g("Re") * pitch + g("hae") * normal, g("Ri") * pitch + g("hai") * normal
    root_e, root_i = g("Re") * pitch - g("hfe") * normal, g("Ri") * pitch - g("hfi") * normal
    for p_e, p_i, ang, apex in ((tip_e, tip_i, g("delta_a"), -g("tzF")), (root_e, root_i, g("delta_f"), -g("tzR"))):
        d = p_e - p_i
        assert math.atan2(d[1], d[0]) == pytest.approx(ang, abs=1e-12)
        if k == 2:  # the pinion's apexes follow the wheel's cones (test_pinion_apexes_from_the_wheel_cones)
            z_axis = p_e[0] - p_e[1] * d[0] / d[1]  # where the line meets r = 0
            assert z_axis == pytest.approx(apex, abs=1e-9)
    assert 2 * tip_e[1] == pytest.approx(g("dae"), abs=1e-9)
    assert 2 * tip_i[1] == pytest.approx(g("dai"), abs=1e-9)
    assert 2 * root_e[1] == pytest.approx(g("dfe"), abs=1e-9)
    assert 2 * root_i[1] == pytest.approx(g("dfi"), abs=1e-9)
    assert tip_e[0] == pytest.approx(g("txo"), abs=1e-9)
    assert tip_i[0] == pytest.approx(g("txi"), abs=1e-9)
    assert (bl.Rm * pitch)[0] == pytest.approx(g("tzm"), abs=1e-9)  # crossing point (= pitch apex) to mean point
    if k == 2:  # whole depth perpendicular to the root cone: distance of the heel tip point from the root line
        d_root = (root_e - root_i) / np.linalg.norm(root_e - root_i)
        v = tip_e - root_i
        assert d_root[0] * v[1] - d_root[1] * v[0] == pytest.approx(g("ht"), abs=1e-9)


@pytest.mark.parametrize("kw", [dict(), dict(taper="standard"), dict(taper="uniform"), dict(shaft_angle=R(75.0)),
                                dict(shaft_angle=R(110.0), z1=20, z2=30)])
def test_pinion_apexes_from_the_wheel_cones(kw):
    """The standard's pinion face (root) cone lies at the clearance c, perpendicular, from the wheel's root (face)
    cone. Built in the plane of both axes from the *wheel's* axis, apexes and angles (pinion axis along z from the
    crossing point, wheel axis at the shaft angle Σ): offset each wheel line by c toward the pinion axis and cut the
    pinion axis. Also the standard's closed forms for a = 0, t_zF1 = (−t_zR2·sin δf2 − c)/sin δa1 and
    t_zR1 = (−t_zF2·sin δa2 − c)/sin δf1."""
    bl = _blank(**kw)
    a2 = np.array([math.cos(bl.Sigma), math.sin(bl.Sigma)])  # wheel axis in the pinion's axial plane
    p = np.array([math.cos(bl.delta1), math.sin(bl.delta1)])  # common pitch generator
    n2 = (p - math.cos(bl.delta2) * a2) / math.sin(bl.delta2)  # wheel radial direction toward the generator

    def pinion_axis_cut(apex_dist, cone_angle):
        """Wheel cone line (apex −apex_dist·a2, angle from a2) moved by c toward the pinion axis; its z at r = 0."""
        d = math.cos(cone_angle) * a2 + math.sin(cone_angle) * n2
        normal = np.array([-d[1], d[0]])
        normal = normal if normal[1] > 0 else -normal  # pointing away from the pinion axis
        q = -apex_dist * a2 - bl.c * normal
        return q[0] - q[1] * d[0] / d[1]

    assert pinion_axis_cut(bl.tzR2, bl.delta_f2) == pytest.approx(-bl.tzF1, abs=1e-9)
    assert pinion_axis_cut(bl.tzF2, bl.delta_a2) == pytest.approx(-bl.tzR1, abs=1e-9)
    iso_f = (-bl.tzR2 * math.sin(bl.delta_f2) - bl.c) / math.sin(bl.delta_a1)
    iso_r = (-bl.tzF2 * math.sin(bl.delta_a2) - bl.c) / math.sin(bl.delta_f1)
    assert bl.tzF1 == pytest.approx(iso_f, abs=1e-9) and bl.tzR1 == pytest.approx(iso_r, abs=1e-9)
    # that face cone lies c·(1 − cos θa1) inside the one through the mean addendum ham1 (perpendicular distance)
    own = -(bl.Rm * math.sin(bl.theta_a1) - bl.ham1 * math.cos(bl.theta_a1)) / math.sin(bl.delta_a1)
    gap = (bl.tzF1 - own) * math.sin(bl.delta_a1)
    assert gap == pytest.approx(-bl.c * (1 - math.cos(bl.theta_a1)), abs=1e-9)


@pytest.mark.parametrize("kw", [dict(), dict(taper="standard"), dict(taper="uniform"), dict(z1=11, z2=43, b=26.0),
                                dict(shaft_angle=R(75.0)), dict(shaft_angle=R(110.0), z1=20, z2=30)])
def test_whole_depth_normal_to_root_equals_the_standard_closed_form(kw):
    """h_t by the standard's expression ((t_zF + t_xo)/cos δa)·sin(θa + θf) − (t_zR − t_zF)·sin δf, built from the
    apex and crown distances, against the point-to-line distance the code uses."""
    bl = _blank(**kw)
    for k in (1, 2):
        g = lambda n, k=k: getattr(bl, f"{n}{k}")  # noqa: E731
        if not (g("delta_a") < R(89.0) and g("delta_f") > R(1.0)):
            continue
        iso = ((g("tzF") + g("txo")) / math.cos(g("delta_a")) * math.sin(g("theta_a") + g("theta_f"))
               - (g("tzR") - g("tzF")) * math.sin(g("delta_f")))
        assert g("ht") == pytest.approx(iso, abs=1e-9)
        assert g("ht") <= g("he") + 1e-12  # the perpendicular to the root is not longer than the heel depth


def test_standard_taper_root_lines_pass_through_the_pitch_apex():
    bl = _blank(taper="standard")
    assert bl.tzR2 == pytest.approx(0.0, abs=1e-12)
    # the pinion's root cone of the standard sits c·(1 − cos θf1) (perpendicular) below its own dedendum line
    assert bl.tzR1 * math.sin(bl.delta_f1) == pytest.approx(-bl.c * (1 - math.cos(bl.theta_f1)), abs=1e-12)


def test_uniform_taper_has_constant_depth():
    bl = _blank(taper="uniform")
    for k in (1, 2):
        for name in ("ha", "hf"):
            m = getattr(bl, f"{name}m{k}")
            assert getattr(bl, f"{name}e{k}") == pytest.approx(m, abs=1e-12)
            assert getattr(bl, f"{name}i{k}") == pytest.approx(m, abs=1e-12)


@pytest.mark.parametrize("taper", ["duplex", "standard", "uniform"])
def test_uniform_clearance_along_the_face(taper):
    bl = _blank(taper=taper)
    for end in ("e", "i"):
        assert getattr(bl, f"hf{end}2") - getattr(bl, f"ha{end}1") == pytest.approx(bl.c, abs=1e-12)
        assert getattr(bl, f"hf{end}1") - getattr(bl, f"ha{end}2") == pytest.approx(bl.c, abs=1e-12)


# ---------------------------------------------------------------- virtual spur gear: tip thickness, chord, undercut
def _involute_tip_thickness(d, s, ha, a_d, a_c):
    """Both flanks drawn as explicit involutes (parameter = roll angle), cut with the tip circle by brentq."""
    r, ra = d / 2, d / 2 + ha

    def flank_polar_angle(alpha):
        rb = r * math.cos(alpha)
        # the flank crosses the reference circle at polar angle s/(2r) from the tooth centre
        t_ref = math.tan(alpha)

        def xy(t):
            return rb * np.array([math.cos(t) + t * math.sin(t), math.sin(t) - t * math.cos(t)])

        t_tip = brentq(lambda t: np.linalg.norm(xy(t)) - ra, 0.0, 3.0, xtol=1e-15)
        ang = lambda t: math.atan2(xy(t)[1], xy(t)[0])  # noqa: E731
        return s / (2 * r) + ang(t_ref) - ang(t_tip)  # half-angle of the tooth at the tip

    return ra * (flank_polar_angle(a_d) + flank_polar_angle(a_c))


@pytest.mark.parametrize("d,s,ha,a_d,a_c", [(82.24, 6.7575, 4.8369, R(20), R(20)), (50.0, 5.0, 3.0, R(22.5), R(17.5)),
                                            (30.0, 4.8, 3.2, R(20), R(20))])
def test_tip_thickness_equals_explicit_involutes(d, s, ha, a_d, a_c):
    assert tip_thickness(d, s, ha, a_d, a_c) == pytest.approx(_involute_tip_thickness(d, s, ha, a_d, a_c), abs=1e-9)


def test_tip_thickness_tends_to_the_rack_value():
    s, ha, a = 5.0, 3.0, R(20)
    rack = s - 2 * ha * math.tan(a)
    assert tip_thickness(1e7, s, ha, a, a) == pytest.approx(rack, abs=1e-5)
    assert tip_thickness(math.inf, s, ha, a, a) == pytest.approx(rack, abs=1e-15)


@pytest.mark.parametrize("delta", [R(19.75), R(70.25), R(45.0)])
def test_chordal_values_by_coordinates(delta):
    """Chord and sagitta of the arc smn on the virtual gear circle built from coordinates; the standard's chordal
    addendum takes the sagitta times cos(delta)."""
    smn, ham, dvn = 6.7575, 4.8369, 82.241
    half = smn / dvn  # half angle subtended by the arc thickness
    p = 0.5 * dvn * np.array([math.sin(half), math.cos(half)])
    q = 0.5 * dvn * np.array([-math.sin(half), math.cos(half)])
    smnc, hamc = chordal_values(smn, ham, dvn, delta)
    assert smnc == pytest.approx(np.linalg.norm(p - q), abs=1e-12)
    assert hamc == pytest.approx(ham + (0.5 * dvn - p[1]) * math.cos(delta), abs=1e-12)  # tip circle to chord


def test_undercut_limit_is_the_interference_point_depth():
    """Pitch point P on the reference circle, line of action through P at the pressure angle; its tangency point T
    with the base circle is the interference point; its depth below the rack pitch line is r·sin²α."""
    r, alpha = 41.1, R(20)
    centre = np.array([0.0, 0.0])
    pitch_point = np.array([0.0, r])
    direction = np.array([math.cos(alpha), -math.sin(alpha)])  # line of action
    t = np.dot(centre - pitch_point, direction)
    tangency = pitch_point + t * direction
    assert np.linalg.norm(tangency - centre) == pytest.approx(r * math.cos(alpha), rel=1e-12)  # base circle
    assert r - tangency[1] == pytest.approx(undercut_limit_depth(2 * r, alpha), rel=1e-12)


def test_mean_top_land_uses_the_mean_thickness():
    bl = _blank()
    for k in (1, 2):
        direct = tip_thickness(getattr(bl, f"dvn{k}"), getattr(bl, f"smn{k}"), getattr(bl, f"ham{k}"),
                               bl.alpha_nD, bl.alpha_nC)
        assert top_land(bl, k, "m") == pytest.approx(direct, abs=1e-12)
        assert getattr(bl, f"sam{k}") == pytest.approx(direct, abs=1e-12)


# ---------------------------------------------------------------- thickness and backlash
def test_thickness_and_backlash_balance():
    bl = _blank()
    removed = bl.jet * bl.Rm / bl.Re2 * math.cos(bl.beta_m1)  # mean normal circular thickness removed
    assert bl.smn1 + bl.smn2 == pytest.approx(math.pi * bl.mmn - removed, abs=1e-12)
    assert bl.jen == pytest.approx(bl.jet * math.cos(bl.beta_e2) * math.cos(bl.alpha_e), abs=1e-15)
    # no backlash, no thickness factor: the rack rule s1 - s2 = 2 * x_hm1 * mmn * (tan aD + tan aC)
    nb = _blank(jen=None, k_t=0.0)
    assert nb.smn1 - nb.smn2 == pytest.approx(4 * nb.x_hm1 * nb.mmn * math.tan(R(20)), abs=1e-12)


def test_backlash_carried_back_to_the_heel_is_the_given_one():
    """Second route: the circular thickness removed at the mean point (pi*mmn - smn1 - smn2, normal section) is turned
    into the transverse section (/cos βm), scaled along the cone to the heel (Re2/Rm), into the heel normal section
    (cos βe2) and onto the flank normal (cos αn): that is the outer normal backlash jen."""
    for kw in (dict(), dict(jen=0.3, k_t=0.0), dict(jen=None, jet=0.2, alpha_dD=R(22.0), alpha_dC=R(18.0))):
        bl = _blank(**kw)
        removed = math.pi * bl.mmn - bl.smn1 - bl.smn2
        alpha_n = 0.5 * (bl.alpha_nD + bl.alpha_nC)
        jen = removed / math.cos(bl.beta_m2) * bl.Re2 / bl.Rm * math.cos(bl.beta_e2) * math.cos(alpha_n)
        assert jen == pytest.approx(bl.jen, abs=1e-12)
        assert bl.jmn == pytest.approx(removed * math.cos(alpha_n), abs=1e-12)  # mean normal backlash
        # half from each member: both members lose the same thickness relative to the backlash-free design
        free = _blank(**{**kw, "jen": None, "jet": None})
        assert free.smn1 - bl.smn1 == pytest.approx(free.smn2 - bl.smn2, abs=1e-12)
        assert free.smn1 - bl.smn1 == pytest.approx(0.5 * removed, abs=1e-12)


def test_thickness_factor_moves_thickness_from_wheel_to_pinion():
    """The rack (basic crown gear) picture: a thickness modification x_smn·mmn on each flank of the pinion's rack
    tooth, 2·x_smn·mmn = k_t·mmn in all, taken from the wheel; the sum stays one normal pitch."""
    a, b = _blank(jen=None, k_t=0.0), _blank(jen=None, k_t=0.12)
    assert b.smn1 - a.smn1 == pytest.approx(0.12 * a.mmn, abs=1e-12)
    assert a.smn2 - b.smn2 == pytest.approx(0.12 * a.mmn, abs=1e-12)
    assert b.smn1 + b.smn2 == pytest.approx(math.pi * b.mmn, abs=1e-12)


def test_backlash_given_as_jet_or_jen_is_the_same():
    a = _blank()
    b = _blank(jen=None, jet=a.jet)
    assert b.jen == pytest.approx(a.jen, rel=1e-14)
    assert b.smn1 == pytest.approx(a.smn1, rel=1e-14)


def test_crown_wheel_limit_is_continuous():
    """delta2 = 90 deg exactly (Σ = acos(-z1/z2)): the virtual gear of the wheel is a rack; top lands and chordal
    values must be the limits of the values just below 90 deg."""
    kw = dict(z1=20, z2=40, met=3.0, b=15.0, beta_m=R(30), rc0=60.0, taper="duplex")
    crown = compute_blank(BlankInput(**kw, shaft_angle=math.acos(-0.5)))
    near = compute_blank(BlankInput(**kw, shaft_angle=math.acos(-0.5) - 1e-7))
    assert crown.delta2 == pytest.approx(math.pi / 2, abs=1e-15) and crown.dvn2 == math.inf
    for name in ("sam2", "sai2", "sae2", "smnc2", "hamc2", "smn2", "hae2", "tzR2"):
        assert getattr(crown, name) == pytest.approx(getattr(near, name), abs=1e-5), name


@pytest.mark.parametrize("kw", [dict(), dict(z1=12, z2=41, met=5.0, de2=None, b=30.0, rc0=76.2),
                                dict(beta_m=R(25.0), rc0=152.4, shaft_angle=R(75.0))])
def test_duplex_taper_keeps_the_completing_slot_consistent_with_the_pitch(kw):
    """Independent of the ISO duplex formula's derivation: with a constant root slot width (face milling, completing),
    the two members' pitch-line thicknesses add up to the normal pitch p_n(R) = π·mmt·(R/Rm)·cos β(R) to first order
    around the mean point *only* for the duplex dedendum angle sum. Checked by finite differences of
    s_n1(R) + s_n2(R) − p_n(R) over R (quadratic residual), and a standard taper fails it."""
    from spiralbevel.design.blank_checks import normal_thickness

    def excess(bl, r):
        """s_n1 + s_n2 − p_n at cone distance r, with the section quantities of the model at r."""
        import dataclasses

        beta = spiral_angle_at(r, bl.Rm, bl.beta_m2, bl.rc0)
        fields = {}
        for k in (1, 2):
            fields[f"Re{k}"] = r
            fields[f"beta_e{k}"] = beta
            fields[f"hfe{k}"] = getattr(bl, f"hfm{k}") + (r - bl.Rm) * math.tan(getattr(bl, f"theta_f{k}"))
        sec = dataclasses.replace(bl, **fields)
        pn = math.pi * bl.mmt * r / bl.Rm * math.cos(beta)
        return normal_thickness(sec, 1, "e") + normal_thickness(sec, 2, "e") - pn

    for taper, first_order in (("duplex", True), ("standard", False)):
        bl = _blank(jen=None, taper=taper, **kw)
        h = 0.5
        slope = (excess(bl, bl.Rm + h) - excess(bl, bl.Rm - h)) / (2 * h)  # central difference, error O(h^2)
        assert excess(bl, bl.Rm) == pytest.approx(0.0, abs=1e-12)
        # the standard's sum is written with angles where the slot argument has tangents: the residual slope is
        # 2·tan αn·(Σθf − Σ tan θf), a third-order small quantity (3.7e-4 for Sample 1)
        tf = (bl.theta_f1, bl.theta_f2)
        small_angle = 2 * math.tan(R(20)) * (sum(tf) - sum(math.tan(t) for t in tf))
        if first_order:
            # O(h^2) truncation of the central difference with h = 0.5 mm: at most 2.3e-6 over these cases
            assert slope == pytest.approx(small_angle, abs=5e-6)
        else:
            assert abs(slope - small_angle) > 1e-3


def test_tilted_root_line_caps_the_duplex_sum():
    """TRL (ISO 23509 Annex C, modified slot width): Sample 1's duplex sum 8.6277° exceeds 1.3 times the standard sum
    (1.3 * 5.6565° = 7.353°), so the root lines tilt about the mean point to 1.3·ΣθfS, split like the duplex sum;
    with a small cutter the duplex sum is below the cap and TRL is the duplex blank."""
    dup, trl = _blank(taper="duplex"), _blank(taper="trl")
    assert dup.sum_theta_fC > 1.3 * dup.sum_theta_fS
    assert trl.sum_theta_f == pytest.approx(1.3 * trl.sum_theta_fS, rel=1e-14)
    assert trl.theta_f1 / trl.sum_theta_f == pytest.approx(dup.theta_f1 / dup.sum_theta_f, rel=1e-14)
    for name in ("ham1", "hfm1", "ham2", "hfm2", "smn1", "smn2"):  # the mean point is where the root line pivots
        assert getattr(trl, name) == getattr(dup, name)
    assert trl.hfe2 < dup.hfe2 and trl.hfi2 > dup.hfi2
    small = dict(rc0=60.0)  # duplex sum ~ (1 - Rm sin(beta)/rc0): a small cutter lowers it
    dup, trl = _blank(taper="duplex", **small), _blank(taper="trl", **small)
    assert dup.sum_theta_fC < 1.3 * dup.sum_theta_fS
    a, b = dup.to_dict(), trl.to_dict()
    assert {k for k in a if a[k] != b[k]} == {"taper"}
