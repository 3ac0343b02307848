"""Benchmark: generated flank grid and batched locate, with normals and principal curvatures, against the best simple
numpy/scipy alternatives.

Each target point is a 2 x 2 nonlinear system (generating parameters u, psi_c for a given axial position and radius,
or a given cone-distance coordinate R and height h). scipy has no vectorized solver for 2 x 2 systems
(``scipy.optimize.elementwise`` is scalar-only), so the baselines are what a competent numpy/scipy user writes on the
package's own vectorized generator (``Generator.points``: the closed-form cutter angle, all points at once):

* **vectorized numpy Newton** (the best simple alternative, the headline ratio): one batched Newton over all targets
  at once, forward-difference Jacobian (steps 1e-6 mm in u, 1e-8 rad in psi_c), ``numpy.linalg.solve`` on the stacked
  2 x 2 systems, stopped at max|F| < 1e-10 mm (the package's tolerance); then normals and principal curvatures by
  second-order finite differences of the surface map (u, psi_c) -> r (central, or one-sided in u next to the fillet
  junction, where the surface is only C1; steps 2e-3 mm and 2e-4 rad) and the eigenvalues of I^-1 II, vectorized. It
  starts from the root offset by (0.2 mm, 0.005 rad) in (u, psi_c): a start the package does not get (it starts from
  its own fillet junction line and continues row by row up the profile, or from a start table for ``locate``).
* per-point ``scipy.optimize.fsolve`` (points only, from the same start), kept for comparison with earlier figures.

Both sides are timed the same way, the median of N runs of the whole call (bench/_timing.py), in CPU time of this
process (``time.process_time``: single-threaded work on a machine shared by several engineers; its load is printed).

Run: python bench/bench_generation.py
Target (issue 13): the 31 x 15 grid with curvatures <= 1 ms on one core.
"""

import os

import numpy as np
from _timing import median_time
from scipy.optimize import fsolve

from spiralbevel.conventions import Member, Side
from spiralbevel.generation import generate_flank
from spiralbevel.machine import seed001_blank, seed001_settings

REPEAT, REPEAT_BASE, REPEAT_FSOLVE = 51, 21, 3


def best(f, n=REPEAT):
    return median_time(f, n, cpu=True)


def numpy_newton(gen, target, u0, p0, to_coords, tol=1e-10, max_iter=50):
    """Batched Newton on (u, psi_c) for ``to_coords(points) = target`` (tuples of (...) arrays), forward-difference
    Jacobian; returns u, psi_c."""
    x = np.stack([u0, p0], -1).astype(float)
    h = np.array([1e-6, 1e-8])

    def F(x):
        return np.stack(to_coords(gen.points(x[..., 0], x[..., 1])), -1) - target

    for _ in range(max_iter):
        f = F(x)
        if np.abs(f).max() < tol:
            break
        J = np.stack([(F(x + h[k] * np.eye(2)[k]) - f) / h[k] for k in range(2)], -1)
        x = x - np.linalg.solve(J, f[..., None])[..., 0]
    return x[..., 0], x[..., 1]


def numpy_curvatures(gen, u, p, n_ref, hu=2e-3, hp=2e-4):
    """Unit normals (oriented as ``n_ref``) and principal curvatures (descending, convex = positive) by second-order
    finite differences of the surface map; in u central, or one-sided toward the blade where the central stencil
    would reach across the fillet junction u_j (the surface is only C1 there)."""
    f = gen.points
    s = (u - hu < gen.cp["u_j"]).astype(float)            # 0: central stencil in u, 1: forward
    fu = [f(u + (s - 1 + j) * hu, p) for j in range(4)]     # nodes u + (s - 1 + j) hu
    w1 = np.where(s[..., None, None] > 0, np.array([-1.5, 2.0, -0.5, 0.0]), np.array([-0.5, 0.0, 0.5, 0.0]))
    w2 = np.where(s[..., None, None] > 0, np.array([2.0, -5.0, 4.0, -1.0]), np.array([1.0, -2.0, 1.0, 0.0]))
    ru = sum(w1[..., j] * fu[j] for j in range(4)) / hu
    ruu = sum(w2[..., j] * fu[j] for j in range(4)) / hu**2
    r = f(u, p)
    rp = (f(u, p + hp) - f(u, p - hp)) / (2 * hp)
    rpp = (f(u, p + hp) - 2 * r + f(u, p - hp)) / hp**2
    rup = sum(w1[..., j] * (f(u + (s - 1 + j) * hu, p + hp) - f(u + (s - 1 + j) * hu, p - hp)) for j in range(3))
    rup = rup / (2 * hp * hu)
    n = np.cross(ru, rp)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    n *= np.sign(np.sum(n * n_ref, -1))[..., None]
    E, F, G = (np.sum(a * b, -1) for a, b in ((ru, ru), (ru, rp), (rp, rp)))
    L, M, N = (-np.sum(a * n, -1) for a in (ruu, rup, rpp))
    I = np.stack([np.stack([E, F], -1), np.stack([F, G], -1)], -2)
    II = np.stack([np.stack([L, M], -1), np.stack([M, N], -1)], -2)
    k = np.linalg.eigvals(np.linalg.solve(I, II)).real
    return r, n, -np.sort(-k, axis=-1)


