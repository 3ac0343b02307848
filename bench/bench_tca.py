"""Benchmark: full TCA (41 positions x 3 tooth pairs + contact ellipses) with the batched solver against a plain
per-position scipy.optimize.fsolve of the same contact equations, measured in the same run, on one core.

Run:  python bench/bench_tca.py [--quick]
Targets: under 50 ms (met); 1 ms for the face-milled pair (met: 0.82-0.84 ms at load 0.8-0.9, JIT-compiled or
from the ahead-of-time extension). Compiled: the surface-contact Newton with the jets
of both flank kinds and of the crowned flank (quadratic normal deviation), the edge-contact Newton (analytic Jacobian,
compiled boundary margins), solved together with the margins, TE, flank tests (with the generated flanks' limit-line
test), screen and acceptance of its solutions in one call per batch, corners of the pinion's fillet junction that a
proof excludes not solved, the surface contacts' flank test, the path predictor, the line-contact test, the contact
geometry of the ellipses (poses, Weingarten tensors, relative curvatures), the continuation of the path of contact (its
levels, predictors, Newton solves and tangents in one call) and the transfer-point iteration (regula falsi with the
surface and edge Newton of each trial inside the kernel, one call per TCA); what is left is the Python orchestration
between them (mean point, edge candidates, TE and statuses, the edge contacts' surface data, the ellipses' arguments:
numpy calls on small arrays) and the fixed cost of each compiled call.

Cases: the crowned log-spiral pair (point contact), the exactly conjugate log-spiral pair (line contact) and the
seed 001 face-milled pair with the locally synthesized pinion (drive side, as the job runs it: ``phased_for_pair``).

Baseline (what a competent scipy user writes): one ``scipy.optimize.fsolve`` per position and pair with the same
residual function (``ContactProblem.residual``), the package's analytic Jacobian (``ContactProblem.system``, passed as
``fprime``) and the same basis of the normal equations, warm-started from the previous position:
pair 0 marches from the mean point to both ends of the cycle; pair k > 0 starts at its first position from pair
k - 1's last one (the same assembly configuration: effective angles coincide), pair k < 0 likewise at its last
position. A pair's march stops at the first position where fsolve does not converge (end of the path of contact;
the failed call is timed). Then the pair with the largest TE at each position and its contact ellipse
(``contact_ellipse_from_surfaces``): 41 ellipses, as in the vectorized TCA. Both must find the same solutions: the
script prints the largest difference and stops if it exceeds 1e-9. Both sides are timed the same way: the median of
N runs of the whole computation (bench/_timing.py), in CPU time of this process (both are single-threaded; the
machine is shared, its load is printed). The compiled kernels are warmed up (cached) before timing.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ[_v] = "1"
if hasattr(os, "sched_setaffinity"):
    os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})  # one core

import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402

import numpy as np  # noqa: E402
from _timing import median_time  # noqa: E402
from scipy.optimize import fsolve  # noqa: E402

from spiralbevel.meshing.contact_problem import ContactProblem  # noqa: E402
from spiralbevel.meshing.contact_surface import NormalDeviation, quadratic_crowning  # noqa: E402
from spiralbevel.meshing.ellipse import contact_ellipse_from_surfaces  # noqa: E402
from spiralbevel.meshing.kinematics import BevelPairKinematics  # noqa: E402
from spiralbevel.meshing.tca import solve_tca  # noqa: E402
from spiralbevel.meshing.tca_result import ContactStatus  # noqa: E402
from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair  # noqa: E402


def baseline(prob, x_mean, phi1, pairs, phi1_mean, approach):
    """Per-position fsolve TCA (see the module docstring). Returns (x (n, P, 5), calls, failed calls, seconds spent
    in failed calls)."""
    n, P = len(phi1), len(pairs)
    T = 2 * np.pi / prob.z1
    mid = int(np.argmin(np.abs(phi1 - phi1_mean)))
    out = np.full((n, P, 5), np.nan)
    stats = {"calls": 0, "failed": 0, "t_failed": 0.0}

    def solve(x_prev, phi):
        t0 = time.perf_counter()
        basis = prob.basis(x_prev, phi)
        y, info, ier, _ = fsolve(lambda v: prob.residual(v - 1.0, phi, basis), x_prev + 1.0, xtol=1e-13,
                                 fprime=lambda v: prob.system(v - 1.0, phi, basis)[1], full_output=True)
        x = y - 1.0
        stats["calls"] += 1
        ok = np.all(np.isfinite(x)) and np.max(np.abs(prob.residual(x, phi, basis))) < 1e-9
        if not ok:
            stats["failed"] += 1
            stats["t_failed"] += time.perf_counter() - t0
        return x, ok

    def march(j, k, x0, order):
        x = x0
        for i in order:
            x, ok = solve(x, phi1[i] + k * T)
            if not ok:
                return
            out[i, j] = x

    order = np.argsort(pairs)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        j0 = int(np.nonzero(pairs == 0)[0][0])
        march(j0, 0, x_mean, range(mid, n))
        march(j0, 0, out[mid, j0] if np.isfinite(out[mid, j0, 0]) else x_mean, range(mid - 1, -1, -1))
        for j in order[np.searchsorted(pairs[order], 1):]:  # k = 1, 2, ...: from pair k-1's last position
            jp = int(np.nonzero(pairs == pairs[j] - 1)[0][0])
            if np.isfinite(out[n - 1, jp, 0]):
                march(j, pairs[j], out[n - 1, jp], range(0, n))
        for j in order[:np.searchsorted(pairs[order], 0)][::-1]:  # k = -1, -2, ...: from pair k+1's first position
            jp = int(np.nonzero(pairs == pairs[j] + 1)[0][0])
            if np.isfinite(out[0, jp, 0]):
                march(j, pairs[j], out[0, jp], range(n - 1, -1, -1))
    # the pair in contact (largest TE) and its contact ellipse
    phi2 = prob.gear_angle(out[..., 4], pairs[None, :])
    te = -(phi2 - phi2[mid, j0]) - prob.ratio * (phi1[:, None] - phi1_mean)
    sel = np.argmax(np.where(np.isfinite(te), te, -np.inf), axis=1)
    for i in range(n):
        x = out[i, sel[i]]
        if np.isfinite(x[0]):
            R1, R2, _, _ = prob.pose(phi1[i] + pairs[sel[i]] * T, x[4])
            contact_ellipse_from_surfaces(prob.pinion, x[0:2], R1, prob.gear, x[2:4], R2, approach)
    return out, stats


def facemilled_case():
    """Seed 001 drive side: gear convex (Table 4 settings), pinion concave by local synthesis (eta = 6 deg,
    a = 3.7 mm, 3 arcsec), phased as in ``job.tca.run_pair_tca``."""
    from spiralbevel.conventions import Member, Side
    from spiralbevel.machine import seed001_blank, seed001_settings
    from spiralbevel.meshing.generated_surface import phased_for_pair
    from spiralbevel.meshing.synthesis import synthesize_pinion

    blank = seed001_blank()
    gc, gs = seed001_settings()[(Member.GEAR, Side.CONVEX)]
    r = synthesize_pinion(gc, gs, blank, side=Side.CONCAVE, eta=math.radians(6.0), semi_major_axis=3.7,
                          te_magnitude=3 * math.pi / 648000)
    c1, c2 = phased_for_pair(r.pinion_flank, r.gear_flank)
    kin = BevelPairKinematics(blank.Sigma, blank.z1, blank.z2)
    return c1, c2, kin, {"start": np.r_[c1.reference_params, c2.reference_params, 0.0]}


def run_case(name, pinion, gear, kin, kw, reps_vec, reps_base, line=False):
    solve_tca(pinion, gear, kin, **kw)  # warm-up
    t_vec, res = median_time(lambda: solve_tca(pinion, gear, kin, **kw), reps_vec, cpu=True)
    prob = ContactProblem(pinion, gear, kin)
    j0 = list(res.pairs).index(0)
    mid = len(res.phi1) // 2
    xm = np.r_[res.params1[mid, j0], res.params2[mid, j0], res.phi2_pairs[mid, j0]]
    t_base, (xb, st) = median_time(lambda: baseline(prob, xm, res.phi1, res.pairs, res.phi1_mean, res.approach),
                                 reps_base, cpu=True)
    # same solutions: gear angle (TE) everywhere both converged; the contact point too for point contact. The
    # baseline solves the surface contact only: pairs whose surface contact leaves a flank are edge contacts in the
    # vectorized TCA (solved there, in its time) and are not compared
    n_edge = int(np.sum(res.status_pairs == ContactStatus.EDGE))
    found_v = (res.status_pairs == ContactStatus.OK) | (res.status_pairs == ContactStatus.LINE)
    found_b = np.isfinite(xb[..., 0])
    both = found_v & found_b
    phi2b = prob.gear_angle(xb[..., 4], res.pairs[None, :])
    d_phi2 = np.max(np.abs(phi2b - res.phi2_pairs)[both])
    d_x = 0.0 if line else np.max(np.abs(np.concatenate([xb[..., 0:4][both] - np.concatenate(
        [res.params1, res.params2], -1)[both]])))
    only_v, only_b = int(np.sum(found_v & ~found_b)), int(np.sum(found_b & ~found_v))
    print(f"{name}:")
    print(f"  vectorized TCA : {t_vec * 1e3:8.2f} ms  (41 positions x 3 pairs + 41 ellipses; "
          f"{res.iterations} final Newton iterations; {n_edge} edge contacts solved)")
    print(f"  fsolve baseline: {t_base * 1e3:8.2f} ms  ({st['calls']} fsolve calls, {st['failed']} not converged "
          f"({st['t_failed'] * 1e3:.1f} ms), 41 ellipses)")
    print(f"  ratio          : {t_base / t_vec:8.1f} x  (median of {reps_vec} / {reps_base} runs, CPU time)", end="")
    if st["failed"]:
        print(f"   (without the failed fsolve calls: {(t_base - st['t_failed']) / t_vec:.1f} x)", end="")
    print()
    print(f"  same solutions : {int(both.sum())} systems, max |phi2 diff| {d_phi2:.1e} rad"
          + ("" if line else f", max |param diff| {d_x:.1e}")
          + f"; found only by vectorized {only_v}, only by baseline {only_b} (edge contacts not compared)")
    if d_phi2 > 1e-9 or d_x > 1e-9:
        sys.exit(f"{name}: vectorized and baseline solutions differ")
    return t_vec, t_base


def main():
    quick = "--quick" in sys.argv
    print(f"machine load {os.getloadavg()[0]:.1f} at start")
    pair = conjugate_logspiral_pair()
    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    crowned = NormalDeviation(pair.pinion, quadratic_crowning(pair.pinion.reference_params, (0.5, 0.0, 5.0)))
    rv, rb = (5, 3) if quick else (51, 7)
    run_case("crowned log-spiral pair (point contact)", crowned, pair.gear, kin, {}, rv, rb)
    run_case("conjugate log-spiral pair (line contact)", pair.pinion, pair.gear, kin, {}, rv, rb, line=True)
    c1, c2, kf, kw = facemilled_case()
    run_case("seed 001 face-milled pair, synthesized pinion (drive side)", c1, c2, kf, kw, rv, rb)
    print(f"machine load {os.getloadavg()[0]:.1f} at end (2 cores, shared); times are CPU time of this process "
          "(time.process_time), one core")


if __name__ == "__main__":
    main()
