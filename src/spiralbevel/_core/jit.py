"""The one compiler of the numerical core: numba's ``njit`` with an on-disk cache that falls back cleanly.

Compiled kernels are declared with :func:`kernel` instead of ``numba.njit``. Machine code is cached on disk in
``<cache>/numba/<numba version>-<key>`` (``<cache>`` is ``$SPIRALBEVEL_CACHE``, else ``~/.cache/spiralbevel``; the
LTCA FE cache lives beside it), where ``key`` hashes the source of every module of ``spiralbevel._core``. numba's own
cache (``cache=True`` alone, next to the source) is invalidated only by a change of the file that defines the
compiled function, not by a change of the kernels it calls from other files: after an update of ``_core/jets.py``,
the TCA Newton of ``_core/tca_newton.py`` would load machine code that still dispatches to the old jets (found as
NaN residuals, "no contact", after a merge). Keying the directory by all sources makes every change a fresh cache.
Where the directory cannot be written, the kernel is compiled in memory on first use instead of failing: the result
is the same, only the first call of each process pays the compile time.

Why numba: the contact kernels are loops over small independent systems (5 x 5 Newton
systems, surface jets at single points) where numpy spends most of its time in call overhead; numba compiles the
plain loops to machine code with the same IEEE arithmetic, ships wheels for every platform the project supports, and
is imported only by the modules that hold compiled kernels (not by the CLI's start-up path). Costs and
figures: README, "Performance".

Compile time. A first run after an install (or after any change of ``_core``) compiles every kernel it reaches
(later runs read the machine code from the cache above); for the CMC example that is most of its cold time.
``bench/bench_compile.py`` lists the compile time of every kernel and numba implementation a job pulls in, and the
signatures of anything compiled twice. What it showed (numba 0.68, CPU seconds on the project machine) gives the
rules for kernels:

* numba's Python front end (typing, rewrites, lowering to LLVM IR) is half or more of the cost, LLVM the rest,
  roughly in proportion to the number of statements typed: a big kernel costs about 1 s, a small helper 0.1-0.3 s;
  a kernel called from other kernels is typed once per signature, not once per caller.
* But LLVM works on it once per compiled function above it: every kernel's module links the IR of every kernel it
  reaches, and LLVM optimises and emits that module whole, so a kernel's IR is optimised again in each caller, in
  each caller's callers, up to the top-level kernels called from Python (``bench_compile.py --ir`` counts it). The
  face-milled jet ``blade_jet_u`` sat below three pass-through kernels (``blade_jet_du``, ``blade_jet_point``,
  ``surface_jet``) and was optimised in 27 of the 121 modules of the CMC example's cold run. Each level of kernels
  between a heavy callee and the top costs a full LLVM pass over the callee: a thin wrapper, or a helper with one call
  site, is ``inline="always"`` (no module of its own); write a Newton loop as ``while True`` with one call of the
  residual (not one before the loop and one at its end), so that the residual has one call site and can be inlined.
* ``inline="always"`` re-types (and deep-copies, and re-reads the bytecode of) the callee at every call site: for thin
  wrappers, small helpers and functions with one call site only. A heavy function called from several places stays a
  kernel of its own: the face-milled jet ``blade_jet_u`` inlined into three kernels (and ``_meshing`` twice into it)
  cost 3-4 s more than compiling it once and calling it; LLVM still inlines small callees at machine level.
* One signature per kernel. Each distinct argument type compiles the whole call tree again: a literal argument
  (``f(x, True)`` from kernel code types as ``Literal[bool](True)``, ``-1`` as ``Literal[int](-1)``), a read-only
  array (``np.broadcast_to`` views, ``setflags(write=False)``) against a writable one, layout ``A`` (a non-contiguous
  slice) against ``C``, int against float, a different dtype spelling of ``np.empty`` (``float``, ``np.float64``,
  none). Pass flags and indices as values read from an array or computed, hand kernels writable C-contiguous float64
  arrays (``np.array(..., float)`` copies when in doubt).
* numpy conveniences inside kernels pull in numba's generic implementations, each compiled once per process and
  signature, several with error-message formatting: an array-to-array set-item (``a[i] = b``, ``a[:, :] = B``: the
  broadcast check with its message, about 1.5 s per dimension count), ``a[:] = v``, ``np.max(np.abs(f))``,
  ``np.all(np.isfinite(J))`` and above all ``np.linalg`` (``lstsq``: about 2 s). A ``for`` loop over the few
  entries of a kernel's small arrays costs nothing to compile; a rarely taken LAPACK branch can call back into
  Python (``numba.objmode``, see ``settings_fit._lstsq``).
* No kernel has a cfunc wrapper (``no_cfunc_wrapper``: numba's C-callable entry point for passing a compiled
  function as a first-class value, which no kernel does; a wrapper is LLVM IR of its own in every module, 8 % of the
  IR of the CMC example's cold run). CPython wrappers stay on every kernel: a kernel compiled without one and then
  called from Python jumps to a null entry point (leaving them out of callee-only kernels saved about 3 %). LLVM
  optimisation level 1 instead of numba's 3 (process-wide ``NUMBA_OPT=1``: about 15 % less compile time; for our
  kernels' compiles only, through a pipeline class that sets ``numba.config.OPT`` around them: about 10 % less LLVM
  time, 5 % less compile time) made the face-milled TCA about 10 % slower (three paired runs of
  ``bench/bench_tca.py``); level 0 halves LLVM time and makes TCA and generation 4-5x slower: left at numba's default.
* One entry point per family of kernels. Every compiled function is a compile of its own (about 50 ms of CPU for a
  trivial one: numba's pipeline, wrappers, cache files; at load 9) and an LLVM module that links its callees. The
  TCA Newton had nine kernels called from Python (the jets' whole Newton; start, propose, accept, assembly and basis
  of the numpy-evaluated iteration; step, path tangent and line-contact test of a batch), each linking the step with
  its LU and SVD. They are one kernel, ``tca_newton.newton_batch``, whose operation is a value read from its integer
  array (one signature), and the helpers that then have one call site are inlined: the CMC example's cold run
  compiles 82 functions instead of 102, and LLVM optimises 114,408 IR instructions in 87 modules instead of 133,521
  in 107 (``bench_compile.py --ir``); about 4-5 s less compile CPU (alternated at load 8-10). The price: a call from
  Python types 32 arguments, about 3 us more per call than the separate kernels.
* Where the cold time goes (the CMC example, empty cache, one process): numba's type inference and lowering are about
  60 % of the compile, LLVM the rest, half optimising and half emitting code. LLVM still optimises more than once the
  face-milled jet ``blade_jet_u`` (in 22 modules: the settings fit's, multi-point control's, blade locator's and edge
  contact's entry points and their callees), the TCA step below the edge-contact kernels (``tca_edge``,
  ``tca_edge_stage``) and ``linalg.lu_solve`` below multi-point control's entry points; one entry point per family
  would cut those too. The JIT cannot bring the cold run to 15 s: with no duplicate LLVM would optimise the 45,521
  distinct instructions, 40 % of today's (about 7 s less), while numba's front end alone (about 17 s CPU at load
  8-10) and the job's work besides compiling (about 12 s there, 10 s idle: FE compliance and the job itself) each
  come near the target or exceed it. numba caches machine code only, not typed IR, so there is no cheaper middle
  state to keep. The ways around are not JIT: compiling ahead of time (``numba.pycc``, below) or shipping a
  filled cache (keyed by the CPU and the source files' time stamps, so it misses on another machine). A second
  process compiling the kernels into the same cache while the job runs was measured and not kept: on this 2-core
  machine it made the cold run slower in wall time at every load measured (43 -> 58 s at load 1.1).
* Give each kernel one argument signature: a read-only broadcast view and a writable array are two numba types, and
  compile the kernel twice (the envelope's guess is copied for that reason).

Ahead of time, at install. ``pip install`` (``setup.py``) builds the extension module ``spiralbevel._core._aot`` with
``numba.pycc`` (``_core/aot_build.py``): for every kernel Python calls and every argument signature of the generated
table ``_core/aot_table.py`` it exports a thin wrapper ``w(a0, ...) = kernel(a0, ...)``. pycc compiles the wrapper;
the kernel below it is compiled by its own dispatcher with the options above (``error_model="numpy"``, no fastmath:
pycc's own default error model is Python's) and its LLVM IR is linked into the extension, so the extension runs the
same code as the JIT: the CMC example's outputs are identical byte for byte, the kernels bit for bit on random inputs
(``tests/_core/test_aot.py``). At run time nothing else changes: ``kernel`` still returns a numba dispatcher (kernels
call kernels, and typing needs one), and puts each exported wrapper into that dispatcher's own overload table
(``_attach_aot``) under the argument types of its signature. numba's dispatcher (C code) picks the overload of a
Python call by the arguments' type codes and calls its CPython entry point; pycc's wrappers are CPython functions
with the same calling convention that unbox the same types, so the same call sites run the extension's machine code,
with no Python-level indirection (a call with other argument types falls through to the JIT as before). The first
run after an install then compiles nothing (the CMC example cold: 0 compiles instead of 83; figures in
docs/performance.md, "Cold start", from ``bench/bench_compile.py --aot/--warm/--build``).

* Which extension counts: its ``aot_key()`` (the numba version and ``sources_key`` of the ``_core`` sources it was
  built from) must equal the running one; after a developer edits any ``_core`` file, or under another numba, it is
  ignored (one logged notice) and the kernels are JIT-compiled and cached as before, until the next ``pip install
  -e .``. ``SPIRALBEVEL_AOT=0`` ignores it too (for developers and for the benchmarks' comparison); at install it
  skips the build.
* It is optional: without a C compiler, or if numba cannot build it, the install goes on without it (one notice)
  and the kernels are JIT-compiled on first use. ``cc.target_cpu = "host"``: the extension is built on the machine
  that installs the package, for that CPU, as the JIT would compile (a wheel built elsewhere would need a generic
  CPU name instead).
* The table: the signatures with which the package calls kernels from Python (30 signatures of 27 kernels: three
  kernels, ``envelope_kernel._envelope_loop``, ``grid_locate.iterate_feet`` and ``blade_locate.locate_R_u``, are
  also called with a read-only array by some path, a second signature each, which the JIT compiles again too).
  ``python -m spiralbevel._core.aot_record`` records them (``jit._Kernel._compile_for_args``, the one place numba's
  dispatcher calls back into Python for a call it has no machine code for) from the bundled examples and the test
  suite. The test suite runs with ``SPIRALBEVEL_AOT_STRICT=1``: a call from the package with argument types missing
  from the table fails the test that made it (the drift check: a new kernel or a changed argument needs the table
  regenerated).
* A pycc bug, patched at the build: the extension's module initialisation (numba's ``pycc/modulemixin.c``, 0.68.1)
  frees the environment object of every compiled callee right after storing it, and a callee that reads its
  environment then reads freed memory: a ``numba.objmode`` block (a call back into Python) boxing an array does
  ("TypeError: expected dtype object, got 'str'", or a crash; ``settings_fit._lstsq``, the settings fit's rare
  singular step, below ``settings_fit.newton``). ``aot_build`` compiles a copy of that file that keeps the reference
  (``_MIXIN_FIX``); where the numba at hand has other code there, nothing is patched and the kernels that reach an
  object-mode block (``aot_build.JIT_ONLY``) are left to the JIT.
* Limits: ``numba.pycc`` is in pending deprecation since numba 0.57; if a numba release drops it, the build fails, the
  install goes on without the extension and the kernels are JIT-compiled as before. The extension's entry points do
  not release the GIL (``nogil`` applies to the JIT's entry points only): the package runs its kernels in one thread
  per process (the local dask sweep uses processes; on a dask cluster whose workers run several threads, their kernel
  calls would take turns). The extension holds its own copy of numba's runtime (NRT); arrays move between it and the
  JIT as numpy arrays.
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib
import logging
import os
import sys
import tempfile
from pathlib import Path

import numba
from numba.core.registry import CPUDispatcher

__all__ = ["kernel"]

_log = logging.getLogger(__name__)

#: options of every compiled kernel: no Python objects, IEEE semantics (no fastmath: roots must match the reference
#: arithmetic), errors as NaN instead of exceptions inside the loops; no cfunc wrapper (the C-callable entry point
#: numba builds for passing a compiled function as a first-class value, which no kernel does: see ``_core/jets.py``)
_OPTIONS = dict(fastmath=False, error_model="numpy", nogil=True, no_cfunc_wrapper=True)


def sources_key(paths) -> str:
    """Hex digest (16 characters) of the contents of ``paths`` (sorted by name): the compiled kernels' cache key."""
    h = hashlib.sha256()
    for p in sorted(Path(q) for q in paths):
        h.update(p.name.encode())
        h.update(p.read_bytes())
    return h.hexdigest()[:16]


