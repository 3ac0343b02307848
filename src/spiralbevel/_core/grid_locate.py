"""Compiled foot-point iteration on a structured bilinear surface grid (the projected Newton of
:func:`spiralbevel.meshing.ltca.locate.locate_on_grid`), one point at a time.

The iteration was a numpy loop over all points at once; in a loaded mesh cycle it runs on a few hundred points per
call with 30-40 steps until the last point settles, so numpy's per-call overhead made it most of the cycle's cost.
Here each point iterates on its own until it stops; the arithmetic of a step is that of the numpy loop, in the same
order (no fastmath).
"""

from __future__ import annotations

from .jit import kernel

__all__ = ["iterate_feet"]


@kernel
def iterate_feet(grid, pts, i, j, xi, eta, iterations):  # pragma: no cover - compiled
    """Projected Newton steps for every point, in place.

    Parameters
    ----------
    grid : (n0, n1, 3) float, mm
    pts : (n, 3) float, mm
    i, j : (n,) int
        Start cells, updated in place.
    xi, eta : (n,) float
        Start bilinear coordinates in [0, 1], updated in place.
    iterations : int
        Most steps per point (cell changes included).

    Notes
    -----
    Each step minimises the squared distance to the bilinear patch of the current cell: exact Hessian, Gauss-Newton
    where that is not positive definite, the step at most one cell long and projected onto the cell. A coordinate at a
    cell edge whose gradient points out of the cell is held there while the other slides; once the step stalls
    (< 1e-13) the point moves to the neighbouring cell across that edge (the coordinate continued), except at the
    grid's outer edge; a point stalled with no move is done.
    """
    n0, n1 = grid.shape[0], grid.shape[1]
    for k in range(pts.shape[0]):
        ia, ja, x, e = i[k], j[k], xi[k], eta[k]
        p0, p1, p2 = pts[k, 0], pts[k, 1], pts[k, 2]
        for _ in range(iterations):
            g1 = 0.0
            g2 = 0.0
            a11 = 0.0
            a22 = 0.0
            a12 = 0.0
            rr = 0.0
            for c in range(3):
                q00, q10 = grid[ia, ja, c], grid[ia + 1, ja, c]
                q01, q11 = grid[ia, ja + 1, c], grid[ia + 1, ja + 1, c]
                r = (1 - x) * (1 - e) * q00 + x * (1 - e) * q10 + (1 - x) * e * q01 + x * e * q11
                ru = (1 - e) * (q10 - q00) + e * (q11 - q01)
                rv = (1 - x) * (q01 - q00) + x * (q11 - q10)
                ruv = q11 - q10 - q01 + q00
                res = r - (p0 if c == 0 else (p1 if c == 1 else p2))
                g1 += ru * res
                g2 += rv * res
                a11 += ru * ru
                a22 += rv * rv
                a12 += ru * rv
                rr += res * ruv
            out_lo1, out_hi1 = x <= 0 and g1 > 0, x >= 1 and g1 < 0
            out_lo2, out_hi2 = e <= 0 and g2 > 0, e >= 1 and g2 < 0
            fix1, fix2 = out_lo1 or out_hi1, out_lo2 or out_hi2
            h12 = a12 + rr
            det = a11 * a22 - h12**2
            if not det > 1e-12 * a11 * a22:  # not positive definite: Gauss-Newton
                h12 = a12
            det = a11 * a22 - h12**2
            d1 = -(a22 * g1 - h12 * g2) / det
            d2 = -(a11 * g2 - h12 * g1) / det
            if fix2:
                d1 = -g1 / a11
            if fix1:
                d2 = -g2 / a22
            if fix1:
                d1 = 0.0
            if fix2:
                d2 = 0.0
            scale = min(1.0, 1.0 / max(max(abs(d1), abs(d2)), 1e-300))  # damping: at most one cell
            x_new = min(max(x + d1 * scale, 0.0), 1.0)
            e_new = min(max(e + d2 * scale, 0.0), 1.0)
            stalled = max(abs(x_new - x), abs(e_new - e)) < 1e-13
            mv1 = stalled and ((out_lo1 and ia > 0) or (out_hi1 and ia < n0 - 2))
            mv2 = stalled and ((out_lo2 and ja > 0) or (out_hi2 and ja < n1 - 2))
            if mv1:
                ia += -1 if out_lo1 else 1
                x = 1.0 if out_lo1 else 0.0
            else:
                x = x_new
            if mv2:
                ja += -1 if out_lo2 else 1
                e = 1.0 if out_lo2 else 0.0
            else:
                e = e_new
            if stalled and not mv1 and not mv2:
                break
        i[k], j[k], xi[k], eta[k] = ia, ja, x, e
