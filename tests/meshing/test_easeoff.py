"""Ease-off: exactly conjugate pairs give zero, a known flank modification is recovered with its sign, and the
conjugate flank of a face-milled gear is checked without the meshing equation (envelope as extremal azimuth)."""

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from spiralbevel.conventions import Hand, Member, Side
from spiralbevel.design.logspiral_pair import BlankBoundaries, design_logspiral_pair
from spiralbevel.errors import DesignError
from spiralbevel.generation import generate_flank
from spiralbevel.machine import seed001_blank, seed001_settings
from spiralbevel.meshing.easeoff import conjugate_pinion, easeoff
from spiralbevel.meshing.envelope import solve_envelope
from spiralbevel.meshing.flank_access import FlankAccess
from spiralbevel.meshing.kinematics import BevelPairKinematics

D = np.radians


def _pair(hand, z1=23, z2=65, S=np.radians(90), an=np.radians(20), bm=np.radians(35)):
    g1 = np.arctan2(np.sin(S), z2 / z1 + np.cos(S))
    m, at = 2 * 100.0 * np.sin(g1) / z1, np.arctan(np.tan(an) / np.cos(bm))
    bounds = []
    for g in (g1, S - g1):
        d = np.arcsin(np.sin(g) * np.cos(at))
        bounds.append(BlankBoundaries(85.0, 115.0, max(g - 1.1 * m / 100, d + D(0.15)), g + m / 100))
    return design_logspiral_pair(z1, z2, S, an, bm, hand, tuple(bounds)), BevelPairKinematics(S, z1, z2)


@pytest.fixture(scope="module")
def seed001():
    b, table = seed001_blank(), seed001_settings()
    gear = generate_flank(*table[(Member.GEAR, Side.CONVEX)], b, Member.GEAR, Side.CONVEX)
    pinion = generate_flank(*table[(Member.PINION, Side.CONCAVE)], b, Member.PINION, Side.CONCAVE)
    kin = BevelPairKinematics(b.Sigma, b.z1, b.z2)
    return pinion, gear, kin, easeoff(pinion, gear, kin)


@pytest.mark.parametrize("hand", [Hand.RIGHT, Hand.LEFT])
@pytest.mark.parametrize("side", [Side.CONCAVE, Side.CONVEX])
def test_conjugate_logspiral_pair_has_zero_easeoff(hand, side):
    """Seed 002 / docs/theory/gearing.md, Eqs. (M1)-(M8): the designed log-spiral flanks are exactly conjugate (line
    contact)."""
    pair, kin = _pair(hand)
    e = easeoff(pair.flank(Member.PINION, side), pair.flank(Member.GEAR, side.mate), kin, n_face=9, n_profile=5)
    assert np.max(np.abs(e.values)) < 1e-8
    # the conjugate points themselves coincide with the real ones once the tooth phase is removed
    assert np.max(np.linalg.norm(e.conjugate_points - e.points, axis=-1)) < 1e-8


