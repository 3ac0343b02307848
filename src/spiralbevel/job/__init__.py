"""The main job: a design file in, a report directory out (``spiralbevel run``), and the drivers of ``check``,
``correct`` and ``sweep``.

A thin layer over :class:`spiralbevel.gearset.GearSet`: :func:`run_design` builds the gear set of a design and asks it
for its report directory; the CLI prints the summary. It computes nothing itself.
"""

import sys as _sys

from ..gearset import (blank, conjugacy, facemilled, hypoid, inspection, logspiral, logspiral_production,  # noqa: F401
                       logspiral_tca, ltca, outputs, partial, problems, progress, rating, run, run_facemilled,
                       run_logspiral, tca)
from ..gearset.run import RunSummary
from .driver import run_design

# the design-file translation, the analyses and the report writer moved to spiralbevel.gearset (issue 12); the old
# module paths (spiralbevel.job.facemilled, ...) stay importable as aliases of the same module objects
for _m in (blank, conjugacy, facemilled, hypoid, inspection, logspiral, logspiral_production, logspiral_tca, ltca,
           outputs, partial, problems, progress, rating, run, run_facemilled, run_logspiral, tca):
    _sys.modules.setdefault(f"{__name__}.{_m.__name__.rsplit('.', 1)[1]}", _m)

__all__ = ["RunSummary", "run_design"]
