"""Benchmark: full TCA (41 positions x 3 tooth pairs + contact ellipses) with the batched solver against a plain
per-position scipy.optimize.fsolve of the same contact equations, measured in the same run, on one core.

Run:  python bench/bench_tca.py
Target (task brief): vectorized >= 100x faster than the baseline and under 50 ms.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import time  # noqa: E402
import warnings  # noqa: E402

import numpy as np  # noqa: E402
from scipy.optimize import fsolve  # noqa: E402

from spiralbevel._core.rotations import rot_z  # noqa: E402
from spiralbevel.meshing.contact_problem import ContactProblem  # noqa: E402
from spiralbevel.meshing.contact_surface import NormalDeviation, quadratic_crowning  # noqa: E402
from spiralbevel.meshing.ellipse import contact_ellipse_from_surfaces  # noqa: E402
from spiralbevel.meshing.kinematics import BevelPairKinematics  # noqa: E402
from spiralbevel.meshing.tca import solve_tca  # noqa: E402
from spiralbevel.meshing.tca_surfaces import conjugate_logspiral_pair  # noqa: E402


def baseline(prob, x_mean, phi1, pairs, phi1_mean):
    """Plain TCA: for each pair march from its mean point (phi10 - k T) through the positions with fsolve started
    from the previous solution (unknowns shifted by +1: MINPACK's difference step needs |x| ~ 1), then the contact
    ellipse at each solution."""
    T = 2 * np.pi / prob.z1
    dphi = phi1[1] - phi1[0]
    out = np.full((len(phi1), len(pairs), 5), np.nan)
    nsolve = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        for j, k in enumerate(pairs):
            # effective angle path from the mean point to each position of the cycle, in steps of dphi
            for direction in (1.0, -1.0):
                x = x_mean.copy()
                o = 0.0
                targets = (phi1 - phi1_mean) + k * T  # effective offsets of this pair's positions
                lim = targets.max() if direction > 0 else targets.min()
                while direction * o <= direction * lim + 1e-12:
                    phi = phi1_mean + o
                    basis = prob.basis(x, phi)
                    y = fsolve(lambda v: prob.residual(v - 1.0, phi, basis), x + 1.0, xtol=1e-13)
                    x = y - 1.0
                    nsolve += 1
                    hit = np.nonzero(np.abs(targets - o) < 1e-9)[0]
                    for i in hit:
                        out[i, j] = x
                    o += direction * dphi
    # ellipses at every solution
    for i in range(len(phi1)):
        for j, k in enumerate(pairs):
            x = out[i, j]
            pe = phi1[i] + 2 * np.pi * k / prob.z1
            R1, R2, _, _ = prob.pose(pe, x[4])
            contact_ellipse_from_surfaces(prob.pinion, x[0:2], R1, prob.gear, x[2:4], R2)
    return out, nsolve


def main():
    pair = conjugate_logspiral_pair()
    kin = BevelPairKinematics(pair.shaft_angle, pair.z1, pair.z2)
    crowned = NormalDeviation(pair.pinion, quadratic_crowning(pair.pinion.reference_params, (0.5, 0.0, 5.0)))
    for name, pin in (("crowned log-spiral pair (point contact)", crowned),
                      ("conjugate log-spiral pair (line contact)", pair.pinion)):
        solve_tca(pin, pair.gear, kin)  # warm-up
        reps = 20
        t0 = time.perf_counter()
        for _ in range(reps):
            res = solve_tca(pin, pair.gear, kin)
        t_vec = (time.perf_counter() - t0) / reps
        assert np.max(res.residual) < 1e-9, "not converged"
        prob = ContactProblem(pin, pair.gear, kin)
        xm = np.r_[res.params1[20, 1], res.params2[20, 1], res.phi2_pairs[20, 1]]
        t0 = time.perf_counter()
        xb, nsolve = baseline(prob, xm, res.phi1, res.pairs, res.phi1_mean)
        t_base = time.perf_counter() - t0
        # same contact points (line contact: the point on the line is arbitrary -> compare TE only)
        phi2b = prob.gear_angle(xb[..., 4], res.pairs[None, :])
        dte = np.nanmax(np.abs(phi2b - res.phi2_pairs))
        print(f"{name}:")
        print(f"  vectorized TCA : {t_vec * 1e3:8.2f} ms  (41 positions x 3 pairs + ellipses, "
              f"{res.iterations} final Newton iterations)")
        print(f"  fsolve baseline: {t_base * 1e3:8.2f} ms  ({nsolve} fsolve calls + 123 ellipses)")
        print(f"  speed-up       : {t_base / t_vec:8.1f} x    max |phi2 difference| {dte:.2e} rad")


if __name__ == "__main__":
    main()
