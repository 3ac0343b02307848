"""Head cutter (seed 001 Eqs. (7)-(10), docs/theory/generation.md, Eqs. (G1)-(G3)): normals, fillet junction, principal
curvatures, validation."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from spiralbevel.conventions import Side
from spiralbevel.errors import DesignError, GeometryError
from spiralbevel.machine import Blade, HeadCutter


def _cutter(blade, rp=math.inf):
    return HeadCutter(113.155, math.radians(23 + 50 / 60), 2.29, 1.31, blade, profile_radius=rp, profile_ref=3.0)


def test_blade_sides_and_signs():
    # docs/theory/generation.md, Eqs. (G1)-(G3): s = +1 outer blade / concave side, s = -1 inner blade / convex side
    assert Blade.OUTER.sign == 1 and Blade.OUTER.side is Side.CONCAVE
    assert Blade.INNER.sign == -1 and Blade.INNER.side is Side.CONVEX
    assert Blade.for_side(Side.CONVEX) is Blade.INNER


def test_nominal_radius_table4():
    # seed 001 Table 4: R_h2 = 113.155 = R_c2 - W/2 with R_c2 = 114.3, W = 2.29 (docs/theory/example.md, exact)
    assert _cutter(Blade.INNER).nominal_radius == pytest.approx(114.3, abs=1e-12)


@pytest.mark.parametrize("blade", list(Blade))
def test_straight_and_fillet_match_printed_equations(blade):
    c = _cutter(blade)
    s, a, R, rf = blade.sign, c.blade_angle, c.point_radius, c.edge_radius
    u0, uj = c.fillet_range
    assert uj == pytest.approx(rf * (1 - math.sin(a)) / math.cos(a), rel=1e-14)   # Eq. (7) lower limit
    assert uj - u0 == pytest.approx(rf * (math.pi / 2 - a), rel=1e-14)
    th = 0.37
    u = np.array([uj + 0.5, uj + 4.0])
    p = c.points(u, th)
    expect = np.stack([(R + s * u * math.sin(a)) * math.cos(th), (R + s * u * math.sin(a)) * math.sin(th),
                       -u * math.cos(a)], -1)                                       # Eq. (7)
    np.testing.assert_allclose(p, expect, rtol=1e-14)
    lam = np.array([0.0, 0.3, math.pi / 2 - a])
    T = R - s * rf * (1 - math.sin(a)) / math.cos(a)
    pf = c.points(uj - rf * (math.pi / 2 - a - lam), th)
    expect = np.stack([(T + s * rf * np.sin(lam)) * math.cos(th), (T + s * rf * np.sin(lam)) * math.sin(th),
                       -rf * (1 - np.cos(lam))], -1)                                # Eq. (8)
    np.testing.assert_allclose(pf, expect, rtol=1e-13, atol=1e-12)


@pytest.mark.parametrize("blade", list(Blade))
@pytest.mark.parametrize("rp", [math.inf, 250.0])
def test_normals_are_normalised_cross_products(blade, rp):
    # Eqs. (9)-(10): n_h = r_u x r_theta / |.| (docs/theory/generation.md#head-cutter: derivative of the fillet w.r.t.
    # lambda)
    c = _cutter(blade, rp)
    u0, uj = c.fillet_range
    u = np.array([u0 + 0.2, 0.5 * (u0 + uj), uj + 0.3, uj + 5.0])
    th = np.array([0.1, 1.0, -2.0, 2.5])
    h = 1e-6
    ru = (c.points(u + h, th) - c.points(u - h, th)) / (2 * h)
    rt = (c.points(u, th + h) - c.points(u, th - h)) / (2 * h)
    n = np.cross(ru, rt)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    np.testing.assert_allclose(c.normals(u, th), n, atol=1e-8)


@pytest.mark.parametrize("blade", list(Blade))
@pytest.mark.parametrize("rp", [math.inf, 250.0])
def test_fillet_joins_blade_with_continuous_normal(blade, rp):
    c = _cutter(blade, rp)
    _, uj = c.fillet_range
    e = 1e-9
    np.testing.assert_allclose(c.points(uj - e, 0.3), c.points(uj + e, 0.3), atol=1e-8)
    np.testing.assert_allclose(c.normals(uj - e, 0.3), c.normals(uj + e, 0.3), atol=1e-8)
    # tip of the fillet: normal along the cutter axis, point in the tip plane
    u0, _ = c.fillet_range
    np.testing.assert_allclose(c.normals(u0, 0.3), [0, 0, blade.sign], atol=1e-14)
    assert abs(c.points(u0, 0.3)[2]) < 1e-14


def test_arc_blade_tangent_to_straight_blade_at_reference():
    c, s = _cutter(Blade.OUTER, 250.0), _cutter(Blade.OUTER)
    np.testing.assert_allclose(c.points(3.0, 0.2), s.points(3.0, 0.2), atol=1e-12)
    np.testing.assert_allclose(c.normals(3.0, 0.2), s.normals(3.0, 0.2), atol=1e-14)
    # profile crowning: the arc deviates quadratically, ~ d^2 / (2 rp)
    d = 2.0
    dev = np.linalg.norm(c.points(3.0 + d, 0.2) - s.points(3.0 + d, 0.2))
    assert dev == pytest.approx(d * d / (2 * 250.0), rel=1e-2)


@settings(max_examples=25, deadline=None)
@given(blade=st.sampled_from(list(Blade)), frac=st.floats(0.02, 0.98), th=st.floats(-3.0, 3.0),
       rp=st.sampled_from([math.inf, 300.0]))
def test_principal_curvatures_against_numerical_shape_operator(blade, frac, th, rp):
    c = _cutter(blade, rp)
    u0, uj = c.fillet_range
    u = u0 + frac * (uj + 8.0 - u0)
    if abs(u - uj) < 0.05:
        u += 0.1
    km, kc, em, ec = c.principal_curvatures(u, th)
    n_in = blade.sign * c.normals(u, th)
    np.testing.assert_allclose(np.cross(em, ec), n_in, atol=1e-14)
    h = 1e-3 if u < uj else 1e-2

    def f(a, b):
        return c.points(a, b)
    ru = (f(u + h, th) - f(u - h, th)) / (2 * h)
    ht = 1e-4
    rt = (f(u, th + ht) - f(u, th - ht)) / (2 * ht)
    ruu = (f(u + h, th) - 2 * f(u, th) + f(u - h, th)) / h**2
    rtt = (f(u, th + ht) - 2 * f(u, th) + f(u, th - ht)) / ht**2
    # convex = positive w.r.t. n_out = -n_in: kappa = II(n_in)/I with II = r_xx . n_in
    k_num_m = ruu @ n_in / (ru @ ru)
    k_num_c = rtt @ n_in / (rt @ rt)
    scale = max(abs(km), abs(kc), 1e-3)
    assert abs(k_num_m - km) < 1e-5 * scale + 1e-7
    assert abs(k_num_c - kc) < 1e-5 * scale
    if math.isinf(rp) and u > uj:
        assert km == 0.0
        rho = c.point_radius + blade.sign * u * math.sin(c.blade_angle)
        assert kc == pytest.approx(-blade.sign * math.cos(c.blade_angle) / rho, rel=1e-14)


def test_bad_cutters():
    with pytest.raises(DesignError, match="point_radius"):
        HeadCutter(-1.0, 0.4, 2.29, 1.31)
    with pytest.raises(DesignError, match="blade_angle"):
        HeadCutter(100.0, 2.0, 2.29, 1.31)
    with pytest.raises(DesignError, match="edge_radius"):
        HeadCutter(100.0, 0.4, 2.29, float("nan"))
    with pytest.raises(GeometryError, match="edge_radius"):       # fillet wider than half the point width
        HeadCutter(100.0, 0.4, 2.29, 4.0)
    with pytest.raises(DesignError, match="profile_radius"):
        HeadCutter(100.0, 0.4, 2.29, 1.0, profile_radius=-5.0)