def test_known_modification_is_recovered_with_its_sign():
    """Real pinion = conjugate log-spiral flank minus delta(psi, phi) along its outward normal (material removed for
    delta > 0, zero at the mean point): the ease-off is +delta (up to |grad delta|^2 delta ~ 1e-8 mm)."""
    pair, kin = _pair(Hand.RIGHT)
    fl = pair.flank(Member.PINION, Side.CONCAVE)
    dom = fl.domain
    um, vm = pair.mean_parameters(Member.PINION, Side.CONCAVE)
    psi_m = float(fl.surface.psi(um, vm))

    def delta(psi, phi):  # profile and lengthwise crowning, bias, and a profile slope; um
        a, b = (psi - psi_m) / 0.05, (phi - vm) / 0.1
        return 1e-3 * (20 * a * a + 10 * b * b - 5 * a * b + 3 * a)

    def modified(psi, phi):  # parametrized by (psi, phi): a plain rectangle, one branch only
        g = fl.evaluate(dom.to_varphi(psi, phi), phi)
        return g.point - delta(psi, phi)[..., None] * g.normal, g.normal

    box = ((dom.psi_min, dom.psi_max), (dom.phi_min, dom.phi_max))
    gear = pair.flank(Member.GEAR, Side.CONVEX)
    ref = easeoff(fl, gear, kin, n_face=7, n_profile=5)
    mp = pair.mean_point(Member.PINION, Side.CONCAVE).point
    g1 = kin.pitch_angle_pinion
    mean = (np.hypot(mp[0], mp[1]) * np.sin(g1) + mp[2] * np.cos(g1),
            np.hypot(mp[0], mp[1]) * np.cos(g1) - mp[2] * np.sin(g1))
    np.testing.assert_allclose(mean, (ref.mean_R, ref.mean_h), atol=1e-9)  # default mean point: R_m on the pitch cone
    e = easeoff(modified, gear, kin, grid=(ref.axial, ref.radius), pinion_bounds=box, mean=mean)
    expected = delta(e.pinion_u, e.pinion_v)
    assert np.max(np.abs(expected)) > 0.01 and np.min(expected) < 0  # several um, both signs
    np.testing.assert_allclose(e.values, expected, atol=1e-7)


def test_swapped_roles_map_back_with_the_original_kinematics(seed001):
    """Conjugate pinion points computed with the swapped pair; the ordinary (pinion -> gear) envelope solver applied
    to them must return the generating gear points."""
    pinion, gear, kin, _ = seed001
    conj, _ = conjugate_pinion(gear, kin)
    g = gear.grid(5, 4, curvature=False)
    cp, cn = conj.evaluate(g.u, g.psi_c)

    def pin_surface(u, v):  # the computed conjugate points as a (trivially parametrized) member-1 surface
        return cp, cn

    best = np.full(g.u.shape, np.inf)
    for branch in (1, -1):
        env = solve_envelope(pin_surface, kin, g.u, g.psi_c, branch=branch, strict=False)
        best = np.minimum(best, np.nan_to_num(np.linalg.norm(env.points - g.points, axis=-1), nan=np.inf))
        ok = np.linalg.norm(env.points - g.points, axis=-1) < 1e-8
        if ok.any():
            np.testing.assert_allclose(env.normals[ok], g.normals[ok], atol=1e-9)  # gear outward normals too
    assert np.max(best) < 1e-8


def test_conjugate_is_the_extremal_azimuth_of_the_gear_family(seed001):
    """Second method, no meshing equation: on the circle (axial, radius) the conjugate (enveloped) pinion flank is
    where the azimuth of the moving gear flank, as a function of the roll angle phi1, is extremal."""
    pinion, gear, kin, e = seed001
    gs = gear.grid(9, 5, curvature=False)

    def to_pinion(phi1):  # gear member frame -> pinion member frame at pinion roll phi1
        return kin.pinion_to_gear(phi1).T

    def gear_in_pinion_frame(phi1):
        M = to_pinion(phi1)

        def surface(u, v):
            f = gear.evaluate(u, v, curvature=False)
            return f.points @ M.T, f.normals @ M.T
        return FlankAccess(surface, (gs.u.ravel(), gs.psi_c.ravel()))

    for i, j in ((2, 2), (12, 6), (7, 4)):
        ax, rad = e.axial[i, j], e.radius[i, j]
        conj_az = np.arctan2(e.conjugate_points[i, j, 1], e.conjugate_points[i, j, 0]) + e.rigid_rotation
        p2 = gear.evaluate(e.gear_u[i, j], e.gear_v[i, j], curvature=False).points

        # roll angle at which this gear point crosses the plane z = axial (start value for the scan only)
        def image_axial(phi1, p2=p2, ax=ax):
            return (to_pinion(phi1) @ p2)[2] - ax

        phis = np.linspace(-np.pi, np.pi, 721)
        vals = np.array([image_axial(p) for p in phis])
        roots = [brentq(image_axial, phis[k], phis[k + 1], xtol=1e-14) for k in np.nonzero(np.diff(np.sign(vals)))[0]]

        def image_az(phi1, p2=p2):
            q = to_pinion(phi1) @ p2
            return np.arctan2(q[1], q[0])

        phi_c = min(roots, key=lambda r: abs(np.angle(np.exp(1j * (image_az(r) - conj_az)))))

        def az_of(phi1, ax=ax, rad=rad):  # azimuth where the moving gear flank cuts the circle (axial, radius)
            p, _, _, _ = gear_in_pinion_frame(phi1).locate(np.array([ax]), np.array([rad]), tol=1e-12)
            return float(np.arctan2(p[0, 1], p[0, 0]))

        a0, a1, a2 = (az_of(phi_c + s) for s in (-0.01, 0.0, 0.01))
        sign = 1.0 if a0 + a2 - 2 * a1 > 0 else -1.0  # minimum or maximum
        res = minimize_scalar(lambda p, sign=sign: sign * az_of(p), bounds=(phi_c - 0.02, phi_c + 0.02),
                              method="bounded", options=dict(xatol=1e-9))
        extremal = sign * res.fun
        assert abs(np.angle(np.exp(1j * (extremal - conj_az)))) * rad < 1e-8  # mm along the circle


