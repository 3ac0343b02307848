"""Log-spiral pair design (docs/theory/logspiral.md, Eq. (S12); docs/theory/gearing.md, Eq. (M8)) checked by independent
measurements."""

import numpy as np
import pytest

from spiralbevel import DesignError, GeometryError, Hand, Member, Side
from spiralbevel.design.logspiral_pair import BlankBoundaries, design_logspiral_pair
from spiralbevel.geometry.diffgeom import surface_geometry

D = np.radians


def _boundaries(z1, z2, shaft, alpha_n, beta_m, R_i=85.0, R_e=115.0, add=1.0, ded=1.1):
    """Blank with addendum/dedendum in mean modules (root kept 0.15 deg above the base cone for small pinions)."""
    g1 = np.arctan2(np.sin(shaft), z2 / z1 + np.cos(shaft))
    Rm = 0.5 * (R_i + R_e)
    m = 2 * Rm * np.sin(g1) / z1
    alpha_t = np.arctan(np.tan(alpha_n) / np.cos(beta_m))
    out = []
    for g in (g1, shaft - g1):
        delta = np.arcsin(np.sin(g) * np.cos(alpha_t))
        root = max(g - ded * m / Rm, delta + D(0.15))
        out.append(BlankBoundaries(R_i, R_e, root, g + add * m / Rm))
    return tuple(out)


CASES = [(23, 65, 90.0, 20.0, 35.0, Hand.RIGHT), (23, 65, 90.0, 20.0, 35.0, Hand.LEFT),
         (17, 41, 75.0, 22.5, 30.0, Hand.LEFT), (12, 31, 60.0, 20.0, 25.0, Hand.RIGHT)]


def _pair(z1, z2, shaft, an, bm, hand, **kw):
    S, an, bm = D(shaft), D(an), D(bm)
    return design_logspiral_pair(z1, z2, S, an, bm, hand, _boundaries(z1, z2, S, an, bm), **kw)


def test_example_recipe_numbers():
    """docs/theory/logspiral.md, Eq. (S2) (#surface) example (23/65, S = 90, alpha_n = 20, beta_m = 35 deg); printed to
    10 decimals of a degree."""
    p = _pair(23, 65, 90.0, 20.0, 35.0, Hand.RIGHT)
    assert np.degrees(p.pinion.pitch_angle) == pytest.approx(19.4861295725, abs=1e-10)
    assert np.degrees(p.transverse_pressure_angle) == pytest.approx(23.9568032445, abs=1e-10)
    assert np.degrees(p.pinion.base_cone_angle) == pytest.approx(17.7486263712, abs=1e-10)
    assert np.degrees(p.gear.base_cone_angle) == pytest.approx(59.4863803737, abs=1e-10)
    assert np.degrees(p.plane_spiral_angle) == pytest.approx(32.6146071483, abs=1e-10)
    assert p.pinion.spiral_parameter > 0 and p.gear.spiral_parameter == -p.pinion.spiral_parameter
    # docs/theory/gearing.md, Eqs. (M1)-(M8): base cones consistent, sin d1 : sin d2 = z1 : z2
    assert np.sin(p.pinion.base_cone_angle) / np.sin(p.gear.base_cone_angle) == pytest.approx(23 / 65, rel=1e-14)


