"""Load-distribution solver (seed 001 Eq. (18), docs/theory/ltca.md, Eqs. (L1)-(L4)) against brute-force enumeration."""

import itertools

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from spiralbevel._core.ltca import primal_active_set
from spiralbevel.errors import DesignError, NoContactError
from spiralbevel.meshing.ltca.lcp import solve_load_distribution


def _random_problem(seed, n):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(n, n))
    C = (A @ A.T + 0.3 * n * np.eye(n)) * 1e-5  # mm/N
    w = rng.uniform(-0.002, 0.01, n)  # mm, some negative
    h = rng.uniform(20.0, 80.0, n)  # mm
    return C, w, h


def _brute_force(C, w, h, T):
    """Enumerate every loaded set S, keep the unique one whose solution is feasible and complementary."""
    n = len(w)
    found = []
    for k in range(1, n + 1):
        for S in itertools.combinations(range(n), k):
            S = list(S)
            K = np.zeros((k + 1, k + 1))
            K[:k, :k] = C[np.ix_(S, S)]
            K[:k, k] = -h[S]
            K[k, :k] = h[S]
            sol = np.linalg.solve(K, np.concatenate([-w[S], [T]]))
            F = np.zeros(n)
            F[S] = sol[:k]
            lam = sol[k]
            d = C @ F + w - lam * h
            d[S] = 0.0
            if np.all(F[S] >= -1e-12) and np.all(d >= -1e-14):
                found.append((F, lam))
    return found


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 10**6), n=st.integers(2, 7), T=st.floats(10.0, 1e5))
def test_matches_brute_force_enumeration(seed, n, T):
    C, w, h = _random_problem(seed, n)
    found = _brute_force(C, w, h, T)
    assert len(found) >= 1
    F_ref, lam_ref = found[0]
    sol = solve_load_distribution(C, w, h, T)
    assert np.allclose(sol.force, F_ref, rtol=1e-9, atol=1e-9 * T / h.min())
    assert sol.dtheta == pytest.approx(lam_ref, rel=1e-9, abs=1e-15)
    comp, eq, cp = sol.residuals(C, w, h, T)
    assert comp < 1e-13 and eq < 1e-10 * T and cp < 1e-12 * T
    assert np.all(sol.force >= 0) and np.all(sol.gap >= 0)


@pytest.mark.parametrize("seed", range(5))
def test_pdas_and_primal_active_set_agree(seed):
    C, w, h = _random_problem(seed, 60)
    sol = solve_load_distribution(C, w, h, 5e4)
    F, d, lam, A, it = primal_active_set(C, w, h, 5e4)
    assert np.allclose(sol.force, F, atol=1e-10)
    assert sol.dtheta == pytest.approx(lam, rel=1e-12)


def test_zero_torque_gives_unloaded_rotation():
    C, w, h = _random_problem(3, 20)
    sol = solve_load_distribution(C, w, h, 0.0)
    assert sol.dtheta == np.min(w / h)
    assert not sol.force.any()
    # the limit T -> 0+ of the loaded solution is the same rotation
    small = solve_load_distribution(C, w, h, 1e-9)
    assert small.dtheta == pytest.approx(np.min(w / h), abs=1e-13)


def test_monotone_growth_with_torque():
    x = np.linspace(-1.0, 1.0, 81)
    C = 2e-5 * np.exp(-np.abs(x[:, None] - x[None, :]) / 0.2) + 2e-6 * np.eye(81)
    w = 0.02 * x**2
    h = np.full(81, 40.0)
    prev_theta, prev_width, active = -np.inf, 0, None
    for T in np.geomspace(1e2, 1e6, 12):
        sol = solve_load_distribution(C, w, h, T, active=active)
        assert sol.dtheta > prev_theta
        assert sol.active.sum() >= prev_width
        prev_theta, prev_width, active = sol.dtheta, sol.active.sum(), sol.active
    assert prev_width > 20


def test_warm_start_gives_same_answer():
    C, w, h = _random_problem(11, 80)
    cold = solve_load_distribution(C, w, h, 2e4)
    warm = solve_load_distribution(C, w, h, 2e4, active=np.ones(80, bool))
    assert np.allclose(cold.force, warm.force, atol=1e-10)


def test_bad_inputs():
    C, w, h = _random_problem(1, 5)
    with pytest.raises(DesignError, match="torque"):
        solve_load_distribution(C, w, h, -1.0, position=4)
    with pytest.raises(DesignError, match=r"h\[2\].*position 7"):
        hb = h.copy()
        hb[2] = -1.0
        solve_load_distribution(C, w, hb, 10.0, position=7)
    with pytest.raises(DesignError, match="positive definite"):
        Cb = C.copy()
        Cb[0, 0] = -1.0
        solve_load_distribution(Cb, w, h, 10.0, position=2)
    with pytest.raises(DesignError, match="symmetric"):
        Cb = C.copy()
        Cb[0, 1] += 1.0
        solve_load_distribution(Cb, w, h, 10.0)
    with pytest.raises(NoContactError, match="position 3"):
        solve_load_distribution(np.zeros((0, 0)), [], [], 10.0, position=3)
    with pytest.raises(DesignError, match="non-finite"):
        wb = w.copy()
        wb[0] = np.nan
        solve_load_distribution(C, wb, h, 10.0)
