"""Where the cold start of the CMC example goes: the numba compile time of every kernel of its main job.

Runs ``spiralbevel run aviation_23x65_cmc`` once in this interpreter with a new, empty cache directory (as
``bench_job.py``'s "cold" run) and listens to numba's compile events (``numba.core.event``). Prints

* the job's CPU and wall time, the CPU time inside numba compiles and the part of it under LLVM's lock (LLVM
  optimisation and machine code; the rest is numba's Python front end: typing, rewrites, lowering to LLVM IR);
* per compiled function (kernels of ``spiralbevel._core`` and the numba implementations of numpy calls they pull in):
  the CPU time of its own compiles (without the nested compiles of its callees), with them, and the number of
  specialisations; a function compiled more than once is listed with its signatures (``--signatures``).

* with ``--ir``: the LLVM IR that LLVM optimised and emitted: the instructions of every compiled function's module
  together with the callees it links (numba links the IR of every kernel a function calls into its module and
  optimises and emits it again there), against the distinct functions among them. A count, not a time: it does not
  move with the machine load, so it compares two versions of the kernels on a busy machine (the counting itself adds
  a few seconds of CPU to the run).

* with ``--aot N``: the cold run with the ahead-of-time extension of the kernels (``_core/_aot``, built by ``pip
  install -e .``; ``_core/jit.py``) against the JIT (``SPIRALBEVEL_AOT=0``), N pairs alternated (which goes first
  alternates too), each a fresh interpreter with a new, empty numba cache (``SPIRALBEVEL_CACHE``) and FE cache
  (``--cache-dir``): the CPU time of the whole process (imports included, ``RUSAGE_CHILDREN``), its wall time, the
  CPU of the job alone and the numba compiles in it; then the outputs of the last AOT and JIT runs compared byte for
  byte (every file; report.json and report.html with their timings removed). The target is <= 15 s CPU cold.
* with ``--warm N``: the warm cost of the same kernels, the face-milled TCA of ``bench_tca.py`` (41 positions x 3
  pairs with ellipses and edge contacts; the median CPU time of 41 runs after a warm-up run) with the extension and
  with the JIT (its machine code read from a numba cache filled beforehand), N pairs of fresh interpreters alternated:
  the Python calls of the kernels go through the extension's entry points instead of the JIT's.
* with ``--build``: the install-time cost, the extension built again into a temporary directory (``aot_build``) in
  a fresh interpreter: its CPU and wall time and the size of the module.

Without ``--aot``: there is no alternative to compare against: the figures locate the compile cost (``_core/jit.py``
lists the rules it led to). One run (a cold run is not repeatable in one process); CPU time is ``time.process_time``,
the machine load is printed. Run: ``python bench/bench_compile.py [--top N] [--signatures] [--ir] [--aot N]
[--warm N] [--build]``.
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from numba.core import event


class _Compiles(event.Listener):
    """Exclusive and inclusive CPU time of every numba compile, by function."""

    def __init__(self):
        self.stack = []
        self.own = collections.defaultdict(float)
        self.total = collections.defaultdict(float)
        self.sigs = collections.defaultdict(list)

    def on_start(self, ev):
        self.stack.append([ev.data["dispatcher"], time.process_time(), 0.0])

    def on_end(self, ev):
        disp, t0, nested = self.stack.pop()
        dt = time.process_time() - t0
        f = disp.py_func
        name = f"{f.__module__.replace('spiralbevel._core.', '')}.{f.__qualname__}"
        self.own[name] += dt - nested
        if not any(d is disp for d, _, _ in self.stack):   # recursion: count once
            self.total[name] += dt
        self.sigs[name].append(str(ev.data.get("args")))
        if self.stack:
            self.stack[-1][2] += dt


class _Timer(event.Listener):
    def __init__(self):
        self.t, self.depth, self.t0 = 0.0, 0, 0.0

    def on_start(self, ev):
        if self.depth == 0:
            self.t0 = time.process_time()
        self.depth += 1

    def on_end(self, ev):
        self.depth -= 1
        if self.depth == 0:
            self.t += time.process_time() - self.t0


class _LinkedIR:
    """Instructions of the LLVM modules numba optimises (each with the callees it links), by function name."""

    def __init__(self):
        from numba.core import codegen

        self.modules, self.size = 0, {}
        self.total = 0
        optimize = codegen.CPUCodeLibrary._optimize_final_module

        def counted(library):
            self.modules += 1
            for fn in library._final_module.functions:
                if not fn.is_declaration:
                    n = sum(1 for b in fn.blocks for _ in b.instructions)
                    self.total += n
                    self.size[fn.name] = max(n, self.size.get(fn.name, 0))
            return optimize(library)

        codegen.CPUCodeLibrary._optimize_final_module = counted


def _child(example, out):
    """One cold run in this (fresh) interpreter: print the job's CPU and wall time and its numba compiles as JSON."""
    compiles, compile_all = _Compiles(), _Timer()
    event.register("numba:compile", compiles)
    event.register("numba:compile", compile_all)
    from spiralbevel._core import jit
    from spiralbevel.cli import app

    os.makedirs(out, exist_ok=True)
    t0, w0 = time.process_time(), time.perf_counter()
    code = app(["run", example, "-o", os.path.join(out, "out"), "--cache-dir", os.path.join(out, "fe")],
               standalone_mode=False)
    if code:
        sys.exit(f"spiralbevel run {example} failed ({code})")
    print(json.dumps({"job_cpu": time.process_time() - t0, "job_wall": time.perf_counter() - w0,
                      "compile_cpu": compile_all.t, "compiles": sum(len(v) for v in compiles.sigs.values()),
                      "aot": bool(jit.aot_module())}))


