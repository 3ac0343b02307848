"""Generic numerical differential geometry (geometry/diffgeom.py) against closed forms.

Independent second methods: seed 000 closed forms (docs/theory/logspiral.md, Eq. (S2) (#surface)) for the log-spiral
flank; textbook curvatures of a
sphere (1/R, 1/R), a cylinder (1/R, 0) and a torus (1/a, cos v/(c + a cos v)) under skewed parametrizations
(F != 0, M != 0), so no F = M = 0 shortcut can pass.
"""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from spiralbevel import LogSpiralFlank
from spiralbevel._core.rotations import rot_axis
from spiralbevel.geometry.diffgeom import derivatives, surface_geometry

RTOL = 1e-8  # task requirement for closed form vs generic module (measured ~1e-10)


def _rel(a, b):
    return np.max(np.abs(a - b) / np.abs(b))


@st.composite
def flank_points(draw):
    rho0 = draw(st.floats(20.0, 300.0))
    delta = np.radians(draw(st.floats(10.0, 75.0)))
    beta = np.radians(draw(st.floats(10.0, 60.0))) * draw(st.sampled_from([1.0, -1.0]))
    sign = draw(st.sampled_from([1.0, -1.0]))  # branch: sign of psi
    seed = draw(st.integers(0, 2**31 - 1))
    rng = np.random.default_rng(seed)
    psi = sign * rng.uniform(0.05, 0.9, 40)
    keep = np.cos(psi - beta) > 0.2  # inside |psi - beta| < 90 deg with margin (docs/theory/logspiral.md, Eq. (S9))
    psi = psi[keep] if keep.any() else sign * np.full(1, 0.05)
    phi = rng.uniform(-0.5, 0.5, psi.size)
    return LogSpiralFlank(rho0, delta, beta), psi / np.sin(delta) + phi, phi


@settings(max_examples=40, deadline=None)
@given(flank_points())
def test_generic_module_matches_closed_forms(data):
    flank, varphi, phi = data
    exact = flank.evaluate(varphi, phi)
    # the outward normal is sign(beta) unit(r_varphi x r_phi) on both branches (docs/theory/logspiral.md, Eqs. (S4),
    # (S9), n_out = sign(psi) n)
    num = surface_geometry(flank.point, varphi, phi, normal_sign=np.sign(flank.spiral_angle))
    assert np.max(np.abs(num.normal - exact.normal)) < 1e-9
    for key in ("E", "G", "L", "N", "k1", "k2"):
        assert _rel(getattr(num, key), getattr(exact, key)) < RTOL, key
    assert np.max(np.abs(num.F) / np.sqrt(exact.E * exact.G)) < 1e-10
    assert np.max(np.abs(num.M) / np.abs(exact.N)) < 1e-8
    assert np.max(np.abs(num.e1 - exact.e1)) < 1e-8
    assert np.max(np.abs(num.e2 - exact.e2)) < 1e-8
    assert _rel(num.gaussian_curvature, exact.gaussian_curvature) < RTOL
    assert _rel(num.mean_curvature, exact.mean_curvature) < 1e-7 * np.max(
        np.abs(exact.k1) / np.abs(exact.mean_curvature))


def _sphere(R, c):
    def f(u, v):
        th, ph = 1.0 + u + 0.3 * v, v - 0.2 * u  # skewed: F != 0 and M != 0
        return c + R * np.stack([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)], -1)
    return f


def test_sphere_skewed_parametrization_outward_normal_is_convex():
    R, c = 37.0, np.array([1.0, -2.0, 3.0])
    f = _sphere(R, c)
    u, v = np.linspace(-0.4, 0.4, 9), np.linspace(-1.0, 2.0, 9)
    g = surface_geometry(f, u, v, reference=f(u, v) - c)
    assert np.max(np.abs(g.F)) > 1.0 and np.max(np.abs(g.M)) > 1e-2  # the test really is non-orthogonal
    assert np.allclose(g.k1, 1 / R, rtol=1e-9) and np.allclose(g.k2, 1 / R, rtol=1e-9)
    assert np.allclose(g.gaussian_curvature, 1 / R**2, rtol=1e-9)
    assert np.allclose(g.mean_curvature, 1 / R, rtol=1e-9)
    inward = surface_geometry(f, u, v, reference=c - f(u, v))
    assert np.allclose(inward.k1, -1 / R, rtol=1e-9)  # seen from inside the sphere is concave