@pytest.mark.parametrize("case", CASES)
def test_measured_pressure_and_spiral_angle_on_pitch_cones(case):
    """Normal from the generic numerical module vs the pitch-cone geometry: alpha_n and beta_m recovered."""
    z1, z2, shaft, an, bm, hand = case
    p = _pair(*case)
    g1 = np.arctan2(np.sin(D(shaft)), z2 / z1 + np.cos(D(shaft)))
    for member, gamma in ((Member.PINION, g1), (Member.GEAR, D(shaft) - g1)):
        m = p.member(member)
        for side in Side:
            f = p.flank(member, side)
            phi = np.linspace(f.domain.phi_min, f.domain.phi_max, 5)
            varphi = f.surface.varphi_of(f.surface.psi_sign(side) * m.psi_pitch, phi)
            sign = np.sign(f.surface.spiral_angle)  # outward = sign(beta) unit(r_varphi x r_phi)
            num = surface_geometry(f.point, varphi, phi, normal_sign=sign)
            r = num.point
            rn = np.linalg.norm(r, axis=-1)
            assert np.allclose(np.arccos(r[:, 2] / rn), gamma, atol=1e-12)  # on the pitch cone
            th = np.arctan2(r[:, 1], r[:, 0])
            cone_n = np.stack([np.cos(gamma) * np.cos(th), np.cos(gamma) * np.sin(th), -np.sin(gamma) + 0 * th], -1)
            alpha = np.arcsin(np.abs(np.einsum("...i,...i", num.normal, cone_n)))
            trace = np.cross(num.normal, cone_n)
            cosb = np.abs(np.einsum("...i,...i", trace, r)) / (np.linalg.norm(trace, axis=-1) * rn)
            assert np.allclose(np.degrees(alpha), an, atol=1e-8)
            assert np.allclose(np.degrees(np.arccos(cosb)), bm, atol=1e-8)
            # the outward normal leaves the tooth: it points away from the tooth centre azimuth
            assert m.hand is (Hand.RIGHT if f.surface.spiral_angle > 0 else Hand.LEFT)
    assert p.pinion.hand is hand and p.gear.hand is hand.opposite


def _invert_onto(flank, side, q):
    """Parameters of the (unrotated) flank point on the same sphere and coaxial cone as q (member frame)."""
    s = flank.surface
    rho = np.linalg.norm(q, axis=-1)
    phi = s.phi_of_rho(rho)
    psi = s.psi_sign(side) * np.arccos(np.cos(np.arccos(q[:, 2] / rho)) / np.cos(s.base_cone_angle))
    return s.varphi_of(psi, phi), phi


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("roll", [0.0, 0.07])
def test_zero_backlash_line_contact_in_pair_frame(case, roll):
    """docs/theory/gearing.md, Eqs. (M1)-(M8): the contact line lies where det[r, n, p] = 0, phi* = +-acos(tan d1/tan
    g1) - (phi1 + rotation).

    Mapped into the gear frame, those pinion points must lie exactly on the mating gear flank (pinion concave <->
    gear convex), with opposite outward normals, up to a whole number of gear pitches: this checks recipe, phasing and
    thickness (zero backlash) together.
    """
    z2 = case[1]
    p = _pair(*case)
    d1, g1 = p.pinion.base_cone_angle, p.pinion.pitch_angle
    for side in Side:
        f1, f2 = p.flank(Member.PINION, side), p.flank(Member.GEAR, side.mate)
        phi = np.linspace(f1.domain.phi_min, f1.domain.phi_max, 7)
        hits = 0
        for root in (1.0, -1.0):
            vp = root * np.arccos(np.tan(d1) / np.tan(g1)) - (roll + f1.rotation)
            centre = 0.5 * (f1.domain.psi_min + f1.domain.psi_max) / np.sin(d1) + phi.mean()
            vp = vp + 2 * np.pi * np.round((centre - vp) / (2 * np.pi))
            g = f1.evaluate(vp, phi)
            P = p.to_pair_frame(Member.PINION, g.point, roll)
            Np = p.to_pair_frame(Member.PINION, g.normal, roll)
            G = p.to_pair_frame(Member.GEAR, np.eye(3), roll)  # rows: images of the gear basis vectors
            q, nq = P @ G.T, Np @ G.T  # back into the gear member frame
            g2 = f2.evaluate(*_invert_onto(f2, side.mate, q))
            k = (np.arctan2(q[:, 1], q[:, 0]) - np.arctan2(g2.point[:, 1], g2.point[:, 0])) / (2 * np.pi / z2)
            kr = np.round(k)
            if np.max(np.abs(k - kr)) > 1e-6:
                continue
            hits += 1
            c, s_ = np.cos(kr * 2 * np.pi / z2), np.sin(kr * 2 * np.pi / z2)
            Rk = np.stack([np.stack([c, -s_, 0 * c], -1), np.stack([s_, c, 0 * c], -1),
                           np.stack([0 * c, 0 * c, 1 + 0 * c], -1)], -2)
            q2 = np.einsum("nij,nj->ni", Rk, g2.point)
            n2 = np.einsum("nij,nj->ni", Rk, g2.normal)
            assert np.max(np.linalg.norm(q2 - q, axis=-1)) < 1e-10
            assert np.allclose(np.einsum("...i,...i", n2, nq), -1.0, atol=1e-12)
        assert hits == 1  # exactly one of the two planes of action carries this flank pair


