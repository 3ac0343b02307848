"""Face-milled designs: cutters and machine settings per flank, generated flanks, tooth assembly.

The names live in small modules and are re-exported here, where callers and tests have always found them:

- :mod:`.flank_setup`: ``FlankSetup``, ``setup_flanks`` and the cutters and settings given or derived per flank;
- :mod:`.default_synthesis`: the developed pair by default (``DEFAULT_SYNTHESIS``, the TE fallback,
  ``effective_synthesis``, ``synthesize_sides``);
- :mod:`.default_candidates`: its candidate search of one pinion side (``DEFAULT_CANDIDATES`` and the other search
  bounds, ``_candidates``) and the TCA count that judges a candidate (``bearing_off_flank``);
- :mod:`.tooth_assembly`: ``tooth_rotation``, ``rotate_grid``;
- :mod:`.flank_checks`: ``CHECK_ANGLE_DEG``, ``CHECK_ROOT_MM``, ``flank_checks``;
- :mod:`.flank_report`: ``flank_report``, ``cmc_paper_model``.

Setting a name here (``monkeypatch.setattr(facemilled, "bearing_off_flank", fake)``, and its undo) sets it in each of
those modules that holds the same object, so that the patch reaches the code that calls it, as when all lived in one
file.
"""

from __future__ import annotations

import sys
import types

from .default_candidates import (_ALL_DIRECTIONS, _CHECK_POSITIONS, _FREE, DEFAULT_CANDIDATES,  # noqa: F401
                                 DEFAULT_DEPTH_ANGLE_MARGIN, DEFAULT_DEPTH_FRACTIONS, DEFAULT_LENGTHWISE_DIRECTIONS,
                                 DEFAULT_MAX_BLADE_CHANGE_DEG, DEFAULT_MAX_SYNTHESES, DEFAULT_OTHER_SET_SYNTHESES,
                                 DEFAULT_PATH_DIRECTIONS, SLOT_CLOSED_RANK, _angle_deviation, _angles_hit, _candidates,
                                 _require_near_branch, bearing_off_flank)
from .default_synthesis import (DEFAULT_FALLBACK_SYNTHESES, DEFAULT_SYNTHESIS, DEFAULT_TE_FALLBACK,  # noqa: F401
                                PAIR_SIDES, SYNTHESIS_PATHS, _default_spec_class, _derived_edge_radius, _slot_floors,
                                _synthesize_sides, effective_synthesis, synthesize_sides)
from .flank_checks import CHECK_ANGLE_DEG, CHECK_ROOT_MM, flank_checks  # noqa: F401
from .flank_report import cmc_paper_model, flank_report  # noqa: F401
from .flank_setup import (_CULPRIT_ANGLE_DEG, _CULPRIT_LENGTH, MEMBERS, SIDES, FlankSetup,  # noqa: F401
                          _basic_setups, _default_cutter, _given_cutter, _given_settings, _in_design_file,
                          _misplaced_cutter, setup_flanks)
from .tooth_assembly import _azimuth, rotate_grid, tooth_rotation  # noqa: F401

_PARTS = tuple(sys.modules[f"{__package__}.{name}"]
               for name in ("flank_setup", "default_candidates", "default_synthesis", "tooth_assembly", "flank_checks",
                            "flank_report"))
_MISSING = object()


class _Facade(types.ModuleType):
    """This module, whose re-exported names, when set, are set in the modules that hold them too."""

    def __setattr__(self, name, value):
        old = self.__dict__.get(name, _MISSING)
        if old is not _MISSING and not name.startswith("__"):
            for part in _PARTS:
                if part.__dict__.get(name, _MISSING) is old:
                    setattr(part, name, value)
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Facade
