"""locate_on_grid against points built on (and off) a curved, non-uniform, sheared grid: the construction is the
oracle (the exact cell, bilinear coordinates and foot of every point are known)."""

import numpy as np
import pytest

from spiralbevel.meshing.ltca.locate import locate_on_grid


def _grid(n0=31, n1=9):
    """A fillet-like strip: a cylinder of radius 4 mm swept over 0.6 rad across (n1 nodes, spacing growing 1:3), 60 mm
    along (n0 nodes, spacing growing 1:4) and sheared along by 6 mm across the strip: cells 0.1-1.4 mm wide and up
    to 20 x as long, the nearest node of a point off the surface several cells from its foot."""
    u = np.cumsum(np.r_[0.0, np.linspace(1.0, 4.0, n0 - 1)])
    u = 60.0 * u / u[-1]
    v = np.cumsum(np.r_[0.0, np.linspace(1.0, 3.0, n1 - 1)])
    v = 0.6 * v / v[-1]
    U, V = np.meshgrid(u, v, indexing="ij")
    return np.stack([U + 10.0 * V, 4.0 * np.cos(V), 4.0 * np.sin(V)], -1)


def _bilinear(g, i, j, xi, eta):
    x, e = xi[:, None], eta[:, None]
    return ((1 - x) * (1 - e) * g[i, j] + x * (1 - e) * g[i + 1, j] + (1 - x) * e * g[i, j + 1]
            + x * e * g[i + 1, j + 1])


def _normal(g, i, j, xi, eta):
    x, e = xi[:, None], eta[:, None]
    ru = (1 - e) * (g[i + 1, j] - g[i, j]) + e * (g[i + 1, j + 1] - g[i, j + 1])
    rv = (1 - x) * (g[i, j + 1] - g[i, j]) + x * (g[i + 1, j + 1] - g[i + 1, j])
    n = np.cross(ru, rv)
    return n / np.linalg.norm(n, axis=1)[:, None]


@pytest.fixture(scope="module")
def cells():
    g = _grid()
    rng = np.random.default_rng(7)
    m = 400
    i = rng.integers(0, g.shape[0] - 1, m)
    j = rng.integers(0, g.shape[1] - 1, m)
    xi, eta = rng.uniform(0.02, 0.98, m), rng.uniform(0.02, 0.98, m)  # off the cell edges: (i, j) unique
    return g, i, j, xi, eta


def test_points_on_the_surface_are_recovered(cells):
    g, i, j, xi, eta = cells
    P = _bilinear(g, i, j, xi, eta)
    ri, rj, rxi, reta, inside = locate_on_grid(g, P)
    assert inside.all()
    np.testing.assert_array_equal(ri, i)
    np.testing.assert_array_equal(rj, j)
    # Newton converges quadratically to round-off: 1e-9 is far above it and far below any cell (>= 0.1 mm)
    np.testing.assert_allclose(rxi, xi, rtol=0, atol=1e-9)
    np.testing.assert_allclose(reta, eta, rtol=0, atol=1e-9)


@pytest.mark.parametrize("offset", [0.3, 1.6])
def test_points_off_the_surface_along_its_normal(cells, offset):
    """``offset`` mm off (1.6 mm: the distance of the point mislocated at mesh position 16 of the synthesized example
    at 565 N m). On the convex side (away from the cylinder's axis) every point lies in its own cell's normal region:
    the foot is the constructed point. On the concave side the faceted surface has several local feet: the one
    found is a stationary one."""
    g, i, j, xi, eta = cells
    F = _bilinear(g, i, j, xi, eta)
    n = _normal(g, i, j, xi, eta)
    n = n * np.sign(np.einsum("ni,ni->n", n, F * [0, 1, 1]))[:, None]  # away from the axis (x)
    ri, rj, rxi, reta, inside = locate_on_grid(g, F + offset * n)
    assert inside.all()
    np.testing.assert_allclose(_bilinear(g, ri, rj, rxi, reta), F, rtol=0, atol=1e-9)
    P = F - offset * n
    ri, rj, rxi, reta, inside = locate_on_grid(g, P)
    assert inside.all()
    # a stationary foot: the point-to-foot vector normal to the patch there (feet on cell edges: the kink has no
    # single normal; the edge case is covered by the convex side above)
    x, e = rxi[:, None], reta[:, None]
    ru = (1 - e) * (g[ri + 1, rj] - g[ri, rj]) + e * (g[ri + 1, rj + 1] - g[ri, rj + 1])
    rv = (1 - x) * (g[ri, rj + 1] - g[ri, rj]) + x * (g[ri + 1, rj + 1] - g[ri + 1, rj])
    res = _bilinear(g, ri, rj, rxi, reta) - P
    mid = (rxi > 0) & (rxi < 1) & (reta > 0) & (reta < 1)
    assert mid.mean() > 0.5
    for t in (ru, rv):
        assert np.max(np.abs(np.einsum("ni,ni->n", t, res) / np.linalg.norm(t, axis=1))[mid]) < 1e-9


