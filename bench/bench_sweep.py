"""Benchmark: misalignment sweep of the bundled synthesized face-milled pair (41-position TCA per case).

Three ways of running the same grid of cases (pinion axial, gear axial, offset, shaft angle), same records:

* ``spiralbevel``: ``misalignment_sweep`` on dask's local processes (one worker per core), a few batches per worker,
  the pool kept between sweeps (timed warm: a first small sweep starts the workers);
* baseline "one dask task per case": what a dask user writes first, ``dask.compute(*[delayed(sweep_point)(...)]``
  with the processes scheduler (new workers for each call);
* ``--scheduler sequential`` in this process (for the parallel efficiency T_seq / (workers T_par)).

Each is timed once per repeat (median of ``--repeat`` runs, default 1: a 10^4-case run takes about a minute).
Run: ``python bench/bench_sweep.py [--cases N] [--repeat R] [--no-baseline]`` (N is rounded to a 4-axis grid; default
10^4).

The wall-clock parallel efficiency T_seq / (workers T_par) means little on a machine shared with other jobs (the
workers wait for a core). So the CPU time is measured too: of this process for the sequential run, and of each pool
worker for the parallel one (``/proc/PID/stat``, Linux). On an otherwise idle machine the parallel run takes as long as
its busiest worker, so T_seq,CPU / (workers x the busiest worker's CPU) is the efficiency it would reach there: it
counts the parallel run's overhead (scheduling, shipping batches and records) and its load imbalance, not the other
jobs.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from _timing import fmt, median_time  # noqa: E402

from spiralbevel.io.design_file import bundled_designs, load_design  # noqa: E402
from spiralbevel.job import sweep as sw  # noqa: E402


def _worker_cpu(pool) -> dict:
    """{pid: user + system CPU seconds} of the pool's worker processes (Linux /proc; {} elsewhere)."""
    out = {}
    tick = os.sysconf("SC_CLK_TCK")
    for pid in list(getattr(pool, "_processes", {}) or {}):
        try:
            with open(f"/proc/{pid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            out[pid] = (int(fields[11]) + int(fields[12])) / tick
        except (OSError, IndexError, ValueError):
            pass
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--no-baseline", action="store_true", help="skip the one-task-per-case baseline")
    args = ap.parse_args()
    k = max(1, round(args.cases ** 0.25))
    grid = {"pinion_axial": np.linspace(-0.05, 0.05, k).tolist(), "gear_axial": np.linspace(-0.05, 0.05, k).tolist(),
            "offset": np.linspace(-0.03, 0.03, k).tolist(), "shaft_angle": np.linspace(-0.02, 0.02, k).tolist()}
    n = k**4
    spec = load_design(bundled_designs()["aviation_23x65_synthesized"])
    workers = sw._local_workers()
    print(f"{n} cases ({k} values on each of 4 axes), {workers} local workers; machine load "
          f"{os.getloadavg()[0]:.1f} at start")
    # start the pool (its workers start on demand: give each a few batches) and build the pair in every worker
    sw.misalignment_sweep(spec, {"offset": [0.0] * 2 * workers * sw.MIN_BATCH})
    sw.misalignment_sweep(spec, {"offset": [0.0]}, scheduler="sequential")  # the same in this process
    pool = sw._local_pool(workers)
    cpu0 = _worker_cpu(pool)
    t_pkg, recs = median_time(lambda: sw.misalignment_sweep(spec, grid), args.repeat)
    cpu1 = _worker_cpu(pool)
    busy = [(cpu1[p] - cpu0[p]) / args.repeat for p in cpu1 if p in cpu0]

    import dask

    spec_json = spec.model_dump_json()
    import itertools

    points = list(itertools.product(*[grid[a] for a in sw.AXES]))

    def per_case():
        return list(dask.compute(*[dask.delayed(sw.sweep_point)(spec_json, "drive", p) for p in points],
                                 scheduler="processes"))

    if not args.no_baseline:
        t_task, recs_task = median_time(per_case, args.repeat)
        assert recs == recs_task
    c0 = time.process_time()
    t_seq, recs_seq = median_time(lambda: sw.misalignment_sweep(spec, grid, scheduler="sequential"), args.repeat)
    c_seq = (time.process_time() - c0) / args.repeat
    assert recs == recs_seq
    print(f"spiralbevel, batched on {workers} workers : {fmt(t_pkg)} ({t_pkg / n * 1e3:.2f} ms per case)")
    if not args.no_baseline:
        print(f"one dask task per case (baseline)     : {fmt(t_task)}  ratio {t_task / t_pkg:.2f}x")
    print(f"sequential, this process              : {fmt(t_seq)}  ratio {t_seq / t_pkg:.2f}x; parallel efficiency "
          f"{t_seq / (workers * t_pkg):.2f} (wall clock; target >= 0.85)")
    if len(busy) == workers:
        print(f"CPU time: sequential {c_seq:.2f} s ({c_seq / n * 1e3:.2f} ms per case); workers "
              + " / ".join(f"{b:.2f}" for b in busy) + f" s; efficiency on an idle machine "
              f"{c_seq / (workers * max(busy)):.2f} (overhead {sum(busy) / c_seq - 1:+.1%}, imbalance "
              f"{max(busy) / (sum(busy) / workers) - 1:+.1%})")
    print(f"(median of {args.repeat} run(s) each; same records from all; machine load {os.getloadavg()[0]:.1f} at "
          "the end)")


if __name__ == "__main__":
    main()