def test_cylinder_skewed_parametrization_directions():
    R = 12.5

    def f(u, v):
        a = u + v
        return np.stack([R * np.cos(a), R * np.sin(a), 2.0 * u - 0.5 * v], -1)

    u, v = np.linspace(-1, 1, 7), np.linspace(0.3, 2.0, 7)
    p = f(u, v)
    g = surface_geometry(f, u, v, reference=p * [1, 1, 0])
    kmax, kmin = g.k_max, g.k_min
    assert np.allclose(kmax, 1 / R, rtol=1e-9) and np.allclose(kmin, 0.0, atol=1e-10)
    circ = np.stack([-np.sin(u + v), np.cos(u + v), 0 * u], -1)
    d_max = np.where((g.k1 > g.k2)[:, None], g.e1, g.e2)
    assert np.allclose(np.abs(np.einsum("...i,...i", d_max, circ)), 1.0, atol=1e-9)
    assert np.allclose(np.cross(g.e1, g.e2), g.normal, atol=1e-12)
    assert np.all(np.einsum("...i,...i", g.e1, g.r_u) > 0)


def test_torus_orthogonal_reference():
    a, c = 3.0, 10.0

    def f(u, v):
        return np.stack([(c + a * np.cos(v)) * np.cos(u), (c + a * np.cos(v)) * np.sin(u), a * np.sin(v)], -1)

    u, v = np.linspace(0, 6, 11), np.linspace(-3, 3, 11)
    p = f(u, v)
    centre = np.stack([c * np.cos(u), c * np.sin(u), 0 * u], -1)
    g = surface_geometry(f, u, v, reference=p - centre)
    # u-direction (parallel circle): cos v/(c + a cos v); v-direction (meridian of the tube): 1/a
    assert np.allclose(g.k1, np.cos(v) / (c + a * np.cos(v)), rtol=1e-8, atol=1e-12)
    assert np.allclose(g.k2, 1 / a, rtol=1e-9)


@settings(max_examples=20, deadline=None)
@given(st.floats(-np.pi, np.pi), st.floats(-1, 1), st.floats(-1, 1), st.floats(0.1, 1), st.floats(-50, 50),
       st.sampled_from([1.0, -1.0]))
def test_rigid_motion_invariance(angle, ax, ay, az, shift, branch):
    flank = LogSpiralFlank(120.0, np.radians(25.0), np.radians(30.0))
    Rm = rot_axis([ax, ay, az], angle)
    T = np.array([shift, -0.5 * shift, 2.0])

    def moved(u, v):
        return flank.point(u, v) @ Rm.T + T

    phi = np.linspace(-0.3, 0.3, 5)
    varphi = phi + branch * 0.3 / np.sin(flank.base_cone_angle)
    g0 = surface_geometry(flank.point, varphi, phi, normal_sign=1.0)
    g1 = surface_geometry(moved, varphi, phi, normal_sign=1.0)
    assert np.allclose(g1.k1, g0.k1, rtol=1e-9) and np.allclose(g1.k2, g0.k2, rtol=1e-9)
    assert np.allclose(g1.normal, g0.normal @ Rm.T, atol=1e-11)
    assert np.allclose(g1.e1, g0.e1 @ Rm.T, atol=1e-9)
    assert np.allclose(g1.E, g0.E, rtol=1e-11) and np.allclose(g1.L, g0.L, rtol=1e-9)


def test_central_difference_order_two_without_extrapolation():
    """levels=1 is plain central differences: halving h divides the error by ~4 (O(h^2))."""
    flank = LogSpiralFlank(100.0, np.radians(20.0), np.radians(35.0))
    exact = flank.evaluate(0.5, 0.1)
    errs = []
    for h in (0.08, 0.04, 0.02):
        d = derivatives(flank.point, 0.5, 0.1, step=h, levels=1)
        n = exact.normal
        errs.append(abs(-np.dot(d.r_uu, n) - exact.L))
    assert 3.6 < errs[0] / errs[1] < 4.4 and 3.6 < errs[1] / errs[2] < 4.4
