"""Wall-clock time of the main job as a user runs it: ``spiralbevel run`` in a fresh interpreter (imports included).

* the default run (``spiralbevel run -o OUT``: the bundled log-spiral pair), target <= 3 s;
* the CMC example (``spiralbevel run aviation_23x65_cmc -o OUT``, face-milled pair with multi-point control and LTCA),
  cold (empty FE cache: the FE compliance is built) and warm (the FE cache of the cold run), targets 15 s and 5 s.

There is no simpler alternative to compare against; the figures are absolute (median of ``--repeat`` runs, default 3;
the cold run clears the cache before each repeat): wall-clock time and, since a shared machine stretches the wall
clock, the CPU time (user + system) of the job's process and its children. Run: ``python bench/bench_job.py [--repeat
R]``.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

EXE = str(Path(sys.executable).with_name("spiralbevel"))


def timed_run(args, env):
    with tempfile.TemporaryDirectory() as out:
        r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
        subprocess.run([EXE, "run", *args, "-o", str(Path(out) / "o")], env=env, check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        r1, t1 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
        return t1 - t0, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)


def median_run(args, env, n, before=None):
    """(median wall s, median CPU s) of n runs."""
    runs = []
    for _ in range(n):
        if before:
            before()
        runs.append(timed_run(args, env))
    return statistics.median(w for w, _ in runs), statistics.median(c for _, c in runs)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    n = ap.parse_args().repeat
    print(f"machine load {os.getloadavg()[0]:.1f} at start; median of {n} runs each")
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, SPIRALBEVEL_CACHE=cache, OPENBLAS_NUM_THREADS="1")
        def clear():
            shutil.rmtree(cache, ignore_errors=True)
            os.makedirs(cache)

        for label, args, before, target in (("default run (log-spiral pair)", [], None, 3),
                                            ("CMC example, cold (FE built)", ["aviation_23x65_cmc"], clear, 15),
                                            ("CMC example, warm (FE cache)", ["aviation_23x65_cmc"], None, 5)):
            w, c = median_run(args, env, n, before)
            print(f"{label:32s}: wall {w:7.2f} s, CPU {c:7.2f} s   (target <= {target} s)")


if __name__ == "__main__":
    main()
