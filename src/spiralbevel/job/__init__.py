"""The main job: a design file in, a report directory out (``spiralbevel run``), and the drivers of ``check``,
``correct`` and ``sweep``.

A thin layer over :class:`spiralbevel.gearset.GearSet`: :func:`run_design` builds the gear set of a design and asks it
for its report directory; the CLI prints the summary. It computes nothing itself.
"""

import importlib
import importlib.abc
import importlib.util
import sys as _sys

from ..gearset.run import RunSummary
from .driver import run_design

# the design-file translation, the analyses and the report writer moved to spiralbevel.gearset (issue 12); the old
# module paths (spiralbevel.job.facemilled, ...) stay importable as aliases of the same module objects, imported on
# first use: a run imports only the analyses its design asks for (the log-spiral default run none of the face-milled
# ones)
_MOVED = frozenset({"blank", "conjugacy", "facemilled", "hypoid", "inspection", "logspiral", "logspiral_production",
                    "logspiral_tca", "ltca", "outputs", "partial", "problems", "progress", "rating", "run",
                    "run_facemilled", "run_logspiral", "tca"})


class _MovedModules(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds ``spiralbevel.job.<name>`` for a moved module: the module ``spiralbevel.gearset.<name>`` itself."""

    def find_spec(self, fullname, path=None, target=None):
        parent, _, name = fullname.rpartition(".")
        if parent != __name__ or name not in _MOVED:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec):
        module = importlib.import_module(f"spiralbevel.gearset.{spec.name.rpartition('.')[2]}")
        spec.loader_state = module.__spec__
        return module

    def exec_module(self, module):
        # the import system has set the alias' spec on the module object in between: give it back its own
        alias = module.__spec__
        module.__spec__ = alias.loader_state


def __getattr__(name):
    if name in _MOVED:  # ``from spiralbevel.job import facemilled``, ``spiralbevel.job.facemilled``
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


if not any(isinstance(f, _MovedModules) for f in _sys.meta_path):
    _sys.meta_path.append(_MovedModules())

__all__ = ["RunSummary", "run_design"]
