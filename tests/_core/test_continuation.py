"""Pseudo-arclength continuation (``_core.continuation``) against a plain per-step solve and a closed-form curve."""

import math

import numpy as np
import pytest

from spiralbevel._core.continuation import arclength_continuation
from spiralbevel._core.newton import solve_batched

# a rotation that couples the two unknowns, so that neither equation is solved by one unknown alone
Q = np.array([[math.cos(0.5), -math.sin(0.5)], [math.sin(0.5), math.cos(0.5)]])


def _smooth(x, t):
    """A homotopy without turning point: g(x) = g(x0) + t (g1 - g(x0)) with g a monotone map (Jacobian positive
    definite everywhere)."""
    y = Q @ x
    g = np.array([y[0] + 0.2 * y[0] ** 3 + 0.1 * y[1], y[1] + 0.3 * math.sinh(y[1]) + 0.1 * y[0]])
    return g - t * np.array([3.0, -2.0])


def test_without_turning_point_the_path_is_the_per_step_solution():
    res = arclength_continuation(_smooth, np.zeros(2), tol=1e-12, path_tol=1e-12)
    assert res.converged and res.t == 1.0 and res.turning_points == 0
    # every point of the path against a plain Newton solve at its own t, started from the previous plain solution
    x = np.zeros(2)
    for *xk, tk in res.path[1:]:
        r = solve_batched(lambda z, tk=tk: _smooth(z, tk), x, tol=1e-13)
        assert bool(r.converged)
        np.testing.assert_allclose(xk, r.x, atol=1e-10)   # both solve to 1e-12 in a well-conditioned system
        x = r.x
    assert res.residual < 1e-12


A = 0.3   # phi(s) = s + A sin(2 pi s) turns back where cos(2 pi s) = -1 / (2 pi A), twice for A > 1 / (2 pi)


def _phi(s):
    return s + A * np.sin(2.0 * np.pi * s)


def _folded(x, t):
    """H(x, t) = (phi(y0) - t, y1 - cos y0) with y = Q x: the solution curve is y = (s, cos s), t = phi(s), which
    rises to a turning point, falls to a second one and rises again to t = 1 at s = 1."""
    y = Q @ x
    return np.array([_phi(y[0]) - t, y[1] - math.cos(y[0])])


def test_passes_two_turning_points_to_the_closed_form_solution():
    x0 = Q.T @ np.array([0.0, 1.0])
    res = arclength_continuation(_folded, x0, tol=1e-12, h_max=0.1)
    assert res.converged and res.turning_points == 2
    np.testing.assert_allclose(Q @ res.x, [1.0, math.cos(1.0)], atol=1e-11)   # s = 1, the end of the branch
    # every path point lies on the closed-form curve (the corrector tolerance, 100 tol, bounds the distance)
    y = res.path[:, :2] @ Q.T
    np.testing.assert_allclose(res.path[:, 2], _phi(y[:, 0]), atol=1e-9)
    np.testing.assert_allclose(y[:, 1], np.cos(y[:, 0]), atol=1e-9)
    # the path is followed in order (s grows along it) and its t passes both turning points: up to phi at
    # cos(2 pi s) = -1/(2 pi A), s in (0, 1/2), down to phi at the mirror point s in (1/2, 1)
    assert np.all(np.diff(y[:, 0]) > 0)
    s_up = math.acos(-1.0 / (2.0 * math.pi * A)) / (2.0 * math.pi)
    t_up, t_down = _phi(s_up), _phi(1.0 - s_up)
    assert t_down < t_up
    first, second = y[:, 0] < 0.5, y[:, 0] > 0.5
    # the steps sample a fold to about h_max^2 in t (the curve is flat in t there)
    assert res.path[first, 2].max() == pytest.approx(t_up, abs=1e-2) and res.path[first, 2].max() <= t_up
    assert res.path[second, 2].min() == pytest.approx(t_down, abs=1e-2) and res.path[second, 2].min() >= t_down


def test_plain_continuation_stalls_at_the_turning_point():
    """The reason for arclength: stepping t and solving for x from the last solution leaves the branch past the
    first turning point (no nearby solution there); Newton either fails or jumps far along the curve."""
    x, t, dt = Q.T @ np.array([0.0, 1.0]), 0.0, 0.05
    while t < 1.0 - 1e-12:
        r = solve_batched(lambda z, t1=t + dt: _folded(z, t1), x, tol=1e-12, max_iter=20)
        if not bool(r.converged) or np.linalg.norm(r.x - x) > 0.3:   # failed or jumped past the fold
            break
        x, t = r.x, t + dt
    s_up = math.acos(-1.0 / (2.0 * math.pi * A)) / (2.0 * math.pi)
    assert t == pytest.approx(_phi(s_up), abs=dt)


def test_a_curve_that_turns_away_from_t1_is_reported_not_raised():
    # g(x) = x^3 - 3x from x = -0.5 toward g = -3: the branch turns back at x = 1 (g = -2) and never returns
    res = arclength_continuation(lambda x, t: x**3 - 3 * x - (1.375 + t * (-3.0 - 1.375)), np.array([-0.5]),
                                 max_steps=200, t_min=-1.0)
    assert not res.converged and res.turning_points == 1 and res.t < 1.0
    assert np.isfinite(res.residual)