@pytest.mark.parametrize("case", CASES[:3])
def test_tooth_placement_and_thickness(case):
    z1, z2, shaft, an, bm, hand = case
    b1 = _boundaries(z1, z2, D(shaft), D(an), D(bm))[0]
    g1 = np.arctan2(np.sin(D(shaft)), z2 / z1 + np.cos(D(shaft)))
    s_given = 0.47 * 2 * np.pi / z1 * b1.mean_cone_distance * np.sin(g1) * np.cos(D(bm))
    p = _pair(*case, thickness=s_given)
    for member, centre in ((Member.PINION, 0.0), (Member.GEAR, np.pi + np.pi / z2)):
        m = p.member(member)
        az = {}
        for side in Side:
            pt = p.mean_point(member, side).point
            az[side] = np.arctan2(pt[1], pt[0])
            assert np.linalg.norm(pt) == pytest.approx(m.mean_cone_distance, rel=1e-14)
        mid = az[Side.CONVEX] + 0.5 * np.angle(np.exp(1j * (az[Side.CONCAVE] - az[Side.CONVEX])))
        width = abs(np.angle(np.exp(1j * (az[Side.CONVEX] - az[Side.CONCAVE]))))
        assert np.angle(np.exp(1j * (mid - centre))) == pytest.approx(0.0, abs=1e-12)
        s_n = width * m.mean_cone_distance * np.sin(m.pitch_angle) * np.cos(D(bm))
        assert s_n == pytest.approx(m.mean_normal_thickness, rel=1e-12)
        # the outward normal at each mean point points away from the tooth centre (into the space)
        for side in Side:
            g = p.mean_point(member, side)
            e_theta = np.array([-np.sin(az[side]), np.cos(az[side]), 0.0])
            away = np.sign(np.angle(np.exp(1j * (az[side] - centre))))
            assert np.sign(g.normal @ e_theta) == away
    pn = 2 * np.pi / z1 * p.pinion.mean_cone_distance * np.sin(p.pinion.pitch_angle) * np.cos(D(bm))
    assert p.pinion.mean_normal_thickness == pytest.approx(s_given, rel=1e-14)
    # zero backlash: thickness fractions of the pitch add to one
    fr1 = p.pinion.mean_normal_thickness / pn
    pn2 = 2 * np.pi / z2 * p.gear.mean_cone_distance * np.sin(p.gear.pitch_angle) * np.cos(D(bm))
    assert fr1 + p.gear.mean_normal_thickness / pn2 == pytest.approx(1.0, rel=1e-13)


def test_convex_concave_per_hand_follow_flank_type_table():
    for hand in Hand:
        p = _pair(23, 65, 90.0, 20.0, 35.0, hand)
        for member in Member:
            m = p.member(member)
            b = m.spiral_parameter
            assert np.sign(p.flank(member, Side.CONVEX).domain.psi_min) == np.sign(b)
            assert np.sign(p.flank(member, Side.CONCAVE).domain.psi_max) == -np.sign(b)
            grid = p.flank(member, Side.CONVEX).grid(5, 4)
            assert np.all(grid.k1 > 0) and np.all(grid.k2 > 0)  # convex: elliptic, convex = positive
            grid = p.flank(member, Side.CONCAVE).grid(5, 4)
            assert np.all(grid.k1 > 0) and np.all(grid.k2 < 0)  # concave lengthwise