def cache_dir() -> Path:
    """Directory of the compiled kernels' machine code (see the module docstring)."""
    base = os.environ.get("SPIRALBEVEL_CACHE") or os.path.join(os.path.expanduser("~"), ".cache", "spiralbevel")
    return Path(base) / "numba" / f"{numba.__version__}-{_sources_key()}"


def _writable(d: Path) -> bool:
    try:
        d.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=d):
            pass
        return True
    except OSError:
        return False


_CACHE: Path | None = None


@contextlib.contextmanager
def _numba_cache_dir(d: Path):
    """numba reads its cache directory when a function is decorated; set it for our kernels only, then restore."""
    config = numba.config
    old = config.CACHE_DIR  # type: ignore[attr-defined]  # set from the environment at numba's import
    config.CACHE_DIR = str(d)  # type: ignore[attr-defined]
    try:
        yield
    finally:
        config.CACHE_DIR = old  # type: ignore[attr-defined]


def kernel(fun=None, **options):
    """Compile ``fun`` with numba (``cache=True`` where a cache directory is writable, else in memory).

    Use as ``@kernel`` or ``@kernel(inline="always")``; ``options`` are passed to ``numba.njit``. Where the
    ahead-of-time extension is installed and current, the calls from Python with a signature of its table run its
    machine code (``_attach_aot``).
    """
    if fun is None:
        return lambda f: kernel(f, **options)
    dispatcher = _jit(fun, {**_OPTIONS, **options})
    dispatcher.__class__ = _Kernel
    _attach_aot(dispatcher)
    return dispatcher


