"""Property tests of LogSpiralFlank (seed 000 Eq. (16), docs/theory/logspiral.md, Eq. (S2) (#surface)) in the public
conventions."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from spiralbevel import DesignError, GeometryError, Hand, LogSpiralFlank, Side
from spiralbevel.geometry.diffgeom import surface_geometry


@st.composite
def flank_and_points(draw):
    rho0 = draw(st.floats(10.0, 500.0))
    delta = np.radians(draw(st.floats(5.0, 80.0)))
    beta = np.radians(draw(st.floats(5.0, 70.0))) * draw(st.sampled_from([1.0, -1.0]))
    side = draw(st.sampled_from(list(Side)))
    flank = LogSpiralFlank(rho0, delta, beta)
    rng = np.random.default_rng(draw(st.integers(0, 2**31 - 1)))
    psi = flank.psi_sign(side) * rng.uniform(0.02, 1.2, 30)
    psi = psi[np.abs(psi - beta) < np.pi / 2 - 0.05]  # n_out = sign(psi) n (docs/theory/logspiral.md, Eq. (S9))
    phi = rng.uniform(-1.0, 1.0, psi.size)
    return flank, side, flank.varphi_of(psi, phi), phi


@settings(max_examples=60, deadline=None)
@given(flank_and_points())
def test_invariants(data):
    flank, side, varphi, phi = data
    if varphi.size == 0:
        return
    g = flank.evaluate(varphi, phi)
    beta = flank.spiral_angle
    assert np.allclose(np.linalg.norm(g.normal, axis=-1), 1.0, atol=1e-14)
    assert np.allclose(np.linalg.norm(g.e1, axis=-1), 1.0, atol=1e-14)
    assert np.allclose(np.linalg.norm(g.e2, axis=-1), 1.0, atol=1e-14)
    assert np.allclose(np.cross(g.e1, g.e2), g.normal, atol=1e-14)
    assert np.allclose(np.einsum("...i,...i", g.e1, g.e2), 0.0, atol=1e-14)
    # n_out . r/|r| = sign(psi) sin(beta) = +sin|beta| on the convex flank, -sin|beta| on the concave flank
    rhat = g.point / np.linalg.norm(g.point, axis=-1, keepdims=True)
    expected = np.sin(abs(beta)) * (1.0 if side is Side.CONVEX else -1.0)
    assert np.allclose(np.einsum("...i,...i", g.normal, rhat), expected, atol=1e-14)
    assert np.allclose(np.linalg.norm(g.point, axis=-1), g.rho, rtol=1e-14)
    assert np.all(g.F == 0.0) and np.all(g.M == 0.0)
    # principal directions follow the parameter lines: e1 || r_varphi, e2 toe -> heel (e2 . r > 0)
    assert np.all(np.einsum("...i,...i", g.e2, g.point) > 0)
    assert flank.side_of(varphi, phi) is side
    if side is Side.CONVEX:  # convex flank: both curvatures positive (elliptic, docs/theory/logspiral.md, Eq. (S9))
        assert np.all(g.k1 > 0) and np.all(g.k2 > 0)
    else:  # concave flank: convex profile, concave lengthwise (hyperbolic)
        assert np.all(g.k1 > 0) and np.all(g.k2 < 0)


@settings(max_examples=30, deadline=None)
@given(flank_and_points())
def test_f_and_m_vanish_numerically_and_normal_is_outward_cross_product(data):
    """F = M = 0 measured by the generic module (docs/theory/logspiral.md, Eqs. (S6)-(S7)); n_out = sign(beta)
    unit(r_varphi x r_phi)."""
    flank, side, varphi, phi = data
    if varphi.size == 0:
        return
    g = flank.evaluate(varphi, phi)
    num = surface_geometry(flank.point, varphi, phi, normal_sign=np.sign(flank.spiral_angle), step=0.02)
    assert np.max(np.abs(num.F) / np.sqrt(num.E * num.G)) < 1e-9
    assert np.max(np.abs(num.M) / np.sqrt(num.L**2 + num.N**2)) < 1e-7
    assert np.max(np.abs(num.normal - g.normal)) < 1e-8


@settings(max_examples=40, deadline=None)
@given(flank_and_points())
def test_left_hand_is_mirror_of_right_hand(data):
    """y -> -y maps the beta flank at (varphi, phi) onto the -beta flank at (-varphi, -phi); convex -> convex."""
    flank, side, varphi, phi = data
    if varphi.size == 0:
        return
    mirror = flank.mirrored()
    assert mirror.hand is flank.hand.opposite
    a = flank.evaluate(varphi, phi)
    b = mirror.evaluate(-varphi, -phi)
    flip = np.array([1.0, -1.0, 1.0])
    assert mirror.side_of(-varphi, -phi) is side
    assert np.allclose(a.point * flip, b.point, rtol=1e-13, atol=1e-11)
    assert np.allclose(a.normal * flip, b.normal, atol=1e-13)  # outward stays outward
    assert np.allclose(a.k1, b.k1, rtol=1e-12) and np.allclose(a.k2, b.k2, rtol=1e-12)
    assert np.allclose(a.e2 * flip, b.e2, atol=1e-13)  # toe -> heel preserved
    assert np.allclose(a.e1 * flip, -b.e1, atol=1e-13)  # varphi reversed by the mirror


def test_singular_edge_raises_geometry_error():
    flank = LogSpiralFlank(100.0, np.radians(20.0), np.radians(35.0))
    with pytest.raises(GeometryError, match="singular"):
        flank.evaluate([0.1, 0.3], [0.1, 0.2])  # first point has psi = 0
    with pytest.raises(GeometryError, match="finite"):
        flank.evaluate(np.nan, 0.2)
    with pytest.raises(GeometryError):
        flank.side_of(0.2, 0.2)
    with pytest.raises(GeometryError, match="both branches"):
        flank.side_of([0.5, -0.5], [0.0, 0.0])
    # the c-curve itself is a valid curve of points (seed 000 Eq. (17))
    assert np.allclose(flank.c_curve(0.2), flank.point(0.2, 0.2))


@pytest.mark.parametrize(
    "args, field",
    [((0.0, 0.3, 0.5), "rho0"), ((-1.0, 0.3, 0.5), "rho0"), ((np.inf, 0.3, 0.5), "rho0"),
     ((100.0, 0.0, 0.5), "base_cone_angle"), ((100.0, np.pi / 2, 0.5), "base_cone_angle"),
     ((100.0, 0.3, 0.0), "spiral_angle"), ((100.0, 0.3, np.pi / 2), "spiral_angle"),
     ((100.0, 0.3, -2.0), "spiral_angle"), ((100.0, "x", 0.5), "base_cone_angle")],
)
def test_validation(args, field):
    with pytest.raises(DesignError, match=field):
        LogSpiralFlank(*args)


def test_broadcasting_and_readonly():
    flank = LogSpiralFlank(100.0, np.radians(20.0), np.radians(-35.0))
    g = flank.evaluate(np.linspace(-1.5, -1.0, 4)[:, None], np.linspace(0.0, 0.2, 3)[None, :])
    assert g.point.shape == (4, 3, 3) and g.k1.shape == (4, 3)
    assert flank.hand is Hand.LEFT
    with pytest.raises(ValueError):
        g.point[0, 0, 0] = 1.0
    r = g.rotated(0.3)
    c, s = np.cos(0.3), np.sin(0.3)
    expected = np.stack([c * g.point[..., 0] - s * g.point[..., 1], s * g.point[..., 0] + c * g.point[..., 1],
                         g.point[..., 2]], -1)
    assert np.allclose(r.point, expected, rtol=1e-14, atol=1e-12)
    assert np.allclose(np.cross(r.e1, r.e2), r.normal, atol=1e-14)
    assert np.array_equal(r.k1, g.k1)