def compare(label, t_pkg, out, t_np, np_out, t_fs, fs_pts, n, u_j):
    r, nrm, k = np_out
    kp = np.sort(np.stack([out.k1, out.k2], -1), -1)[..., ::-1]
    # the profile curvature jumps at the fillet junction (the surface is only C1 there): points located on it within
    # round-off belong to either side; those the package places on the fillet side (u_j - 1e-9 < u < u_j, the
    # baseline's stencil is one-sided into the blade) are left out of the curvature comparison
    on_junction = (out.u < u_j) & (out.u > u_j - 1e-9)
    krel = np.abs(k - kp)[~on_junction].max() / np.abs(kp).max()
    print(f"{label}: spiralbevel {1e3 * t_pkg:.3f} ms (median of {REPEAT})")
    print(f"  vectorized numpy Newton + finite-difference curvatures: {1e3 * t_np:.3f} ms (median of {REPEAT_BASE}) "
          f"-> ratio {t_np / t_pkg:.1f}x; max |dr| {np.abs(r - out.points).max():.1e} mm, "
          f"max |dn| {np.abs(nrm - out.normals).max():.1e}, curvatures {krel:.1e} of the largest "
          f"({int(on_junction.sum())} fillet-side points on the junction left out)")
    print(f"  per-point fsolve (points only): {1e3 * t_fs:.1f} ms (median of {REPEAT_FSOLVE}) -> ratio "
          f"{t_fs / t_pkg:.0f}x; max |dr| {np.abs(fs_pts - out.points).max():.1e} mm  ({n} points)")


def main():
    blank = seed001_blank()
    cutter, settings = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    flank = generate_flank(cutter, settings, blank, Member.GEAR, Side.CONVEX)
    gen = flank.generator
    flank.grid(31, 15)
    g3 = flank.grid(3, 3, curvature=False)
    flank.locate(g3.axial[1, 1], g3.radius[1, 1])          # warm-up: compiled kernels from the cache
    print(f"machine load {os.getloadavg()[0]:.1f} at start (shared machine: CPU times of this process)")

    t_new, _ = best(lambda: generate_flank(cutter, settings, blank, Member.GEAR, Side.CONVEX).grid(31, 15), 11)
    t_grid, g = best(lambda: flank.grid(31, 15))
    res = np.abs(flank.meshing_residual(g.u, g.theta, g.psi_c)).max()
    print(f"(fresh flank incl. its start tables: {1e3 * t_new:.2f} ms; grid max |n.v|/|v| = {res:.1e})")

    # baselines: the same grid targets (R, h), unknowns (u, psi_c)
    ol = flank.outline
    R, h = ol.Rh(g.axial, g.radius)
    Rh = np.stack([R, h], -1)
    u0, p0 = g.u + 0.2, g.psi_c + 0.005

    def grid_numpy():
        u, p = numpy_newton(gen, Rh, u0, p0, lambda q: ol.Rh(q[..., 2], np.hypot(q[..., 0], q[..., 1])))
        return numpy_curvatures(gen, u, p, g.normals)

    t_np, np_out = best(grid_numpy, REPEAT_BASE)

    def grid_fsolve():
        out = np.empty(g.u.shape + (3,))
        for i, j in np.ndindex(g.u.shape):
            def F(x, i=i, j=j):
                p = gen.points(x[0], x[1])
                Rx, hx = ol.Rh(p[2], np.hypot(p[0], p[1]))
                return [Rx - R[i, j], hx - h[i, j]]
            x = fsolve(F, [u0[i, j], p0[i, j]], xtol=1e-12)
            out[i, j] = gen.points(x[0], x[1])
        return out

    t_fs, fs_pts = best(grid_fsolve, REPEAT_FSOLVE)
    compare("grid 31x15 with normals and curvatures", t_grid, g, t_np, np_out, t_fs, fs_pts, g.u.size,
            gen.cp["u_j"])

    # locate on 1000 points
    rng = np.random.default_rng(0)
    fine = flank.grid(41, 25, curvature=False)
    idx = rng.choice(fine.u.size, 1000, replace=False)
    ax, rad = fine.axial.ravel()[idx], fine.radius.ravel()[idx]
    t_loc, loc = best(lambda: flank.locate(ax, rad))
    err = np.abs(loc.points - fine.points.reshape(-1, 3)[idx]).max()
    u0, p0 = fine.u.ravel()[idx] + 0.2, fine.psi_c.ravel()[idx] + 0.005
    tgt = np.stack([ax, rad], -1)

    def loc_numpy():
        u, p = numpy_newton(gen, tgt, u0, p0, lambda q: (q[..., 2], np.hypot(q[..., 0], q[..., 1])))
        return numpy_curvatures(gen, u, p, loc.normals)

    t_lnp, lnp_out = best(loc_numpy, REPEAT_BASE)

    def loc_fsolve():
        out = np.empty((1000, 3))
        for k in range(1000):
            def F(x, k=k):
                p = gen.points(x[0], x[1])
                return [np.hypot(p[0], p[1]) - rad[k], p[2] - ax[k]]
            x = fsolve(F, [u0[k], p0[k]], xtol=1e-10)
            out[k] = gen.points(x[0], x[1])
        return out

    t_lfs, lfs_pts = best(loc_fsolve, REPEAT_FSOLVE)
    compare(f"locate 1000 points with normals and curvatures (max error against the grid {err:.1e} mm)", t_loc, loc,
            t_lnp, lnp_out, t_lfs, lfs_pts, 1000, gen.cp["u_j"])
    print(f"machine load {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