def test_points_beyond_the_grid_edges_are_outside():
    g = _grid()
    n0, n1 = g.shape[:2]
    rng = np.random.default_rng(3)
    P = []
    for _ in range(50):  # beyond the first / last row: continue the edge cell's direction by 0.5-3 of its length
        a, s = rng.integers(0, n1), rng.uniform(0.5, 3.0)
        P.append(g[0, a] - s * (g[1, a] - g[0, a]))
        P.append(g[-1, a] + s * (g[-1, a] - g[-2, a]))
    for _ in range(50):  # beyond the first / last column: off the cylinder's arc, tangentially
        a, s = rng.integers(0, n0), rng.uniform(0.2, 2.0)
        P.append(g[a, 0] - s * (g[a, 1] - g[a, 0]) / np.linalg.norm(g[a, 1] - g[a, 0]))
        P.append(g[a, -1] + s * (g[a, -1] - g[a, -2]) / np.linalg.norm(g[a, -1] - g[a, -2]))
    i, j, xi, eta, inside = locate_on_grid(g, np.array(P))
    assert not inside.any()
    assert np.all((xi >= 0) & (xi <= 1) & (eta >= 0) & (eta <= 1))


def test_a_failed_iteration_is_never_inside():
    """With too few steps to reach the foot, the points are reported off the grid, never at a made-up foot."""
    g = _grid()
    P = _bilinear(g, np.array([25]), np.array([6]), np.array([0.5]), np.array([0.5]))
    P = P + 1.6 * _normal(g, np.array([25]), np.array([6]), np.array([0.5]), np.array([0.5]))
    far = np.array([[-30.0, 0.0, 0.0]]) + g[0, 0]  # many cells from every node
    i, j, xi, eta, inside = locate_on_grid(g, np.vstack([P, far]), iterations=1)
    assert not inside.any()


def test_feet_on_random_grids_against_brute_force():
    """Random warped grids and random points near them: every foot reported inside is the nearest point of its cell,
    against a brute-force search of the cell (sampled 81 x 81, the sample nearest to the point). (The foot is a local
    one: on a strongly warped grid another cell may hold a nearer point; the iteration starts at the nearest node.)"""
    rng = np.random.default_rng(11)
    t = np.linspace(0.0, 1.0, 81)
    X, E = (a.ravel() for a in np.meshgrid(t, t, indexing="ij"))
    checked = 0
    for _ in range(12):
        n0, n1 = rng.integers(3, 9), rng.integers(3, 6)
        s, w = np.meshgrid(np.sort(rng.uniform(0, 30, n0)), np.sort(rng.uniform(0, 8, n1)), indexing="ij")
        g = np.stack([s + 0.3 * w, w + 0.02 * s**1.5, 0.01 * s**2 - 0.05 * w**2 + rng.normal(0, 0.1, s.shape)], -1)
        P = np.stack([rng.uniform(s.min(), s.max(), 40), rng.uniform(0, 8, 40), rng.normal(0, 0.5, 40)], -1)
        P[:, 1] += 0.02 * P[:, 0] ** 1.5
        i, j, xi, eta, inside = locate_on_grid(g, P)
        d = np.linalg.norm(_bilinear(g, i, j, xi, eta) - P, axis=1)
        for k in np.flatnonzero(inside):
            q = _bilinear(g, np.full(len(X), i[k]), np.full(len(X), j[k]), X, E)
            best = np.min(np.linalg.norm(q - P[k], axis=1))
            corners = g[[i[k], i[k] + 1, i[k] + 1, i[k]], [j[k], j[k], j[k] + 1, j[k] + 1]]
            step = np.max(np.linalg.norm(corners - np.roll(corners, 1, axis=0), axis=1)) / 80
            # no sample is nearer than the foot (1e-9 mm: round-off), and a sample lies within a sampling step of it
            assert d[k] <= best + 1e-9 and best - d[k] < step
            checked += 1
    assert checked > 200
