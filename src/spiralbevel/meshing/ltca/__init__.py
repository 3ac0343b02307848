"""Loaded tooth contact analysis (seed 001 §4.3.2, Eq. (18); docs/theory/ltca.md, Eqs. (L1)-(L4)).

Building blocks: exact load-distribution solver (:mod:`.lcp`), half-space contact flattening (:mod:`.halfspace`),
FE tooth compliance (:mod:`.mesher`, :mod:`.compliance`; extra ``fem``), separations (:mod:`.separation`) and the
driver (:mod:`.ltca`) returning :class:`LTCAResult`; :mod:`.from_tca` connects an unloaded TCA (``loaded_tca``).
"""

from .compliance import ToothCompliance, default_cache_dir, tooth_compliance
from .from_tca import (FE_DEFAULTS, LTCAModel, contact_positions, default_extents, loaded_tca, ltca_model,
                       segment_compliance)
from .halfspace import STEEL, Material, contact_modulus, halfspace_flexibility
from .lcp import LoadSolution, solve_load_distribution
from .ltca import APPROACH_TARGET, ContactPosition, PairContact, run_ltca, torque_for_approach
from .mesher import SegmentMesh, grid_normals, mesh_tooth_segment
from .result import LTCAResult
from .separation import SeparationGrid, posed_separations, quadratic_separations, surface_separations

__all__ = [
    "APPROACH_TARGET", "ContactPosition", "FE_DEFAULTS", "LTCAModel", "contact_positions", "default_extents",
    "loaded_tca", "ltca_model", "segment_compliance", "posed_separations", "LTCAResult", "LoadSolution", "Material",
    "PairContact", "STEEL",
    "SegmentMesh", "SeparationGrid", "ToothCompliance", "contact_modulus", "default_cache_dir", "grid_normals",
    "halfspace_flexibility", "mesh_tooth_segment", "quadratic_separations", "run_ltca", "solve_load_distribution",
    "surface_separations", "tooth_compliance", "torque_for_approach",
]
