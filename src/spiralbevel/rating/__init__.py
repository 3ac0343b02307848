"""Load capacity of spiral bevel gears: ISO 10300 Method B1 (parts 1 to 3).

:func:`rate_iso10300` takes the ISO 23509 blank (:class:`~spiralbevel.design.blank_result.BevelBlank`) and the
operating and material data (:class:`RatingInput`) and returns a :class:`RatingResult` whose values are keyed by ISO
symbols in ASCII (``sigma_H``, ``Z_M-B``, ``Y_Fa1`` ...). Lengths mm, forces N, stresses N/mm^2, angles rad inside
(degrees only in :meth:`RatingResult.to_dict`).
"""

from .fe_root_stress import MemberRootStress, compare_root_stress, fe_root_stress
from .inputs import RatingInput, pitch_deviation_from_grade
from .ltca_compare import compare_with_ltca
from .rate import rate_iso10300
from .result import RatingResult

__all__ = ["RatingInput", "RatingResult", "rate_iso10300", "pitch_deviation_from_grade", "compare_with_ltca",
           "fe_root_stress", "compare_root_stress", "MemberRootStress"]