def _cold_run(example, out, aot):
    """A fresh interpreter running ``_child`` with empty caches; returns its figures with the process's CPU and wall."""
    env = {**os.environ, "SPIRALBEVEL_CACHE": os.path.join(out, "cache"), "SPIRALBEVEL_AOT": "1" if aot else "0"}
    env.pop("SPIRALBEVEL_AOT_STRICT", None)
    r0, t0, load = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter(), os.getloadavg()[0]
    p = subprocess.run([sys.executable, __file__, "--child", out, "--example", example], env=env, check=True,
                       capture_output=True, text=True)
    r1, t1 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    fig = json.loads(p.stdout.strip().splitlines()[-1])
    fig.update(cpu=(r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime), wall=t1 - t0, load=load)
    return fig


#: timings in report.json ("elapsed": 0.03, "timings": {...}) and in report.html's tables (a row named so)
_TIMING = (re.compile(rb'"[a-z_]*(time|timings|seconds|elapsed)[a-z_]*": *(\{[^{}]*\}|[-0-9.e]+)'),
           re.compile(rb'<code>[a-z_]*(time|timings|seconds|elapsed)[a-z_]*</code></td><td class=num>[^<]*</td>'))


def _differences(a: Path, b: Path) -> list:
    """Files of output directories ``a``, ``b`` that differ (report.json / report.html compared without timings)."""
    fa = sorted(p.relative_to(a) for p in a.rglob("*") if p.is_file())
    fb = sorted(p.relative_to(b) for p in b.rglob("*") if p.is_file())
    if fa != fb:
        return [f"file lists differ: {sorted(set(fa) ^ set(fb))}"]
    diff = []
    for rel in fa:
        x, y = (a / rel).read_bytes(), (b / rel).read_bytes()
        if rel.name in ("report.json", "report.html"):
            for pattern in _TIMING:
                x, y = pattern.sub(b"", x), pattern.sub(b"", y)
        if x != y:
            diff.append(str(rel))
    return diff


