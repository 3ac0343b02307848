"""Benchmark: vectorized envelope (conjugate-surface) solve and instantaneous contact line against the best simple
scipy alternative on the same arrays.

For each grid point (u, v) of a pinion log-spiral flank (black-box callable) the meshing equation
f(u, v, phi1) = (r1 x n1) . R(a1, -phi1) p = 0 (Litvin's equation of meshing, seed 000 Eq. (23)) is solved for phi1 and
the conjugate gear point is formed.

Both sides are timed the same way: median CPU time (``time.process_time``, one thread) of N runs of the whole call;
the machine is shared, and CPU time is what the load does not inflate.

Baselines (what a competent scipy user writes):

* envelope: evaluate the surface once, then ONE vectorized ``scipy.optimize.newton`` call (secant, all points at once)
  on f(phi1) from a start 0.1 rad off the root, then map the points and normals to the gear (``to_gear``, the same
  elementwise map the package uses). The package solves f = A cos phi1 + B sin phi1 + C in closed form
  (atan2/arccos, two Newton polish steps) in one compiled pass; a competent user who knows this form writes the same
  closed form with numpy (``_core.meshing.meshing_roots`` + ``polish_phi1``), so that is timed too, as a second
  baseline;
* contact line: evaluate f on a 64-point scan of v for all u at once, take the first sign change as bracket, then ONE
  vectorized ``scipy.optimize.elementwise.find_root`` (Chandrupatla) call. The package scans the same way; its start
  inside each bracket comes from the closed-form contact rotations of the bracket ends (exact on a log-spiral flank,
  hence a second case on a reparametrized flank where it is not). Both sides are dominated by the shared scan.

Run: ``python bench/bench_envelope.py``.
"""

from __future__ import annotations

import numpy as np
from _timing import median_time, report
from scipy.optimize import newton
from scipy.optimize.elementwise import find_root

from spiralbevel._core import logspiral as ls
from spiralbevel._core import meshing as _m
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


REPEAT = 21


def envelope_case(n_u, n_v):
    u = np.linspace(-0.3, 0.3, n_u)[:, None]
    v = np.linspace(0.05, 0.4, n_v)[None, :]
    t_vec, env = median_time(lambda: solve_envelope(surface, KIN, u, v), REPEAT, cpu=True)
    assert env.converged.all()
    start = env.phi1 + 0.1

    def baseline():
        r1, n1 = surface(u, v)
        phi = newton(lambda a: KIN.meshing_function(r1, n1, a), start, tol=1e-14, maxiter=50)
        return phi, KIN.to_gear(r1, phi), -KIN.to_gear(n1, phi)

    def closed_form_numpy():
        r1, n1 = surface(u, v)
        A, B, C = _m.meshing_coefficients(r1, n1, KIN.pitch_angle_pinion)
        plus = _m.meshing_roots(A, B, C)[0]
        phi = _m.wrap_near(_m.polish_phi1(A, B, C, plus), 0.0)
        return phi, KIN.to_gear(r1, phi), -KIN.to_gear(n1, phi)

    t_base, (phi_ref, pts_ref, nrm_ref) = median_time(baseline, REPEAT, cpu=True)
    t_cf, (phi_cf, pts_cf, nrm_cf) = median_time(closed_form_numpy, REPEAT, cpu=True)
    err_phi = max(np.max(np.abs(env.phi1 - phi_ref)), np.max(np.abs(env.phi1 - phi_cf)))
    err_pts = max(np.max(np.abs(env.points - pts_ref)), np.max(np.abs(env.points - pts_cf)))
    err_nrm = max(np.max(np.abs(env.normals - nrm_ref)), np.max(np.abs(env.normals - nrm_cf)))
    report(f"envelope {n_u}x{n_v} ({n_u * n_v} pts)", t_vec, t_base, "vectorized scipy newton", REPEAT)
    report(f"envelope {n_u}x{n_v} ({n_u * n_v} pts)", t_vec, t_cf, "closed form in numpy", REPEAT)
    print(f"    same results: max |dphi1| {err_phi:.1e} rad, max |dr2| {err_pts:.1e} mm, max |dn2| {err_nrm:.1e}")


def reparametrized(u, v):
    """The same flank with v -> v + v^2 / 2: the contact-rotation angle is not linear in v, so the package's
    closed-form start is not the root (its Newton has to iterate; a fairer case than the log-spiral's exact start)."""
    return surface(u, v + 0.5 * v ** 2)


def contact_line_case(n_u, surf=surface, hi=1.0, label=""):
    u = np.linspace(-0.3, 0.0, n_u)
    phi1 = 0.05
    t_vec, cl = median_time(lambda: solve_contact_line(surf, KIN, phi1, u, (0.05, hi)), REPEAT, cpu=True)
    assert cl.converged.all()

    def f(x, uu):
        r, n = surf(uu, x)
        return KIN.meshing_function(r, n, phi1)

    def baseline():
        grid = np.linspace(0.05, hi, 64)
        vals = f(grid[None, :], u[:, None])
        j = np.argmax(vals[:, :-1] * vals[:, 1:] <= 0, axis=1)
        res = find_root(f, (grid[j], grid[j + 1]), args=(u,), tolerances=dict(xatol=1e-15, xrtol=0.0))
        return res.x

    t_base, v_ref = median_time(baseline, REPEAT, cpu=True)
    report(f"contact line {n_u} pts{label}", t_vec, t_base, "scan + vectorized scipy find_root", REPEAT)
    print(f"    same roots: max |dv| {np.max(np.abs(cl.v - v_ref)):.1e} rad; Newton iterations {cl.iterations}")


if __name__ == "__main__":
    import os
    print(f"load average {os.getloadavg()[0]:.1f}; CPU time (time.process_time)")
    envelope_case(31, 15)
    envelope_case(100, 100)
    contact_line_case(200)
    contact_line_case(200, reparametrized, 0.8, " (reparametrized flank)")
