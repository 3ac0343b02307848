"""Sub-progress of long computations, for a caller's progress bar: library code reports, a driver listens.

Library code calls :func:`report` at natural checkpoints (a factorization done, a block of solves done); it is a
no-op unless a driver installed a listener with :func:`listening` (a context variable, so threads and concurrent
jobs do not see each other's listener). Imports nothing from spiralbevel: any layer may use it.
"""

from __future__ import annotations

from contextlib import contextmanager
from contextvars import ContextVar
from typing import Callable, Iterator, Optional

Listener = Callable[[str, int, int], None]

_listener: ContextVar[Optional[Listener]] = ContextVar("spiralbevel_progress", default=None)


def report(stage: str, done: int, total: int) -> None:
    """Tell the listener, if any, that ``done`` of ``total`` units of ``stage`` are finished."""
    fn = _listener.get()
    if fn is not None:
        fn(stage, done, total)


@contextmanager
def listening(fn: Listener) -> Iterator[None]:
    """Install ``fn(stage, done, total)`` as the listener for the duration of the ``with`` block."""
    token = _listener.set(fn)
    try:
        yield
    finally:
        _listener.reset(token)
