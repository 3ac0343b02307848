"""Contact flattening validated against Hertz theory through the full LTCA code path: exact-surface separations
(separation.py) -> half-space flexibility (halfspace.py, Love's closed form) -> load-distribution solver (lcp.py)."""

import numpy as np
import pytest
from scipy.integrate import dblquad
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from spiralbevel._core.ltca import rect_integral
from spiralbevel.errors import DesignError
from spiralbevel.meshing.ltca.halfspace import Material, contact_modulus, halfspace_flexibility
from spiralbevel.meshing.ltca.lcp import solve_load_distribution
from spiralbevel.meshing.ltca.separation import quadratic_separations, surface_separations

ESTAR = contact_modulus()


def hertz(A, B, P, estar):
    """Hertz point contact for w = A x^2 + B y^2, A <= B: (a along x, b along y, p0, approach).

    Johnson, Contact Mechanics (1985), Eqs. (4.39)-(4.41); the circular case Eqs. (4.22)-(4.23).
    """
    if B - A < 1e-12 * B:
        R = 1.0 / (2.0 * A)
        a = (3.0 * P * R / (4.0 * estar)) ** (1.0 / 3.0)
        return a, a, 3.0 * P / (2.0 * np.pi * a * a), a * a / R
    m = brentq(lambda m: (ellipe(m) / (1.0 - m) - ellipk(m)) / (ellipk(m) - ellipe(m)) - B / A, 1e-9, 1.0 - 1e-12)
    K, E = ellipk(m), ellipe(m)
    a = (3.0 * P * (K - E) / (2.0 * np.pi * estar * m * A)) ** (1.0 / 3.0)
    b = a * np.sqrt(1.0 - m)
    p0 = 3.0 * P / (2.0 * np.pi * a * b)
    return a, b, p0, p0 * b * K / estar


def cylinder_below(R):
    """Body 1 (material at z < 0), axis along y, touching the origin."""
    def f(u, v):
        z = np.sqrt(R**2 - u**2) - R
        return np.stack([u, v, z], -1), np.stack([u, 0 * u, z + R], -1) / R
    return f


def cylinder_above(R):
    """Body 2 (material at z > 0), axis along x."""
    def f(u, v):
        z = R - np.sqrt(R**2 - v**2)
        return np.stack([u, v, z], -1), np.stack([0 * u, v, z - R], -1) / R
    return f


def sphere_below(R):
    def f(u, v):
        z = np.sqrt(R**2 - u**2 - v**2) - R
        return np.stack([u, v, z], -1), np.stack([u, v, z + R], -1) / R
    return f


def plane_above(u, v):
    return np.stack([u, v, 0 * u], -1), np.stack([0 * u, 0 * u, -np.ones_like(u)], -1)


def _edge(coord, p):
    """Contact edge along a grid line (coord >= 0): p^2 extrapolated linearly to zero from the last two loaded cells
    (Hertz-independent: any smooth contact edge has p ~ sqrt(distance))."""
    k = np.flatnonzero(p > 0).max()
    return coord[k] + p[k] ** 2 * (coord[k] - coord[k - 1]) / (p[k - 1] ** 2 - p[k] ** 2)


def _solve(surf1, surf2, P, a, b, nb):
    """LTCA code path on a square-cell grid with nb cells per minor semi-axis; returns (pmax, ax, ay, approach)."""
    cell = min(a, b) / nb
    nx, ny = int(np.ceil(1.25 * a / cell)), int(np.ceil(1.25 * b / cell))
    s, t = cell * np.arange(-nx, nx + 1), cell * np.arange(-ny, ny + 1)
    sep = surface_separations(surf1, surf2, [0, 0, 0], [0, 0, 1], [1, 0, 0], s, t, [0, 0], [0, 0])
    S, T = np.meshgrid(s, t, indexing="ij")
    C = halfspace_flexibility(np.stack([S.ravel(), T.ravel()], 1), cell, cell, ESTAR)
    sol = solve_load_distribution(C, sep.w.ravel(), np.ones(S.size), P)  # h = 1: dtheta is the approach in mm
    p = (sol.force / cell**2).reshape(S.shape)
    return p.max(), _edge(s[nx:], p[nx:, ny]), _edge(t[ny:], p[nx, ny:]), sol.dtheta


def test_love_rectangle_against_quadrature():
    a, b = 0.7, 0.3
    for x, y in [(2.0, 0.5), (-1.1, 1.3), (0.0, 3.0)]:
        ref = dblquad(lambda yy, xx, x=x, y=y: 1.0 / np.hypot(x - xx, y - yy), -a, a, -b, b, epsabs=1e-12)[0]
        assert rect_integral(x, y, a, b) == pytest.approx(ref, rel=1e-9)
    # centre of a square of side 2c: 8 c ln(1 + sqrt 2) (Johnson, Contact Mechanics, §3.3)
    assert rect_integral(0.0, 0.0, 0.5, 0.5) == pytest.approx(4.0 * np.log(1 + np.sqrt(2)), rel=1e-14)
    # on an edge midpoint, by quadrature split at the singular point
    ref = sum(dblquad(lambda yy, xx: 1.0 / np.hypot(0.7 - xx, yy), lo, hi, -b, b, epsabs=1e-12)[0]
              for lo, hi in [(-a, 0.0), (0.0, a)])
    assert rect_integral(0.7, 0.0, a, b) == pytest.approx(ref, rel=1e-7)


