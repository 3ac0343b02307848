"""FE root stress on a case with a known answer: the end-loaded cantilever plate.

The exact plane-stress elasticity solution (Timoshenko & Goodier, Theory of Elasticity, Art. 21: parabolic shear
load P at the free end x = 0, clamped at x = L, depth 2c) has sigma_xx = -P x y / I, tau_xy = -P (c^2 - y^2)/(2 I),
I = 2c^3/3; at the clamped root the bending stress is the beam value 6 P L/(2c)^2 (Lewis's cantilever). The FE solve
prescribes the exact displacement on the clamped edge and the parabolic shear on the loaded edge.
"""

import math

import numpy as np
import pytest

skfem = pytest.importorskip("skfem")

from spiralbevel.rating.root_fe import solve_plane_stress  # noqa: E402

E, NU, P, L, C = 206000.0, 0.3, 1000.0, 20.0, 2.0
I = 2.0 * C ** 3 / 3.0
G = E / (2.0 * (1.0 + NU))


def exact_displacement(x):
    X, Y = x
    u = (-P * X ** 2 * Y / (2 * E * I) - NU * P * Y ** 3 / (6 * E * I) + P * Y ** 3 / (6 * I * G)
         + (P * L ** 2 / (2 * E * I) - P * C ** 2 / (2 * I * G)) * Y)
    v = NU * P * X * Y ** 2 / (2 * E * I) + P * X ** 3 / (6 * E * I) \
        - P * L ** 2 * X / (2 * E * I) + P * L ** 3 / (3 * E * I)
    return np.stack([u, v])


def exact_stress(x):
    X, Y = x
    return np.stack([-P * X * Y / I, np.zeros_like(X), -P * (C ** 2 - Y ** 2) / (2 * I)])


def test_exact_solution_is_consistent():
    # the oracle itself: its strains (central differences) obey plane-stress Hooke's law with its stresses
    rng = np.random.default_rng(1)
    x = np.stack([rng.uniform(0, L, 20), rng.uniform(-C, C, 20)])
    h = 1e-4
    du_dx = (exact_displacement(x + [[h], [0]]) - exact_displacement(x - [[h], [0]])) / (2 * h)
    du_dy = (exact_displacement(x + [[0], [h]]) - exact_displacement(x - [[0], [h]])) / (2 * h)
    s = exact_stress(x)
    assert np.allclose(du_dx[0], (s[0] - NU * s[1]) / E, atol=1e-10)
    assert np.allclose(du_dy[1], (s[1] - NU * s[0]) / E, atol=1e-10)
    assert np.allclose(du_dy[0] + du_dx[1], s[2] / G, atol=1e-10)


def _solve(n):
    mesh = skfem.MeshTri.init_tensor(np.linspace(0, L, 5 * n + 1), np.linspace(-C, C, n + 1))
    return solve_plane_stress(
        mesh, E, NU,
        clamped=lambda x: np.isclose(x[0], L), clamp_displacement=exact_displacement,
        loaded=lambda x: np.isclose(x[0], 0.0),
        traction=lambda x, nrm: np.stack([np.zeros_like(x[0]), P * (C ** 2 - x[1] ** 2) / (2 * I)]))


def test_cantilever_root_stress_converges_at_second_order():
    root = np.array([[L], [-C]])           # tension side of the clamped section
    beam = 6.0 * P * L / (2.0 * C) ** 2    # Lewis / beam value at the root, = P L c / I
    assert beam == pytest.approx(P * L * C / I, rel=1e-14)
    errs = []
    for n in (2, 4, 8):
        res = _solve(n)
        errs.append(abs(res.max_principal(root)[0] - beam) / beam)
    rates = [math.log2(errs[i] / errs[i + 1]) for i in range(2)]
    # P2 triangles: stresses converge as h^2 (measured 2.03 and 2.03; 2.01 on the next refinement)
    assert min(rates) > 1.9, (errs, rates)
    # measured relative errors 1.24 %, 0.30 %, 0.074 %: the finest mesh (40 x 8 cells) well inside 5 %
    assert errs[-1] < 1e-3


def test_cantilever_stress_along_the_tension_edge():
    res = _solve(8)
    x = np.stack([np.linspace(0.1 * L, L, 10), np.full(10, -C)])
    exact = exact_stress(x)[0]             # sigma_1 = sigma_xx on the free edge (tau = sigma_yy = 0 there)
    # 0.5 % of the root value: the finest mesh's error with margin (see the convergence test)
    assert np.allclose(res.max_principal(x), exact, atol=5e-3 * exact.max())