def test_domain_boundaries_are_the_blank_spheres_and_cones():
    p = _pair(17, 41, 75.0, 22.5, 30.0, Hand.LEFT)
    for member in Member:
        b = p.member(member).boundaries
        for side in Side:
            g = p.flank(member, side).grid(3, 3)
            r = np.linalg.norm(g.point, axis=-1)
            assert np.allclose(r[0], b.inner_cone_distance, rtol=1e-13)  # rows run toe -> heel for either hand
            assert np.allclose(r[-1], b.outer_cone_distance, rtol=1e-13)
            cone = np.arccos(g.point[..., 2] / r)
            lo, hi = sorted([cone[0, 0], cone[0, -1]])
            assert lo == pytest.approx(b.root_angle, abs=1e-12) and hi == pytest.approx(b.face_angle, abs=1e-12)


def test_root_inside_base_cone_is_a_clear_geometry_error():
    S, an, bm = D(90), D(20), D(35)
    b1, b2 = _boundaries(23, 65, S, an, bm)
    bad = BlankBoundaries(b1.inner_cone_distance, b1.outer_cone_distance, D(17.0), b1.face_angle)
    with pytest.raises(GeometryError, match=r"root angle 17\.000000 deg <= base cone angle 17\.748626 deg"):
        design_logspiral_pair(23, 65, S, an, bm, Hand.RIGHT, (bad, b2))


@pytest.mark.parametrize(
    "kw, field",
    [(dict(z1=-3), "z1"), (dict(z2=0), "z2"), (dict(z1=23.5), "z1"), (dict(spiral_angle=D(90)), "spiral_angle"),
     (dict(spiral_angle=-0.1), "spiral_angle"), (dict(normal_pressure_angle=0.0), "normal_pressure_angle"),
     (dict(shaft_angle=D(180)), "shaft_angle"), (dict(pinion_hand="up"), "pinion_hand"),
     (dict(thickness=-1.0), "thickness"), (dict(thickness=100.0), "thickness"),
     (dict(shaft_angle=D(170)), "shaft_angle")],
)
def test_bad_input_is_design_error(kw, field):
    S, an, bm = D(90), D(20), D(35)
    args = dict(z1=23, z2=65, shaft_angle=S, normal_pressure_angle=an, spiral_angle=bm, pinion_hand=Hand.RIGHT,
                boundaries=_boundaries(23, 65, S, an, bm))
    args.update(kw)
    with pytest.raises(DesignError, match=field):
        design_logspiral_pair(**args)


def test_profile_inflection_near_crown_gear_is_rejected():
    """A 12/31 pair at S = 105 deg has a gear pitch angle near 80 deg: on the gear concave flank |psi - beta| passes
    90 deg, where k1 = cos(psi - beta)/(rho |sin psi|) changes sign (outside the region verified in
    docs/theory/logspiral.md, Eq. (S9) (#flank-types))."""
    with pytest.raises(GeometryError, match=r"gear concave flank: \|psi - beta\| reaches 1\d\d\.\d{4} deg"):
        _pair(12, 31, 105.0, 20.0, 25.0, Hand.RIGHT)


def test_bad_boundaries_and_pointed_teeth():
    S, an, bm = D(90), D(20), D(35)
    b1, b2 = _boundaries(23, 65, S, an, bm)
    with pytest.raises(DesignError, match="inner_cone_distance"):
        design_logspiral_pair(23, 65, S, an, bm, "RH",
                              (BlankBoundaries(120.0, 115.0, b1.root_angle, b1.face_angle), b2))
    with pytest.raises(DesignError, match="face_angle"):
        design_logspiral_pair(23, 65, S, an, bm, "RH", (BlankBoundaries(85.0, 115.0, b1.root_angle, D(19.0)), b2))
    with pytest.raises(DesignError, match="boundaries"):
        design_logspiral_pair(23, 65, S, an, bm, "RH", {Member.PINION: b1})
    with pytest.raises(GeometryError, match="pointed"):
        design_logspiral_pair(23, 65, S, an, bm, "RH",
                              (BlankBoundaries(85.0, 115.0, b1.root_angle, b1.face_angle + D(1.5)), b2))
    # the mapping form is accepted and equivalent
    p = design_logspiral_pair(23, 65, S, an, bm, "LH", {Member.PINION: b1, Member.GEAR: b2})
    q = design_logspiral_pair(23, 65, S, an, bm, Hand.LEFT, (b1, b2))
    assert p == q
