"""The user-facing gear set: a design becomes a pair assembled once; each analysis returns a result object.

Layer above the computational packages (design, machine, generation, meshing, rating, manufacturing, io, viz) and
below the main job and the CLI, which are thin drivers over it. The modules here also hold the translation of a
design file into the library's objects (blank, cutters, settings, flanks) and the report.json sections, so that the
job and the API give the same numbers from the same functions.
"""

from .gearset import GearSet
from .results import (EaseOff, LTCA, MachineSummary, MeasurementGrids, Rating, Sensitivity, TCA)

__all__ = ["GearSet", "TCA", "LTCA", "EaseOff", "Sensitivity", "MachineSummary", "MeasurementGrids", "Rating"]