def test_seed001_easeoff_is_smooth_and_nearly_parabolic(seed001):
    """The face-milled seed 001 pair: ease-off of tens of um, dominated by a quadratic (doubly-parabolic plus tilt)
    surface, and smooth: least-squares polynomial fits in (R, h) converge fast with the degree."""
    _, _, _, e = seed001
    assert e.values.shape == (15, 9) and e.branch in (1, -1)
    assert np.all(np.isfinite(e.values))
    v = e.values.ravel()
    assert np.max(np.abs(v)) > 0.01  # tens of um: the seed 001 flanks are not conjugate
    x, y = (e.R - e.mean_R).ravel(), (e.h - e.mean_h).ravel()
    rms = {}
    for deg in (2, 3, 4):
        A = np.stack([x ** i * y ** j for i in range(deg + 1) for j in range(deg + 1 - i)], -1)
        c, *_ = np.linalg.lstsq(A, v, rcond=None)
        rms[deg] = np.sqrt(np.mean((v - A @ c) ** 2))
        if deg == 2:
            assert 1 - np.sum((v - A @ c) ** 2) / np.sum((v - v.mean()) ** 2) > 0.9  # measured 0.957
            assert abs(c[0]) < rms[2]  # passes near 0 at the mean point
            fit = e.quadratic_fit()  # same basis, other order: (1, y, y^2, x, xy, x^2)
            np.testing.assert_allclose(fit["coefficients"], c[[0, 3, 1, 5, 4, 2]], rtol=1e-8, atol=1e-12)
    assert rms[3] < rms[2] / 3 and rms[4] < rms[3] / 3  # measured factors 4.8 and 3.8
    assert rms[4] < 0.005 * np.max(np.abs(v))


def test_plot_and_errors(seed001):
    pinion, gear, kin, e = seed001
    import matplotlib.pyplot as plt

    for kind in ("surface", "contour"):
        fig = e.plot(kind=kind)
        assert fig.axes
        plt.close(fig)
    with pytest.raises(DesignError, match="kind"):
        e.plot(kind="bars")
    with pytest.raises(DesignError, match="kinematics"):
        easeoff(pinion, gear, (np.pi / 2, 23, 65))
    with pytest.raises(DesignError, match="grid"):
        easeoff(lambda u, v: (u, v), gear, kin, pinion_bounds=((0, 1), (0, 1)))
    with pytest.raises(DesignError, match="branch"):
        conjugate_pinion(gear, kin, branch=2)
