"""Benchmark: generated flank grid and batched locate against per-point scipy.optimize.fsolve baselines.

Each target point is a 2 x 2 nonlinear system (generating parameters u, psi_c for a given axial position and radius)
that scipy has no vectorized solver for (``scipy.optimize.elementwise`` is scalar-only), so the baseline is what a
competent scipy user writes: one ``fsolve`` per point on the same vectorized generator, from a start off the root. Both
sides are timed the same way, the median of N runs of the whole call (bench/_timing.py), in CPU time of this process
(``time.process_time``: single-threaded work on a machine shared by several engineers; its load is printed).

Run: python bench/bench_generation.py
Target (issue 13): the 31 x 15 grid with curvatures <= 1 ms on one core (not met: the blade points are located by a
compiled Newton, ``_core/blade_locate.py``; the junction line, the start-table queries and the curvatures at the
located points are numpy).
"""

import os

import numpy as np
from _timing import median_time
from scipy.optimize import fsolve

from spiralbevel.conventions import Member, Side
from spiralbevel.generation import generate_flank
from spiralbevel.machine import seed001_blank, seed001_settings


REPEAT, REPEAT_BASE = 21, 3


def best(f, n=REPEAT):
    return median_time(f, n, cpu=True)


def main():
    blank = seed001_blank()
    cutter, settings = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    flank = generate_flank(cutter, settings, blank, Member.GEAR, Side.CONVEX)
    gen = flank.generator
    flank.grid(31, 15)
    g3 = flank.grid(3, 3, curvature=False)
    flank.locate(g3.axial[1, 1], g3.radius[1, 1])          # warm-up: compiled kernels from the cache
    print(f"machine load {os.getloadavg()[0]:.1f} at start (shared machine: CPU times of this process)")

    t_new, _ = best(lambda: generate_flank(cutter, settings, blank, Member.GEAR, Side.CONVEX).grid(31, 15))
    t_grid, g = best(lambda: flank.grid(31, 15))
    res = np.abs(flank.meshing_residual(g.u, g.theta, g.psi_c)).max()
    print(f"grid 31x15 with normals and curvatures: {1e3 * t_grid:.2f} ms (fresh flank incl. start table "
          f"{1e3 * t_new:.2f} ms); max |n.v|/|v| = {res:.1e}")

    # baseline: the same grid targets, solved point by point with fsolve (unknowns u, psi_c)
    ol = flank.outline
    R, h = ol.Rh(g.axial, g.radius)

    def grid_fsolve():
        out = np.empty(g.u.shape + (3,))
        for i, j in np.ndindex(g.u.shape):
            def F(x, i=i, j=j):
                p = gen.points(x[0], x[1])
                Rx, hx = ol.Rh(p[2], np.hypot(p[0], p[1]))
                return [Rx - R[i, j], hx - h[i, j]]
            x = fsolve(F, [g.u[i, j] + 0.2, g.psi_c[i, j] + 0.005], xtol=1e-12)
            out[i, j] = gen.points(x[0], x[1])
        return out
    t_base, pb = best(grid_fsolve, REPEAT_BASE)
    print(f"  per-point fsolve baseline: {1e3 * t_base:.1f} ms  -> ratio {t_base / t_grid:.0f}x "
          f"(median of {REPEAT} / {REPEAT_BASE} runs)  "
          f"(max diff {np.abs(pb - g.points).max():.1e} mm)")

    # locate on 1000 points
    rng = np.random.default_rng(0)
    fine = flank.grid(41, 25, curvature=False)
    idx = rng.choice(fine.u.size, 1000, replace=False)
    ax, rad = fine.axial.ravel()[idx], fine.radius.ravel()[idx]
    t_loc, loc = best(lambda: flank.locate(ax, rad))
    err = np.abs(loc.points - fine.points.reshape(-1, 3)[idx]).max()
    print(f"locate 1000 points (with curvatures): {1e3 * t_loc:.2f} ms; max error {err:.1e} mm")
    u0, p0 = fine.u.ravel()[idx] + 0.3, fine.psi_c.ravel()[idx] + 0.01

    def loc_fsolve():
        out = np.empty((1000, 3))
        for k in range(1000):
            def F(x, k=k):
                p = gen.points(x[0], x[1])
                return [np.hypot(p[0], p[1]) - rad[k], p[2] - ax[k]]
            x = fsolve(F, [u0[k], p0[k]], xtol=1e-10)
            out[k] = gen.points(x[0], x[1])
        return out
    t_lb, pl = best(loc_fsolve, REPEAT_BASE)
    print(f"  per-point fsolve baseline: {1e3 * t_lb:.1f} ms  -> ratio {t_lb / t_loc:.0f}x "
          f"(median of {REPEAT} / {REPEAT_BASE} runs)  "
          f"(max diff {np.abs(pl - loc.points).max():.1e} mm)")


if __name__ == "__main__":
    main()
