"""Wall-clock and CPU time of the main job as a user runs it: ``spiralbevel run`` in a fresh interpreter (imports
included).

* the default run (``spiralbevel run -o OUT``: the bundled log-spiral pair), warm (the compiled kernels cached),
  target <= 3 s;
* the CMC example (``spiralbevel run aviation_23x65_cmc -o OUT``, face-milled pair with multi-point control and LTCA):
  - cold: a new, empty cache directory for each run (``--cache-dir``): the FE compliance is built and the numba
    kernels are compiled, as on the first run after an install; target <= 15 s;
  - FE cold: a new cache directory holding only the compiled kernels (the FE compliance is built);
  - warm: the cache of an earlier run (FE compliance and kernels read back); target <= 5 s.

Before timing, the package's bytecode is compiled (``compileall``, as ``pip install`` does for the Quick start's
install; an editable install run with ``PYTHONDONTWRITEBYTECODE`` set would otherwise compile its about 100 modules
from source on every run), and one untimed default run and one CMC run fill the warm cache. There is no simpler
alternative to compare against; the figures are absolute, the median of ``--repeat`` runs (default 3): wall-clock time
and, since a shared machine stretches the wall clock, the CPU time (user + system) of the job's process and its
children. Each case also prints the 1-minute load average over its runs.

With ``--baseline SRC`` (the ``src`` directory of another checkout, e.g. ``git archive main src | tar -x -C /tmp/b``)
the default run of that code (put first on ``PYTHONPATH``, its bytecode compiled and its kernels cached in the same
warm cache beforehand) is alternated run by run with this code's, so that both see the same share of a busy machine;
it prints both medians and the median of the runs' ratios (baseline / this code).

Run: ``python bench/bench_job.py [--repeat R] [--only default|cold|fe-cold|warm ...] [--baseline SRC]``.
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


LOADS: list = []   # 1-minute load average at the start of every timed run


def timed_run(args, env):
    with tempfile.TemporaryDirectory() as out:
        LOADS.append(os.getloadavg()[0])
        r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
        subprocess.run([EXE, "run", *args, "-o", str(Path(out) / "o")], env=env, check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        r1, t1 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
        return t1 - t0, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)


def median_run(make_args, env, n):
    """(median wall s, median CPU s) of n runs; ``make_args()`` gives the arguments of each run (and prepares it)."""
    runs = [timed_run(make_args(), env) for _ in range(n)]
    return statistics.median(w for w, _ in runs), statistics.median(c for _, c in runs)


def load_range(first: int) -> str:
    """The load averages of the runs from index ``first`` on, as "a-b"."""
    loads = LOADS[first:]
    return f"{min(loads):.1f}-{max(loads):.1f}"


def alternated(args, env, base_env, n):
    """n pairs of runs, this code and the baseline alternating which goes first: (CPU s of this code's runs, of the
    baseline's runs), both in run order."""
    mine, base = [], []
    for i in range(n):
        for which in ((0, 1) if i % 2 == 0 else (1, 0)):
            (mine if which == 0 else base).append(timed_run(args, env if which == 0 else base_env)[1])
    return mine, base


CASES = ("default", "cold", "fe-cold", "warm")


def compile_package(package_dir=None):
    """Write the bytecode of the installed package (what ``pip install`` does), so that no timed run compiles it."""
    if package_dir is None:
        import spiralbevel

        package_dir = Path(spiralbevel.__file__).parent
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(package_dir)], check=True, stdout=subprocess.DEVNULL)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", nargs="*", choices=CASES, default=None, help="cases to time (default: all)")
    ap.add_argument("--baseline", type=Path, default=None,
                    help="src directory of other code to alternate the default run with (see the module docstring)")
    a = ap.parse_args()
    n, only = a.repeat, set(a.only or CASES)
    cmc = "aviation_23x65_cmc"
    compile_package()
    if a.baseline is not None:
        if not (a.baseline / "spiralbevel" / "__init__.py").is_file():
            raise SystemExit(f"--baseline {a.baseline}: no spiralbevel package in it")
        compile_package(a.baseline / "spiralbevel")
    with tempfile.TemporaryDirectory() as root:
        root = Path(root)
        warm = root / "warm"
        env = dict(os.environ, SPIRALBEVEL_CACHE=str(warm), OPENBLAS_NUM_THREADS="1")
        env.pop("PYTHONPATH", None)
        base_env = None if a.baseline is None else dict(env, PYTHONPATH=str(a.baseline.resolve()))
        timed_run(["--cache-dir", str(warm)], env)          # compiles the kernels into the warm cache
        if base_env is not None:
            timed_run(["--cache-dir", str(warm)], base_env)  # and the baseline's (numba keys them by source file)
        if only - {"default"}:
            timed_run([cmc, "--cache-dir", str(warm)], env)  # and builds the FE compliance there
        kernels = root / "kernels"
        shutil.copytree(warm / "numba", kernels / "numba")  # the compiled kernels alone
        count = iter(range(10**6))

        def fresh(template=None):
            def make():
                d = root / f"cold{next(count)}"
                if template is not None:
                    shutil.copytree(template, d)
                return [cmc, "--cache-dir", str(d)]
            return make

        print(f"machine load {os.getloadavg()[0]:.1f} at start; median of {n} runs each")
        for case, label, make, target in (
                ("default", "default run (log-spiral pair)", lambda: ["--cache-dir", str(warm)], 3),
                ("cold", "CMC example, cold (empty cache)", fresh(), 15),
                ("fe-cold", "CMC example, FE cold (kernels cached)", fresh(kernels), None),
                ("warm", "CMC example, warm (FE cache)", lambda: [cmc, "--cache-dir", str(warm)], 5)):
            if case not in only:
                continue
            first = len(LOADS)
            w, c = median_run(make, env, n)
            goal = f"   (target <= {target} s)" if target else ""
            print(f"{label:38s}: wall {w:7.2f} s, CPU {c:7.2f} s{goal}   load {load_range(first)}")
        if base_env is not None and "default" in only:
            first = len(LOADS)
            mine, base = alternated(["--cache-dir", str(warm)], env, base_env, n)
            ratios = [b / m for m, b in zip(mine, base)]
            print(f"default run alternated with --baseline, {n} pairs, load {load_range(first)}: CPU median "
                  f"{statistics.median(mine):.2f} s ({min(mine):.2f}-{max(mine):.2f}) against "
                  f"{statistics.median(base):.2f} s ({min(base):.2f}-{max(base):.2f}); median ratio baseline / this "
                  f"code {statistics.median(ratios):.3f}")
        print(f"machine load {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
