"""Benchmark: misalignment sweep of the bundled synthesized face-milled pair (41-position TCA per case).

Three ways of running the same grid of cases (pinion axial, gear axial, offset, shaft angle), same records:

* ``spiralbevel``: ``misalignment_sweep`` on dask's local processes (one worker per core), a few batches per worker,
  the pool kept between sweeps (timed warm: a first small sweep starts the workers);
* baseline "one dask task per case": what a dask user writes first, ``dask.compute(*[delayed(sweep_point)(...)]``
  with the processes scheduler (new workers for each call);
* ``--scheduler sequential`` in this process (for the parallel efficiency T_seq / (workers T_par)).

Each is timed once per repeat (median of ``--repeat`` runs, default 1: a 10^4-case run takes about a minute).
Run: ``python bench/bench_sweep.py [--cases N] [--repeat R]`` (N is rounded to a 4-axis grid; default 10^4).
"""

from __future__ import annotations

import argparse
import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from _timing import fmt, median_time  # noqa: E402

from spiralbevel.io.design_file import bundled_designs, load_design  # noqa: E402
from spiralbevel.job import sweep as sw  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    k = max(1, round(args.cases ** 0.25))
    grid = {"pinion_axial": np.linspace(-0.05, 0.05, k).tolist(), "gear_axial": np.linspace(-0.05, 0.05, k).tolist(),
            "offset": np.linspace(-0.03, 0.03, k).tolist(), "shaft_angle": np.linspace(-0.02, 0.02, k).tolist()}
    n = k**4
    spec = load_design(bundled_designs()["aviation_23x65_synthesized"])
    workers = sw._local_workers()
    print(f"{n} cases ({k} values on each of 4 axes), {workers} local workers; machine load "
          f"{os.getloadavg()[0]:.1f} at start")
    sw.misalignment_sweep(spec, {"offset": [0.0] * 2 * workers})  # start the pool, build the pair in the workers
    t_pkg, recs = median_time(lambda: sw.misalignment_sweep(spec, grid), args.repeat)

    import dask

    spec_json = spec.model_dump_json()
    import itertools

    points = list(itertools.product(*[grid[a] for a in sw.AXES]))

    def per_case():
        return list(dask.compute(*[dask.delayed(sw.sweep_point)(spec_json, "drive", p) for p in points],
                                 scheduler="processes"))

    t_task, recs_task = median_time(per_case, args.repeat)
    t_seq, recs_seq = median_time(lambda: sw.misalignment_sweep(spec, grid, scheduler="sequential"), args.repeat)
    assert recs == recs_task == recs_seq
    print(f"spiralbevel, batched on {workers} workers : {fmt(t_pkg)} ({t_pkg / n * 1e3:.2f} ms per case)")
    print(f"one dask task per case (baseline)     : {fmt(t_task)}  ratio {t_task / t_pkg:.2f}x")
    print(f"sequential, this process              : {fmt(t_seq)}  ratio {t_seq / t_pkg:.2f}x; parallel efficiency "
          f"{t_seq / (workers * t_pkg):.2f} (target >= 0.85)")
    print(f"(median of {args.repeat} run(s) each; same records from all three)")


if __name__ == "__main__":
    main()
