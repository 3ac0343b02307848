"""The one compiler of the numerical core: numba's ``njit`` with an on-disk cache that falls back cleanly.

Compiled kernels are declared with :func:`kernel` instead of ``numba.njit``. Machine code is cached next to the
source (``__pycache__``) or, where that is read-only (a system-wide install), in numba's user-wide cache directory
(``NUMBA_CACHE_DIR`` when set). Where no cache location is writable at all, the kernel is compiled in memory on first
use instead of failing: the result is the same, only the first call of each process pays the compile time.

Why numba: the contact kernels are loops over small independent systems (5 x 5 Newton
systems, surface jets at single points) where numpy spends most of its time in call overhead; numba compiles the
plain loops to machine code with the same IEEE arithmetic, ships wheels for every platform the project supports, and
is imported only by the modules that hold compiled kernels (not by the CLI's start-up path). Costs and
figures: README, "Performance".
"""

from __future__ import annotations

import logging

import numba

__all__ = ["kernel"]

_log = logging.getLogger(__name__)

#: options of every compiled kernel: no Python objects, IEEE semantics (no fastmath: roots must match the reference
#: arithmetic), errors as NaN instead of exceptions inside the loops
_OPTIONS = dict(fastmath=False, error_model="numpy", nogil=True)


def kernel(fun=None, **options):
    """Compile ``fun`` with numba (``cache=True`` where a cache directory is writable, else in memory).

    Use as ``@kernel`` or ``@kernel(inline="always")``; ``options`` are passed to ``numba.njit``.
    """
    if fun is None:
        return lambda f: kernel(f, **options)
    opts = {**_OPTIONS, **options}
    try:
        return numba.njit(cache=True, **opts)(fun)
    except RuntimeError as err:  # numba: "cannot cache function ...: no locator available"
        _log.info("numba cache not writable for %s (%s); compiling in memory", fun.__qualname__, err)
        return numba.njit(cache=False, **opts)(fun)
