"""Partial results: a failing secondary analysis becomes a report entry with its reason, not a lost run.

The main job calls each secondary analysis (conjugacy check, TCA of one side, loaded TCA, one case of the
misalignment sensitivity) through :func:`attempt`. A solver failure (:class:`~spiralbevel.errors.ConvergenceError`,
:class:`~spiralbevel.errors.NoContactError`, a singular linear system) is recorded as
``{"status": "failed", "analysis": ..., "reason": ...}``, announced as a
:class:`~spiralbevel.errors.PartialResultWarning`, and counted in :class:`PartialLog`; the CLI then exits with the
"completed with warnings" code (3). Bad input (:class:`~spiralbevel.errors.DesignError`) and missing extras are not
partial results: they still stop the run.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np

from ..errors import ConvergenceError, NoContactError, PartialResultWarning

#: failures of a secondary analysis that leave the rest of the run valid
ANALYSIS_FAILURES = (ConvergenceError, NoContactError, np.linalg.LinAlgError)


@dataclass
class PartialLog:
    """The analyses of a run that failed: ``failed`` is a list of (analysis, reason)."""

    failed: list = field(default_factory=list)

    def record(self, analysis: str, reason: str) -> dict:
        """Count a failure, warn, and return its report entry."""
        self.failed.append((analysis, reason))
        warnings.warn(f"{analysis} failed ({reason}); the rest of the report was written", PartialResultWarning,
                      stacklevel=3)
        return failed_entry(analysis, reason)


def failed_entry(analysis: str, reason: str) -> dict:
    """The report entry of a failed analysis."""
    return {"status": "failed", "analysis": analysis, "reason": reason}


def attempt(log: PartialLog, analysis: str, fn, *args, **kwargs):
    """``(fn(*args, **kwargs), None)``, or ``(None, failed entry)`` after a solver failure (recorded in ``log``)."""
    try:
        return fn(*args, **kwargs), None
    except ANALYSIS_FAILURES as err:
        return None, log.record(analysis, str(err) or type(err).__name__)


def mark_failed(log: PartialLog, section: dict, analysis: str) -> None:
    """A report section that holds an ``"error"`` (a side or case without contact): mark it failed and warn."""
    if isinstance(section, dict) and "error" in section and section.get("status") != "failed":
        section.update(log.record(analysis, section["error"]))
