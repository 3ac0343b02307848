"""Timing used by every ``bench/`` script: the package and its baseline are timed the same way, as the median of
``repeat`` wall-clock runs (``time.perf_counter``) of the whole call, output included."""

from __future__ import annotations

import statistics
import time


def median_time(fun, repeat: int, cpu: bool = False):
    """(median seconds over ``repeat`` runs, the last run's output). ``cpu``: CPU time of this process
    (``time.process_time``) instead of the wall clock, for single-threaded work on a shared machine."""
    clock = time.process_time if cpu else time.perf_counter
    times, out = [], None
    for _ in range(max(1, int(repeat))):
        t0 = clock()
        out = fun()
        times.append(clock() - t0)
    return statistics.median(times), out


def fmt(seconds: float) -> str:
    """Seconds as ms below 1 s, else s."""
    return f"{seconds * 1e3:9.3f} ms" if seconds < 1.0 else f"{seconds:9.3f} s "


def report(label: str, t_pkg: float, t_base: float, baseline: str, repeat: int) -> None:
    """One line: package time, baseline time, ratio baseline / package."""
    print(f"{label}: spiralbevel {fmt(t_pkg)} | {baseline} {fmt(t_base)} | ratio {t_base / t_pkg:6.2f}x "
          f"(median of {repeat} runs each)")