def _jit(fun, opts):
    global _CACHE
    if _BUILDING:  # the extension's build links the kernels' LLVM IR: compile in memory, read no cache
        return numba.njit(cache=False, **opts)(fun)
    if _CACHE is None:
        _CACHE = cache_dir()
    if _writable(_CACHE):
        try:
            with _numba_cache_dir(_CACHE):
                return numba.njit(cache=True, **opts)(fun)
        except RuntimeError as err:  # numba: "cannot cache function ...: no locator available"
            _log.info("numba cache not usable for %s (%s); compiling in memory", fun.__qualname__, err)
    else:
        _log.info("numba cache directory %s not writable; compiling %s in memory", _CACHE, fun.__qualname__)
    return numba.njit(cache=False, **opts)(fun)


# --- the ahead-of-time extension (see the module docstring) ---

#: set by ``aot_build`` while it builds the extension
_BUILDING = False
_AOT: object = None  # the extension module once looked up, False where there is none (or it is stale or disabled)


def qualified_name(fun) -> str:
    """``module.function`` of a kernel, ``module`` relative to ``spiralbevel._core``: the key of ``aot_table``."""
    return f"{fun.__module__.rsplit('.', 1)[-1]}.{fun.__qualname__}"


def aot_module():
    """The extension ``spiralbevel._core._aot`` if it is installed, built from the current sources and numba and not
    disabled (``SPIRALBEVEL_AOT=0``), else ``False`` (the kernels are compiled by the JIT); looked up once."""
    global _AOT
    if _AOT is None:
        _AOT = False
        if os.environ.get("SPIRALBEVEL_AOT", "1") == "0" or _BUILDING:
            return _AOT
        try:
            _aot = importlib.import_module(f"{__package__}._aot")  # built at install (setup.py)
        except ImportError as err:
            _log.info("the compiled kernels' extension is not built (%s): compiling them on first use (JIT)", err)
            return _AOT
        key = f"{numba.__version__}-{_sources_key()}"
        if _aot.aot_key() != key:
            _log.info("the compiled kernels' extension was built from other sources (%s, now %s): compiling them on "
                      "first use (JIT)", _aot.aot_key(), key)
            return _AOT
        _AOT = _aot
    return _AOT


