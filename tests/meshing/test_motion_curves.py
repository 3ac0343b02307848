"""Motion curves and the predesigned combined motion curve of seed 001 §2 (Eqs. (1)-(6); docs/theory/tca.md, Eqs.
(T1)-(T4); docs/theory/example.md#table-2)."""

import numpy as np
import pytest
from scipy.optimize import brentq
from hypothesis import given, settings
from hypothesis import strategies as st

from spiralbevel.errors import DesignError
from spiralbevel.meshing.motion_curves import (
    ARCSEC, CombinedMotionCurve, compare_te, fit_quartic, parabola_through, parabolic_te, quartic_roots, quartic_te,
    seed001_cmc, seed001_control_points)

T = 2 * np.pi / 23  # one mesh cycle of the 23-tooth pinion, rad


@settings(max_examples=30, deadline=None)
@given(st.floats(1e-4, 1e-2), st.floats(-1e-3, 1e-3), st.floats(-1.0, -1e-2))
def test_fit_quartic_recovers_coefficients(a2, a3, a4):
    x = np.linspace(-0.1, 0.1, 10)
    got = fit_quartic(x, quartic_te(x, (a2, a3, a4)))
    np.testing.assert_allclose(got, (a2, a3, a4), rtol=1e-6, atol=1e-12)


def test_roots_against_numpy():
    a = (2e-3, 3e-4, -0.13)
    b1, b3 = quartic_roots(a)
    r = np.sort(np.roots([a[2], a[1], a[0], 0, 0]).real)
    np.testing.assert_allclose([b1, b3], [r[0], r[-1]], rtol=1e-12)
    assert abs(quartic_te(b1, a)) < 1e-18 and abs(quartic_te(b3, a)) < 1e-18


def test_parabola_general_and_printed_symmetric_form():
    b1, b2, b3 = -0.05, 2e-5, 0.08
    np.testing.assert_allclose(parabola_through([b1, 0.0, b3], b1, b2, b3), [0, b2, 0], atol=1e-20)
    x = np.linspace(-0.1, 0.1, 7)
    # docs/theory/tca.md, Eq. (T3): the printed b2 - (b2/b1^2) x^2 is the case b3 = -b1
    np.testing.assert_allclose(parabola_through(x, -0.05, b2, 0.05), b2 - b2 / 0.05**2 * x**2, rtol=1e-12)


def test_parabolic_te():
    assert parabolic_te(0.1, -0.00489) == pytest.approx(-0.00489 * 0.01)


def test_symmetric_quartic_gives_c1_at_both_points():
    a2, a4 = 2e-3, -0.13
    c = CombinedMotionCurve.from_quartic((a2, 0.0, a4))
    assert c.b2 == pytest.approx(-(a2**2) / a4, rel=1e-12)  # b2 = a2 b1^2 = -a2^2/a4
    jumps = c.continuity()
    for k in ("c0_b1", "c0_b3", "c1_b1", "c1_b3"):
        assert abs(jumps[k]) < 1e-15


def test_seed001_cmc_regenerated():
    c = seed001_cmc()
    x = np.linspace(-2 * T, 2 * T, 200001)
    y = c(x)
    # Eq. (6): the final CMC has its maximum on the abscissa
    assert y.max() <= 1e-18
    assert y.max() > -1e-6 * ARCSEC
    # depth of the TE envelope of neighbouring pairs over one cycle = the predesigned 3 arcsec (Table 2),
    # recomputed here: smooth maximum from a dense grid, minimum at the crossing of pair 0 with pair +1 (brentq)
    xc = np.linspace(-T / 2, T / 2, 200001)
    env = np.max(np.stack([c(xc - k * T) for k in (-2, -1, 0, 1, 2)]), axis=0)
    i = int(np.argmin(env))
    t = brentq(lambda s: c(s) - c(s + T), xc[i] - 1e-4, xc[i] + 1e-4, xtol=1e-15) if xc[i] < 0 else \
        brentq(lambda s: c(s) - c(s - T), xc[i] - 1e-4, xc[i] + 1e-4, xtol=1e-15)
    assert (env.max() - c(t)) / ARCSEC == pytest.approx(3.0, rel=1e-9)
    assert c(t) <= env.min() + 1e-18
    # the mean point M is a local minimum below the abscissa ("an error exists at the mean contact point")
    assert c(0.0) < 0 and c.slope(0.0) == pytest.approx(0.0, abs=1e-15)
    # B1 < 0 < B3 inside the cycle, C0 at both, C1 jump equal and opposite-signed parabola slopes
    assert -T / 2 < c.b1 < 0 < c.b3 < T / 2
    j = c.continuity()
    assert abs(j["c0_b1"]) < 1e-18 and abs(j["c0_b3"]) < 1e-18
    # with a3 != 0 one b2 cannot give C1 at both points; least squares makes the two jumps equal
    assert c.a[1] != 0
    assert j["c1_b1"] == pytest.approx(j["c1_b3"], rel=1e-9)
    # the slope jump is small against the slopes that meet there
    assert abs(j["c1_b1"]) < 0.05 * abs(c.slope(c.b1 - 1e-12))


def test_control_points_fit_step1():
    x, y = seed001_control_points()
    assert len(x) == 10  # A_1..A_10 (seed 001 §2.2 Step 1)
    a = fit_quartic(x, y)
    assert a[0] > 0 > a[2]


def test_bad_control_points():
    with pytest.raises(DesignError):
        CombinedMotionCurve.from_quartic((-1e-3, 0.0, -0.1))  # no real non-zero roots
    with pytest.raises(DesignError):
        fit_quartic([0.1], [1.0])


def test_compare_te_reports_max_deviation():
    c = seed001_cmc()
    x = np.linspace(-T / 2, T / 2, 41)
    bump = 0.1 * ARCSEC * np.sin(np.pi * (x / T + 0.5)) ** 2
    cmp = compare_te(x, c.envelope(x, T) + bump, c, period=T, align="none")
    assert cmp.max_deviation == pytest.approx(0.1 * ARCSEC, rel=1e-3)
    assert cmp.relative == pytest.approx(cmp.max_deviation / cmp.depth)
    te = c.envelope(x, T) + 5e-6
    assert compare_te(x, te, c, period=T, align="max").max_deviation < 1e-18
