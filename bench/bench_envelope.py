"""Benchmark: vectorized envelope (conjugate-surface) solve vs a per-point scipy loop of the same equations.

For each grid point (u, v) of a pinion log-spiral flank (black-box callable) the meshing equation
f(u, v, phi1) = (r1 x n1) . R(a1, -phi1) p = 0 (ERRATA §2.2) is solved for phi1 and the conjugate gear point is formed.
Baseline: per point, evaluate the surface, ``scipy.optimize.fsolve`` on f(phi1) from a start 0.1 rad off the root,
map the point. Also: the instantaneous contact line (safeguarded Newton over all u at once) vs per-point
``scipy.optimize.brentq``. Run: ``python bench/bench_envelope.py``.
"""

from __future__ import annotations

import time

import numpy as np
from scipy.optimize import brentq, fsolve

from spiralbevel._core import logspiral as ls
from spiralbevel.meshing.envelope import solve_contact_line, solve_envelope
from spiralbevel.meshing.kinematics import BevelPairKinematics

KIN = BevelPairKinematics(np.radians(90.0), 23, 65)
ALPHA_T = np.radians(20.0)
D1 = np.arcsin(np.sin(KIN.pitch_angle_pinion) * np.cos(ALPHA_T))
BETA = np.radians(35.0)


def surface(u, v):
    """Pinion flank: u = phi (spiral parameter), v = psi > 0; outward normals (seed 000 Eq. 16)."""
    u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
    g = ls.geometry(u + v / np.sin(D1), u, 100.0, D1, BETA)
    return g["r"], g["n"]


def best_of(fun, repeat):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t0)
    return best, out


def envelope_case(n_u, n_v):
    u = np.linspace(-0.3, 0.3, n_u)[:, None]
    v = np.linspace(0.05, 0.4, n_v)[None, :]
    t_vec, env = best_of(lambda: solve_envelope(surface, KIN, u, v), 5)
    assert env.converged.all()

    uu, vv = np.broadcast_arrays(u, v)

    def loop():
        phi = np.empty(uu.shape)
        pts = np.empty(uu.shape + (3,))
        for idx in np.ndindex(uu.shape):
            r1, n1 = surface(uu[idx], vv[idx])
            f = lambda a: [float(KIN.meshing_function(r1, n1, a[0]))]
            sol, info, ier, _ = fsolve(f, [env.phi1[idx] + 0.1], xtol=1e-14, full_output=True)
            phi[idx] = sol[0]
            pts[idx] = KIN.to_gear(r1, sol[0])
        return phi, pts

    t_loop, (phi_ref, pts_ref) = best_of(loop, 1)
    err_phi = np.max(np.abs(env.phi1 - phi_ref))
    err_pts = np.max(np.abs(env.points - pts_ref))
    print(f"envelope {n_u:>3}x{n_v:<3} ({n_u * n_v:>5} pts): vectorized {t_vec * 1e3:8.2f} ms, "
          f"fsolve loop {t_loop * 1e3:9.1f} ms, ratio {t_loop / t_vec:7.0f}x, max |dphi1| {err_phi:.1e} rad, "
          f"max |dr2| {err_pts:.1e} mm")


def contact_line_case(n_u):
    u = np.linspace(-0.3, 0.0, n_u)
    phi1 = 0.05
    t_vec, cl = best_of(lambda: solve_contact_line(surface, KIN, phi1, u, (0.05, 1.0)), 5)
    assert cl.converged.all()

    def loop():
        out = np.empty(n_u)
        for k in range(n_u):
            def f(x):
                r, n = surface(u[k], x)
                return float(KIN.meshing_function(r, n, phi1))

            grid = np.linspace(0.05, 1.0, 64)
            vals = [f(x) for x in grid]
            j = next(i for i in range(63) if vals[i] * vals[i + 1] <= 0)
            out[k] = brentq(f, grid[j], grid[j + 1], xtol=1e-15)
        return out

    t_loop, v_ref = best_of(loop, 1)
    print(f"contact line {n_u:>4} pts: vectorized {t_vec * 1e3:8.2f} ms, scan+brentq loop {t_loop * 1e3:9.1f} ms, "
          f"ratio {t_loop / t_vec:7.0f}x, max |dv| {np.max(np.abs(cl.v - v_ref)):.1e} rad")


if __name__ == "__main__":
    envelope_case(31, 15)
    envelope_case(100, 100)
    contact_line_case(200)
