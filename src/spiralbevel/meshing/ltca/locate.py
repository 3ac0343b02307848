"""Location of points on a structured surface grid: cell indices and bilinear coordinates (projected Newton)."""

from __future__ import annotations

import numpy as np

__all__ = ["locate_on_grid"]

#: stationarity tolerance (mm): the tangential part of the point-to-foot vector along each cell coordinate direction
#: at a converged foot (round-off of grid coordinates of ~100 mm is ~1e-13 mm)
FOOT_TOL = 1e-9


def _patch(grid, i, j, xi, eta):
    p00, p10 = grid[i, j], grid[i + 1, j]
    p01, p11 = grid[i, j + 1], grid[i + 1, j + 1]
    x, e = xi[:, None], eta[:, None]
    r = (1 - x) * (1 - e) * p00 + x * (1 - e) * p10 + (1 - x) * e * p01 + x * e * p11
    ru = (1 - e) * (p10 - p00) + e * (p11 - p01)
    rv = (1 - x) * (p01 - p00) + x * (p11 - p10)
    ruv = p11 - p10 - p01 + p00
    return r, ru, rv, ruv


def _dot(a, b):
    return np.einsum("ni,ni->n", a, b)


def locate_on_grid(grid, points, iterations=200):
    """Cell (i, j) and bilinear coordinates (xi, eta) in [0, 1] of the foot points of ``points`` on ``grid``.

    Parameters
    ----------
    grid : (n0, n1, 3) float, mm
        Structured surface grid (bilinear cells).
    points : (n, 3) float, mm
        Points on or near the surface; points beyond the grid edge get the nearest point of the edge.
    iterations : int
        Newton steps at most (cell changes included).

    Returns
    -------
    i, j : (n,) int
        Cell indices (0 <= i <= n0 - 2, 0 <= j <= n1 - 2).
    xi, eta : (n,) float
        Bilinear coordinates in the cell, in [0, 1].
    inside : (n,) bool
        True only where the foot converged (the point-to-foot vector normal to the grid surface to ``FOOT_TOL`` mm,
        or on a cell edge shared by two cells with the distance growing into both) and lies on the grid, not beyond
        its edge. A point whose iteration did not converge is never inside.

    Notes
    -----
    Start at the grid node nearest to the point; then Newton steps on the squared distance to the bilinear patch of
    the current cell (exact Hessian, Gauss-Newton where that is not positive definite), each at most one cell long
    and projected onto the cell. A coordinate at a cell edge whose gradient points out of the cell is held there
    while the other one slides along the edge; once that stalls, the point moves on to the neighbouring cell (its
    coordinate continued across the edge), except at the grid's outer edge, where the foot stays (not inside).
    The steps run compiled, each point until it stops (``_core.grid_locate.iterate_feet``).
    """
    grid = np.asarray(grid, float)
    pts = np.asarray(points, float).reshape(-1, 3)
    n0, n1 = grid.shape[:2]
    npt = len(pts)
    nodes = grid.reshape(-1, 3)
    d2 = np.sum(nodes**2, axis=1)[None, :] - 2.0 * pts @ nodes.T  # + |p|^2, the same for every node
    near = np.argmin(d2, axis=1) if npt else np.zeros(0, int)
    a, b = near // n1, near % n1
    i, j = np.minimum(a, n0 - 2), np.minimum(b, n1 - 2)
    xi, eta = (a - i).astype(float), (b - j).astype(float)
    from ..._core.grid_locate import iterate_feet

    i, j = np.ascontiguousarray(i, np.int64), np.ascontiguousarray(j, np.int64)
    xi, eta = np.ascontiguousarray(xi, float), np.ascontiguousarray(eta, float)
    if npt:
        iterate_feet(np.ascontiguousarray(grid), np.ascontiguousarray(pts), i, j, xi, eta, int(iterations))
    # Karush-Kuhn-Tucker check of the foot in its cell (never trust an unconverged iterate)
    r, ru, rv, _ = _patch(grid, i, j, xi, eta)
    res = r - pts
    t1 = _dot(ru, res) / np.linalg.norm(ru, axis=1)
    t2 = _dot(rv, res) / np.linalg.norm(rv, axis=1)
    lo1, hi1, lo2, hi2 = xi <= 0, xi >= 1, eta <= 0, eta >= 1

    def coord_ok(t, lo, hi, first, last):
        interior = ~lo & ~hi & (np.abs(t) <= FOOT_TOL)
        at_lo = lo & ((t <= FOOT_TOL) | first)   # wanting out only where there is no neighbour (grid edge)
        at_hi = hi & ((t >= -FOOT_TOL) | last)
        return interior | at_lo | at_hi

    ok = coord_ok(t1, lo1, hi1, i == 0, i == n0 - 2) & coord_ok(t2, lo2, hi2, j == 0, j == n1 - 2)
    beyond = (lo1 & (t1 > FOOT_TOL)) | (hi1 & (t1 < -FOOT_TOL)) | (lo2 & (t2 > FOOT_TOL)) | (hi2 & (t2 < -FOOT_TOL))
    inside = ok & ~beyond
    return i, j, xi, eta, inside
