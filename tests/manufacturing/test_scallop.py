"""Exact scallop formula of a ball on a surface of constant curvature, against direct 2-D geometry."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

from spiralbevel.manufacturing.scallop import flat_stepover, max_scallop, scallop_for_stepover, stepover_for_scallop


def _scallop_2d(R, w, kappa, n=4001):
    """Largest normal distance from a circular (or straight) section to the union of two balls w apart (arc).

    Brute force: sample the surface between the two contact points, shoot the outward normal, and find where it
    first enters one of the two ball circles (closest root of |P + s n - C|^2 = R^2).
    """
    if abs(kappa) * w < 1e-9:  # flat within rounding: 1/kappa would swamp the coordinates
        u = np.linspace(0.0, w, n)
        P = np.stack([u, np.zeros_like(u)], -1)
        N = np.tile([0.0, 1.0], (n, 1))
        C = [np.array([0.0, R]), np.array([w, R])]
    else:
        rs = 1.0 / abs(kappa)
        th = np.linspace(0.0, w * abs(kappa), n)
        radial = np.stack([np.sin(th), np.cos(th)], -1)
        if kappa > 0:  # centre inside the material, outward normal = radial
            P, N = rs * radial, radial
            C = [(rs + R) * radial[0], (rs + R) * radial[-1]]
        else:  # centre on the tool side at (0, 0); surface below it; outward normal points to the centre
            P, N = -rs * radial, radial
            C = [-(rs - R) * radial[0], -(rs - R) * radial[-1]]
    best = np.full(n, np.inf)
    for c in C:
        d = c - P
        a = (d * N).sum(-1)
        disc = R * R - (d * d).sum(-1) + a * a
        s = np.where(disc >= 0, a - np.sqrt(np.maximum(disc, 0.0)), np.inf)
        best = np.minimum(best, s)
    return float(best.max())


@pytest.mark.parametrize("kappa", [0.0, 0.02, 0.2, -0.02, -0.15])
def test_scallop_matches_brute_force_geometry(kappa):
    R, h = 4.0, 0.05
    w = float(stepover_for_scallop(R, h, kappa))
    # brute force samples 4001 points: the cusp is missed by at most (dx)^2 * curvature, about 1e-8 mm here
    assert _scallop_2d(R, w, kappa) == pytest.approx(h, rel=1e-6)


def test_flat_limit_and_flat_formula():
    R, h = 3.0, 0.01
    w0 = flat_stepover(R, h)
    assert w0 == pytest.approx(2 * math.sqrt(2 * R * h - h * h), rel=1e-15)
    assert float(stepover_for_scallop(R, h, 0.0)) == pytest.approx(w0, rel=1e-15)
    for k in (1e-9, -1e-9, 1e-5, -1e-5):  # continuous through kappa = 0, O(kappa) change
        assert float(stepover_for_scallop(R, h, k)) == pytest.approx(w0, rel=10 * abs(k) * R)
    assert float(scallop_for_stepover(R, w0, 0.0)) == pytest.approx(h, rel=1e-12)


def test_convex_needs_smaller_concave_allows_larger_stepover():
    R, h = 3.0, 0.01
    w0 = flat_stepover(R, h)
    assert stepover_for_scallop(R, h, 0.05) < w0 < stepover_for_scallop(R, h, -0.05)


def test_classical_small_scallop_approximation():
    # Lin & Koren style w ~ sqrt(8 h R rho/(rho +- R)); relative error O(h/R)
    R, h = 5.0, 1e-6
    for rho, sign in ((20.0, 1), (20.0, -1), (200.0, 1)):
        approx = math.sqrt(8 * h * R * rho / (rho + sign * R))
        assert float(stepover_for_scallop(R, h, sign / rho)) == pytest.approx(approx, rel=1e-5)


@settings(max_examples=60, deadline=None)
@given(R=st.floats(0.5, 20.0), frac=st.floats(1e-4, 0.9), kr=st.floats(-0.9, 5.0))
def test_inverse_roundtrip(R, frac, kr):
    kappa = kr / R
    h = frac * min(R, float(max_scallop(R, kappa)))
    w = float(stepover_for_scallop(R, h, kappa))
    if w * abs(kappa) >= 2 * math.pi - 1e-9:  # concave case where the balls always meet
        return
    assert float(scallop_for_stepover(R, w, kappa)) == pytest.approx(h, rel=1e-9, abs=1e-12 * R)


@settings(max_examples=25, deadline=None)
@given(R=st.floats(1.0, 10.0), frac=st.floats(1e-3, 0.3), kr=st.floats(-0.8, 2.0))
def test_brute_force_random(R, frac, kr):
    h = frac * R
    kappa = kr / R
    w = float(stepover_for_scallop(R, h, kappa))
    assert _scallop_2d(R, w, kappa) == pytest.approx(h, rel=1e-5)


def test_scallop_root_is_the_cusp_on_the_bisector():
    # independent of the brute force: intersect the two ball circles with brentq on the bisector (convex case)
    R, h, kappa = 2.0, 0.1, 0.1
    rs = 1 / kappa
    w = float(stepover_for_scallop(R, h, kappa))
    half = 0.5 * w * kappa
    c1 = (rs + R) * np.array([0.0, 1.0])
    f = lambda r: np.hypot(r * math.sin(half) - c1[0], r * math.cos(half) - c1[1]) - R  # noqa: E731
    r_cusp = brentq(f, rs, rs + R)
    assert r_cusp - rs == pytest.approx(h, rel=1e-12)


@pytest.mark.parametrize("kappa", [0.0, 0.3, -0.1])
def test_max_scallop_is_the_tangency_of_the_two_balls(kappa):
    # at the tangency the ball circles touch at one point: largest stepover with a cusp, scallop h_max
    R = 2.0
    hmax = float(max_scallop(R, kappa))
    assert (hmax < R) if kappa > 0 else (hmax >= R)
    if kappa == 0:
        w = 2 * R  # two flat-surface balls touch when their centres are 2R apart
    else:
        a = abs(1 / kappa + R)
        w = 2 * math.asin(R / a) / abs(kappa)
    # just inside the tangency (w (1 - 1e-13)) so the touching point is found despite rounding: the scallop then
    # falls short of h_max by about R sqrt(2e-13) ~ 1e-6 R
    assert _scallop_2d(R, w * (1 - 1e-13), kappa, n=20001) == pytest.approx(hmax, rel=3e-6)
    if kappa > 0:  # above the limit (still < R) there is no stepover: NaN from the kernel, never a spurious root
        assert hmax * 1.01 < R and np.isnan(stepover_for_scallop(R, hmax * 1.01, kappa))
    assert float(max_scallop(R, -0.6 / R)) == math.inf


def _stepover_all_branches(R, h, k):
    """The formula of :func:`stepover_for_scallop` with every branch evaluated and selected elementwise (the form the
    kernel had before its shortcut for arrays without full circles or near-zero arguments)."""
    q = np.sqrt(h * (2.0 * R - h) / ((1.0 + k * R) * (1.0 + k * h)))
    x = 0.5 * np.abs(k) * q
    full = x >= 1.0
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        w_full = np.where(full, 2.0 * np.pi / np.where(k == 0, 1.0, np.abs(k)), 0.0)
        xm = np.minimum(x, 1.0)
        small = np.abs(xm) < 1e-3
        xs = np.where(small, 1.0, xm)
        ratio = np.where(small, 1.0 + xm**2 / 6.0 + 3.0 * xm**4 / 40.0, np.arcsin(np.clip(xs, -1.0, 1.0)) / xs)
        hmax = np.where(1.0 + 2.0 * R * k > 0, 2.0 * R / (1.0 + np.sqrt(np.maximum(1.0 + 2.0 * R * k, 0.0))), np.inf)
    return np.where(h < hmax, np.where(full, w_full, 2.0 * q * ratio), np.nan)


@pytest.mark.parametrize("mix", ["march", "with_small", "with_full", "with_both"])
def test_shortcut_gives_the_same_bits_as_every_branch(mix):
    """The kernel skips the series and the full-circle branch when no element needs them (the tool-path march): the
    result must be bit for bit the elementwise selection of all branches, with and without such elements."""
    rng = np.random.default_rng(7)
    R, h = 2.0, 0.005
    k = rng.uniform(-0.2, 0.3, 257)                         # march-like curvatures: x of order 1e-2
    if mix in ("with_small", "with_both"):
        k[::17] = rng.uniform(-1e-6, 1e-6, k[::17].size)      # x below 1e-3: the series
    if mix in ("with_full", "with_both"):
        k[5::23] = -0.4999                                    # concave, 1 + kR near 0: any stepover, full circle
    got = stepover_for_scallop(R, h, k)
    ref = _stepover_all_branches(R, h, k)
    assert np.array_equal(got, ref, equal_nan=True)
    assert (mix in ("with_full", "with_both")) == bool(np.any(0.5 * np.abs(k) * np.sqrt(
        h * (2 * R - h) / ((1 + k * R) * (1 + k * h))) >= 1.0))   # the case really takes the branch it names
