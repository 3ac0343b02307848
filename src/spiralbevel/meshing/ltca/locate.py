"""Location of points on a structured surface grid: cell indices and bilinear coordinates (Gauss-Newton)."""

from __future__ import annotations

import numpy as np

__all__ = ["locate_on_grid"]


def _bilinear(grid, i, j, xi, eta):
    p00, p10 = grid[i, j], grid[i + 1, j]
    p01, p11 = grid[i, j + 1], grid[i + 1, j + 1]
    x, e = xi[:, None], eta[:, None]
    r = (1 - x) * (1 - e) * p00 + x * (1 - e) * p10 + (1 - x) * e * p01 + x * e * p11
    ru = (1 - e) * (p10 - p00) + e * (p11 - p01)
    rv = (1 - x) * (p01 - p00) + x * (p11 - p10)
    return r, ru, rv


def locate_on_grid(grid, points, sweeps=4, iterations=6):
    """Cell (i, j) and bilinear coordinates (xi, eta) in [0, 1] of the foot points of ``points`` on ``grid``.

    Parameters
    ----------
    grid : (n0, n1, 3) float, mm
        Structured surface grid.
    points : (n, 3) float, mm
        Points on or near the surface; points beyond the grid edge are clamped to it.

    Returns
    -------
    i, j : (n,) int
        Cell indices (0 <= i <= n0 - 2, 0 <= j <= n1 - 2).
    xi, eta : (n,) float
        Bilinear coordinates in the cell, clamped to [0, 1].
    inside : (n,) bool
        False for points whose foot lies beyond the grid edge (before clamping).

    Notes
    -----
    Start at the cell of the nearest grid node, then Gauss-Newton on the bilinear patch for the closest point;
    when a coordinate leaves [0, 1] the point moves to the neighbouring cell (``sweeps`` times).
    """
    grid = np.asarray(grid, float)
    pts = np.asarray(points, float).reshape(-1, 3)
    n0, n1 = grid.shape[:2]
    d2 = np.sum((pts[:, None, :] - grid.reshape(1, -1, 3)) ** 2, axis=-1)
    near = np.argmin(d2, axis=1)
    i = np.clip(near // n1, 0, n0 - 2)
    j = np.clip(near % n1, 0, n1 - 2)
    xi = np.full(len(pts), 0.5)
    eta = np.full(len(pts), 0.5)
    for _ in range(sweeps):
        for _ in range(iterations):
            r, ru, rv = _bilinear(grid, i, j, xi, eta)
            res = r - pts
            a11, a12, a22 = (ru * ru).sum(1), (ru * rv).sum(1), (rv * rv).sum(1)
            b1, b2 = -(ru * res).sum(1), -(rv * res).sum(1)
            det = a11 * a22 - a12**2
            xi = xi + (a22 * b1 - a12 * b2) / det
            eta = eta + (a11 * b2 - a12 * b1) / det
        di = np.where(xi < 0, -1, np.where(xi > 1, 1, 0))
        dj = np.where(eta < 0, -1, np.where(eta > 1, 1, 0))
        ni, nj = np.clip(i + di, 0, n0 - 2), np.clip(j + dj, 0, n1 - 2)
        moved = (ni != i) | (nj != j)
        if not moved.any():
            break
        xi = np.where(moved, 0.5, xi)
        eta = np.where(moved, 0.5, eta)
        i, j = ni, nj
    tol = 1e-6
    inside = (xi > -tol) & (xi < 1 + tol) & (eta > -tol) & (eta < 1 + tol)
    return i, j, np.clip(xi, 0.0, 1.0), np.clip(eta, 0.0, 1.0), inside