def compare_aot(example, n):
    """``--aot N``: N pairs of cold runs, extension and JIT alternated (see the module docstring)."""
    runs = {True: [], False: []}
    with tempfile.TemporaryDirectory() as d:
        for i in range(n):
            for aot in ((True, False) if i % 2 == 0 else (False, True)):
                out = os.path.join(d, f"{'aot' if aot else 'jit'}{i}")
                fig = _cold_run(example, out, aot)
                if fig["aot"] != aot:
                    sys.exit("the ahead-of-time extension is not built or not current: pip install -e . first")
                runs[aot].append(fig)
                print(f"  {'AOT' if aot else 'JIT'} run {i + 1}: CPU {fig['cpu']:.1f} s (job {fig['job_cpu']:.1f} s, "
                      f"compiles {fig['compiles']}: {fig['compile_cpu']:.1f} s), wall {fig['wall']:.1f} s, "
                      f"load {fig['load']:.1f}", file=sys.stderr)
        diff = _differences(Path(d) / f"aot{n - 1}" / "out", Path(d) / f"jit{n - 1}" / "out")
        nfiles = sum(1 for p in (Path(d) / f"aot{n - 1}" / "out").rglob("*") if p.is_file())
    for aot in (True, False):
        r = runs[aot]
        print(f"{example}, cold, {'AOT extension' if aot else 'JIT (SPIRALBEVEL_AOT=0)'}: median of {n}: CPU "
              f"{statistics.median(x['cpu'] for x in r):.1f} s, wall {statistics.median(x['wall'] for x in r):.1f} s, "
              f"job CPU {statistics.median(x['job_cpu'] for x in r):.1f} s, numba compiles "
              f"{statistics.median(x['compiles'] for x in r):.0f} "
              f"({statistics.median(x['compile_cpu'] for x in r):.1f} s CPU)", file=sys.stderr)
    print(f"outputs AOT vs JIT: {nfiles} files, " + ("all identical (report.json/html but their timings)" if not diff
          else f"DIFFERENT: {diff}"), file=sys.stderr)