def _attach_aot(dispatcher) -> None:
    """Put the extension's functions of ``dispatcher``'s signatures into numba's overload table of ``dispatcher``.

    numba's dispatcher (C code) finds the overload of a Python call by the argument types' codes and calls its
    CPython entry point; the extension's exported wrappers are CPython functions of the same calling convention
    (``METH_VARARGS | METH_KEYWORDS``) that unbox the same types. Calls from other kernels are typed by the
    dispatcher as before (they link the kernel's IR and never reach this table).
    """
    from . import aot_table

    sigs = aot_table.SIGNATURES.get(qualified_name(dispatcher.py_func))
    if not sigs or not aot_module():
        return
    from .aot_build import export_name

    attached = []
    for i, (text, _) in enumerate(sigs):
        entry = getattr(_AOT, export_name(qualified_name(dispatcher.py_func), i), None)
        if entry is None:  # left to the JIT (aot_build.JIT_ONLY)
            continue
        argtypes = aot_table.parse(text)
        dispatcher._insert([t._code for t in argtypes], entry, False)
        attached.append(argtypes)
    dispatcher._aot_signatures = tuple(attached)


_KEY: str | None = None


def _sources_key() -> str:
    global _KEY
    if _KEY is None:
        _KEY = sources_key(Path(__file__).parent.glob("*.py"))
    return _KEY