def test_halfspace_matrix_symmetric_positive_definite():
    g = np.arange(-4, 5) * 0.1
    S, T = np.meshgrid(g, g, indexing="ij")
    C = halfspace_flexibility(np.stack([S.ravel(), T.ravel()], 1), 0.1, 0.1, ESTAR)
    assert np.allclose(C, C.T, rtol=1e-14, atol=0)
    assert np.linalg.eigvalsh(C).min() > 0


def test_contact_modulus_and_bad_material():
    assert contact_modulus() == pytest.approx(206000.0 / (2 * (1 - 0.09)), rel=1e-15)
    with pytest.raises(DesignError, match="poisson_ratio"):
        Material(206000.0, 0.6)
    with pytest.raises(DesignError, match="dx"):
        halfspace_flexibility(np.zeros((1, 2)), 0.0, 1.0, ESTAR)


def test_hertz_reference_reduces_to_circle():
    # curvature ratio 1 + 1e-4: the elliptic solution differs from the circular one by O(1e-4)
    a, b, p0, dl = hertz(1.0 / 40.0, (1.0 + 1e-4) / 40.0, 1000.0, ESTAR)
    ac, _, p0c, dlc = hertz(1.0 / 40.0, 1.0 / 40.0, 1000.0, ESTAR)
    assert a == pytest.approx(ac, rel=2e-4) and b == pytest.approx(ac, rel=2e-4)
    assert p0 == pytest.approx(p0c, rel=2e-4) and dl == pytest.approx(dlc, rel=2e-4)


def test_separations_exact_and_quadratic():
    R1, R2 = 20.0, 60.0
    s, t = np.linspace(-1.5, 1.5, 7), np.linspace(-3.0, 3.0, 9)
    sep = surface_separations(cylinder_below(R1), cylinder_above(R2), [0, 0, 0], [0, 0, 1], [1, 0, 0], s, t,
                              [0, 0], [0, 0])
    S, T = np.meshgrid(s, t, indexing="ij")
    exact = R1 - np.sqrt(R1**2 - S**2) + R2 - np.sqrt(R2**2 - T**2)
    assert np.allclose(sep.w, exact, atol=1e-11)
    quad = quadratic_separations([[1 / R1, 0], [0, 1 / R2]], s, t)
    assert np.allclose(sep.w, quad, rtol=0.01, atol=1e-12)  # 2nd-order: rel. error ~ x^2/(4 R^2) < 0.2 %


def test_sphere_on_plane_within_2_percent_of_hertz():
    R, P = 25.0, 1500.0
    a, _, p0, dl = hertz(1 / (2 * R), 1 / (2 * R), P, ESTAR)
    pmax, ax, ay, approach = _solve(sphere_below(R), plane_above, P, a, a, nb=8)
    assert pmax == pytest.approx(p0, rel=0.02)
    assert ax == pytest.approx(a, rel=0.02) and ay == pytest.approx(a, rel=0.02)
    assert approach == pytest.approx(dl, rel=0.02)


def test_crossed_cylinders_within_2_percent_of_hertz_and_converging():
    R1, R2, P = 20.0, 60.0, 2000.0
    b, a, p0, dl = hertz(1 / (2 * R2), 1 / (2 * R1), P, ESTAR)  # major semi-axis b along y (cylinder 2's x-axis)
    err = {}
    for nb in (4, 8):
        pmax, ax, ay, approach = _solve(cylinder_below(R1), cylinder_above(R2), P, a, b, nb)
        err[nb] = abs(pmax / p0 - 1)
        assert pmax == pytest.approx(p0, rel=0.02)
        assert ax == pytest.approx(a, rel=0.02) and ay == pytest.approx(b, rel=0.02)
        assert approach == pytest.approx(dl, rel=0.02)
    # peak pressure converges at second order in the cell size (measured 4.7x per halving at nb = 4 -> 8)
    assert err[4] / err[8] > 3.0


def test_library_hertz_ellipse_matches_the_reference():
    """meshing.ellipse's array-based Hertz solution (bisection on b/a) against the brentq reference above, from the
    sphere to a 1:400 curvature ratio (tooth contacts are 1:10 to 1:200)."""
    from spiralbevel.meshing.ellipse import hertz_peak_pressure, hertz_semi_axes

    # 1e-8: the reference's brentq stops at |dm| ~ 2e-12, which moves b = a sqrt(1 - m) by ~1e-9 at m -> 1
    for lam in ([0.05, 0.05], [0.02, 0.05], [0.002, 0.08], [0.0002, 0.08]):
        A, B = 0.5 * np.array(lam)
        a, b, p0, dl = hertz(A, B, 1500.0, ESTAR)
        p, ab = hertz_peak_pressure(np.array(lam), 1500.0, ESTAR)
        assert p == pytest.approx(p0, rel=1e-8) and ab == pytest.approx([a, b], rel=1e-8)
        assert hertz_semi_axes(np.array(lam), dl) == pytest.approx([a, b], rel=1e-8)
