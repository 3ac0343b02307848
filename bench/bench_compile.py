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

There is no alternative to compare against: the figures locate the compile cost (``_core/jit.py`` lists the rules it
led to). One run (a cold run is not repeatable in one process); CPU time is ``time.process_time``, the machine load is
printed. Run: ``python bench/bench_compile.py [--top N] [--signatures] [--ir]``.
"""

from __future__ import annotations

import argparse
import collections
import os
import sys
import tempfile
import time

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


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--top", type=int, default=30, help="functions listed (by own compile time)")
    ap.add_argument("--signatures", action="store_true", help="print the signatures of functions compiled twice")
    ap.add_argument("--example", default="aviation_23x65_cmc")
    ap.add_argument("--ir", action="store_true", help="count the LLVM IR instructions optimised (see above)")
    a = ap.parse_args()
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
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