class _Kernel(CPUDispatcher):
    """numba's dispatcher, knowing the signatures the extension answers (``signatures``) and checking, under the test
    suite (``SPIRALBEVEL_AOT_STRICT``), that every call from the package has a signature of the table."""

    _aot_signatures: tuple = ()

    @property
    def signatures(self):
        """Argument signatures: those compiled in this process and those the extension answers."""
        return list(self.overloads) + [s for s in self._aot_signatures if s not in self.overloads]

    def add_overload(self, cres):
        if os.environ.get("SPIRALBEVEL_AOT_RECORD"):
            # recording: machine code compiled for a caller kernel is not put into numba's table of Python calls, so
            # that a Python call with the same types still comes to _compile_for_args (and is recorded)
            self.overloads[tuple(cres.signature.args)] = cres
            return
        super().add_overload(cres)

    def _compile_for_args(self, *args, **kws):
        # reached from numba's C dispatcher only when no overload matches a Python call's argument types
        check = os.environ.get("SPIRALBEVEL_AOT_STRICT") == "1"
        record = os.environ.get("SPIRALBEVEL_AOT_RECORD")
        if not (check or record) or not _called_from_package():
            return super()._compile_for_args(*args, **kws)
        from . import aot_table

        name = qualified_name(self.py_func)
        argtypes = tuple(self.typeof_pyval(a) for a in args)
        if check and not record and repr(argtypes) not in [a for a, _ in aot_table.SIGNATURES.get(name, ())]:
            raise AssertionError(
                f"kernel {name} called from the package with argument types {argtypes!r}, which are not in "
                f"_core/aot_table.py: the ahead-of-time extension would not answer this call (the JIT would compile "
                f"it, tens of seconds on a first run); regenerate the table (python -m spiralbevel._core.aot_record)")
        result = super()._compile_for_args(*args, **kws)
        if record and (name, argtypes) not in _RECORDED:
            _RECORDED.add((name, argtypes))
            with open(record, "a") as f:
                f.write(f"{name}\t{argtypes!r}\t{self.overloads[argtypes].signature.return_type!r}\n")
        return result


_RECORDED: set = set()


def _called_from_package() -> bool:
    """Whether the Python caller of the kernel (three frames up: this function, ``_compile_for_args``; numba's C
    dispatcher adds none) is code of ``spiralbevel`` (the tests' own direct calls of kernels are not)."""
    name = sys._getframe(2).f_globals.get("__name__", "")
    return name == "spiralbevel" or name.startswith("spiralbevel.")
