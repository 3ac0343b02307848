"""spiralbevel: design, manufacture and contact analysis of spiral bevel gears.

The public API is the curated ``__all__`` below (names are imported on first use); ``spiralbevel._core`` is private.
Units inside: mm and rad; conventions in docs/conventions.md.
"""

from importlib import import_module

# re-exported: __all__ below is built with sorted(), which the linter cannot read
from spiralbevel.conventions import Hand, Member, Side  # noqa: F401
from spiralbevel.errors import (ConvergenceError, DesignError, GeometryError, MissingDependencyError,  # noqa: F401
                                NoContactError, SpiralBevelError)

__version__ = "0.1.0"

_LAZY = {
    # log-spiral bevel gears (seeds 000, 002)
    "LogSpiralFlank": "geometry.logspiral", "FlankGeometry": "geometry.logspiral",
    "surface_geometry": "geometry.diffgeom",
    "design_logspiral_pair": "design.logspiral_pair", "BlankBoundaries": "design.logspiral_pair",
    # ISO 23509 blank
    "BlankInput": "design.blank", "BevelBlank": "design.blank", "compute_blank": "design.blank",
    # face milling (seeds 001, 003)
    "HeadCutter": "machine.cutter", "Blade": "machine.cutter", "MachineSettings": "machine.settings",
    "UniversalSettings": "machine.universal", "UniversalGenerator": "machine.universal",
    "generate_flank": "generation.flank", "ToothFlank": "generation.flank",
    # meshing
    "BevelPairKinematics": "meshing.kinematics", "HypoidPairKinematics": "meshing.hypoid_kinematics",
    "solve_envelope": "meshing.envelope",
    "compare_conjugate": "meshing.conjugate", "solve_tca": "meshing.tca", "TCAResult": "meshing.tca_result",
    "Misalignment": "meshing.misalignment", "contact_ellipse": "meshing.ellipse",
    "CombinedMotionCurve": "meshing.motion_curves", "GeneratedSurface": "meshing.generated_surface",
    "synthesize_pinion": "meshing.synthesis", "easeoff": "meshing.easeoff",
    # manufacturing
    "draft_map": "manufacturing.draft", "plan_toolpath": "manufacturing.toolpath",
    "measurement_grid": "manufacturing.measurement", "correct_settings": "manufacturing.correction",
    # load capacity (ISO 10300)
    "rate_iso10300": "rating", "RatingInput": "rating", "RatingResult": "rating",
    # files and the main job
    "load_design": "io.design_file", "run_design": "job",
    # the user-facing gear set (design -> pair assembled once -> result objects)
    "GearSet": "gearset",
}

__all__ = sorted(["Hand", "Member", "Side", "SpiralBevelError", "DesignError", "GeometryError", "ConvergenceError",
                  "NoContactError", "MissingDependencyError", "__version__", *_LAZY])


def __getattr__(name):
    if name in _LAZY:
        value = getattr(import_module(f"spiralbevel.{_LAZY[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'spiralbevel' has no attribute {name!r}")


def __dir__():
    return __all__
