"""Throughput of the closed-form log-spiral flank (points + normals + fundamental forms + principal curvatures).

Baseline, measured in the same run (CPU time, median of N): the generic numerical module (geometry/diffgeom.py,
Richardson-extrapolated central differences) on the same surface. Both run on one core; the closed-form kernel is
compiled (numba), the baseline is numpy. The script checks that the two agree (relative curvature error) before printing
points/s and the speed ratio. Both sides are timed the same way, the median of N runs (bench/_timing.py).

Run: /work/venv/bin/python bench/bench_logspiral.py [n_points]
"""

from __future__ import annotations

import sys

import numpy as np
from _timing import median_time

from spiralbevel import LogSpiralFlank
from spiralbevel._core import logspiral_flank as kernel
from spiralbevel.geometry.diffgeom import surface_geometry


def best_of(fun, repeat=5):
    return median_time(fun, repeat, cpu=True)[0]


def main(n=1_000_000):
    rng = np.random.default_rng(0)
    flank = LogSpiralFlank(100.0, np.radians(20.0), np.radians(32.6))
    phi = rng.uniform(-0.3, 0.3, n)
    psi = rng.uniform(0.05, 0.2, n)
    varphi = flank.varphi_of(psi, phi)
    d, b = flank.base_cone_angle, flank.spiral_angle

    out = kernel.allocate(n)
    t_kernel = best_of(lambda: kernel.flank_flat(varphi, phi, 100.0, d, b, out=out))
    t_public = best_of(lambda: flank.evaluate(varphi, phi))

    m = min(n, 200_000)
    t_generic = best_of(lambda: surface_geometry(flank.point, varphi[:m], phi[:m], normal_sign=1.0))
    num = surface_geometry(flank.point, varphi[:m], phi[:m], normal_sign=1.0)
    exact = flank.evaluate(varphi[:m], phi[:m])
    err = max(np.max(np.abs(num.k1 / exact.k1 - 1)), np.max(np.abs(num.k2 / exact.k2 - 1)))
    assert err < 1e-8, err

    rate_kernel, rate_public, rate_generic = n / t_kernel, n / t_public, m / t_generic
    print(f"points: {n} (generic baseline on {m}); max rel. curvature difference closed form vs generic: {err:.2e}")
    print(f"closed-form kernel, preallocated output : {rate_kernel / 1e6:8.2f} million points/s")
    print(f"LogSpiralFlank.evaluate (public, checks) : {rate_public / 1e6:8.2f} million points/s")
    print(f"generic numerical diffgeom (baseline)    : {rate_generic / 1e6:8.2f} million points/s")
    print("(median of 5 runs each)")
    print(f"ratio kernel / generic: {rate_kernel / rate_generic:.1f}x   public / generic: "
          f"{rate_public / rate_generic:.1f}x")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000)
