"""The main job: a design file in, a report directory out (``spiralbevel run``).

Layer above every computational package; the CLI calls :func:`run_design` and prints its summary.
"""

from .run import RunSummary, run_design

__all__ = ["RunSummary", "run_design"]
