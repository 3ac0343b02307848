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
  contact's entry points and their callees), the TCA step below the four edge-contact kernels (``tca_edge``,
  ``tca_edge_screen``) and ``linalg.lu_solve`` below multi-point control's entry points; one entry point per family
  would cut those too. It cannot bring the cold run to 15 s: with no duplicate at all LLVM would optimise the 45,521
  distinct instructions, 40 % of today's (about 7 s less), while numba's front end alone (about 17 s CPU at load
  8-10) and the job's work besides compiling (about 12 s there, 10 s idle: FE compliance and the job itself) each
  come near the target or exceed it. numba caches machine code only, not typed IR, so there is no cheaper middle
  state to keep. The ways around are not JIT: compiling ahead of time (``numba.pycc``, pending deprecation since
  numba 0.57; one extension module per platform built at install, generic code for the CPU family) or shipping a
  filled cache (keyed by the CPU and the source files' time stamps); neither is done. A second
  process compiling the kernels into the same cache while the job runs was measured and not kept: on this 2-core
  machine it made the cold run slower in wall time at every load measured (43 -> 58 s at load 1.1).
* Give each kernel one argument signature: a read-only broadcast view and a writable array are two numba types, and
  compile the kernel twice (the envelope's guess is copied for that reason).
"""

from __future__ import annotations

import contextlib
import hashlib
import logging
import os
import tempfile
from pathlib import Path

import numba

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
    key = sources_key(Path(__file__).parent.glob("*.py"))
    return Path(base) / "numba" / f"{numba.__version__}-{key}"


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

    Use as ``@kernel`` or ``@kernel(inline="always")``; ``options`` are passed to ``numba.njit``.
    """
    if fun is None:
        return lambda f: kernel(f, **options)
    global _CACHE
    opts = {**_OPTIONS, **options}
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