def _tca_child():
    """Median CPU time of the face-milled TCA of bench_tca.py in this interpreter (printed as JSON)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import bench_tca  # one core, one thread (set at its import)
    from _timing import median_time

    from spiralbevel._core import jit

    from spiralbevel._core import tca_ellipse

    c1, c2, kin, kw = bench_tca.facemilled_case()
    bench_tca.solve_tca(c1, c2, kin, **kw)
    t, _ = median_time(lambda: bench_tca.solve_tca(c1, c2, kin, **kw), 41, cpu=True)
    # the fixed cost of one Python call (5 arguments, no work: empty arrays)
    args = (np.empty((0, 3, 2)), np.empty((0, 3, 2)), np.empty((0, 3, 3)), True, np.empty((0, 3, 3)))
    tca_ellipse.weingarten_batch(*args)
    call, _ = median_time(lambda: [tca_ellipse.weingarten_batch(*args) for _ in range(10000)], 5, cpu=True)
    print(json.dumps({"tca_ms": t * 1e3, "call_us": call * 1e2, "aot": bool(jit.aot_module())}))


def compare_warm(n):
    """``--warm N``: face-milled TCA with the extension against the JIT, N pairs of fresh interpreters."""
    with tempfile.TemporaryDirectory() as d:
        env = {**os.environ, "SPIRALBEVEL_CACHE": d}
        env.pop("SPIRALBEVEL_AOT_STRICT", None)
        subprocess.run([sys.executable, __file__, "--tca-child"], env={**env, "SPIRALBEVEL_AOT": "0"}, check=True,
                       capture_output=True)  # fills the numba cache of the JIT runs
        runs = {True: [], False: []}
        for i in range(n):
            for aot in ((True, False) if i % 2 == 0 else (False, True)):
                load = os.getloadavg()[0]
                p = subprocess.run([sys.executable, __file__, "--tca-child"], check=True, capture_output=True,
                                   text=True, env={**env, "SPIRALBEVEL_AOT": "1" if aot else "0"})
                fig = json.loads(p.stdout.strip().splitlines()[-1])
                if fig["aot"] != aot:
                    sys.exit("the ahead-of-time extension is not built or not current: pip install -e . first")
                runs[aot].append(fig["tca_ms"])
                print(f"  {'AOT' if aot else 'JIT'}: face-milled TCA {fig['tca_ms']:.3f} ms (median of 41, CPU); "
                      f"one call of a 5-argument kernel doing nothing {fig['call_us']:.2f} us; load {load:.1f}",
                      file=sys.stderr)
    ratios = [j / a for a, j in zip(runs[True], runs[False])]
    print(f"face-milled TCA warm, median of {n} processes each: AOT {statistics.median(runs[True]):.3f} ms, JIT "
          f"{statistics.median(runs[False]):.3f} ms; JIT / AOT per pair: "
          + ", ".join(f"{r:.3f}" for r in ratios), file=sys.stderr)


def build_cost():
    """``--build``: build the extension again into a temporary directory, in a fresh interpreter (install cost)."""
    code = ("import sys, time; from spiralbevel._core import aot_build; cc = aot_build.make_cc(sys.argv[1]); "
            "cc.compile()")
    with tempfile.TemporaryDirectory() as d:
        r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
        subprocess.run([sys.executable, "-c", code, d], check=True, env={**os.environ, "SPIRALBEVEL_AOT": "0"})
        r1, t1 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
        (so,) = Path(d).glob("_aot*")
        from spiralbevel._core import aot_table

        n = sum(len(v) for v in aot_table.SIGNATURES.values())
        print(f"extension build (install time): {n} exported kernels, CPU "
              f"{(r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime):.1f} s, wall {t1 - t0:.1f} s, "
              f"{so.stat().st_size / 1e6:.2f} MB ({so.name}), load {os.getloadavg()[0]:.1f}", file=sys.stderr)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--top", type=int, default=30, help="functions listed (by own compile time)")
    ap.add_argument("--signatures", action="store_true", help="print the signatures of functions compiled twice")
    ap.add_argument("--example", default="aviation_23x65_cmc")
    ap.add_argument("--ir", action="store_true", help="count the LLVM IR instructions optimised (see above)")
    ap.add_argument("--aot", type=int, default=0, metavar="N", help="AOT against JIT cold, N pairs (see above)")
    ap.add_argument("--build", action="store_true", help="time the extension's build (see above)")
    ap.add_argument("--warm", type=int, default=0, metavar="N", help="face-milled TCA, AOT against JIT (see above)")
    ap.add_argument("--child", help=argparse.SUPPRESS)
    ap.add_argument("--tca-child", action="store_true", help=argparse.SUPPRESS)
    a = ap.parse_args()
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    if a.child:
        return _child(a.example, a.child)
    if a.tca_child:
        return _tca_child()
    if a.build or a.aot or a.warm:
        if a.build:
            build_cost()
        if a.aot:
            compare_aot(a.example, a.aot)
        if a.warm:
            compare_warm(a.warm)
        return
    compiles, llvm, compile_all = _Compiles(), _Timer(), _Timer()
    event.register("numba:compile", compiles)
    event.register("numba:compile", compile_all)
    event.register("numba:llvm_lock", llvm)
    ir = _LinkedIR() if a.ir else None
    from spiralbevel.cli import app

    load = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as d:
        t0, w0 = time.process_time(), time.perf_counter()
        app(["run", a.example, "-o", os.path.join(d, "out"), "--cache-dir", os.path.join(d, "cache")],
            standalone_mode=False)
        cpu, wall = time.process_time() - t0, time.perf_counter() - w0
    print(f"machine load {load:.1f} at start, {os.getloadavg()[0]:.1f} at the end", file=sys.stderr)
    print(f"{a.example}, cold (empty cache), in-process: CPU {cpu:.1f} s, wall {wall:.1f} s; numba compiles "
          f"{compile_all.t:.1f} s CPU, of which LLVM {llvm.t:.1f} s; {sum(len(v) for v in compiles.sigs.values())} "
          f"compiles of {len(compiles.sigs)} functions", file=sys.stderr)
    if ir is not None:
        print(f"LLVM IR optimised: {ir.total} instructions in {ir.modules} modules, {sum(ir.size.values())} in "
              f"distinct functions", file=sys.stderr)
    print(f"{'own s':>7} {'with callees s':>14} {'n':>3}  function", file=sys.stderr)
    for name, own in sorted(compiles.own.items(), key=lambda kv: -kv[1])[:a.top]:
        n = len(compiles.sigs[name])
        print(f"{own:7.2f} {compiles.total[name]:14.2f} {n:3d}  {name}", file=sys.stderr)
        if a.signatures and n > 1 and name.split(".")[0] not in ("arrayobj", "builtins", "unicode", "linalg"):
            for s in compiles.sigs[name]:
                print(f"{'':28s}{s}", file=sys.stderr)


if __name__ == "__main__":
    main()
