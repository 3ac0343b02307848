"""The one place where the rating reads the ISO 23509 blank.

Every quantity the ISO 10300 rating takes from :class:`~spiralbevel.design.blank_result.BevelBlank` is read here,
so that a change of the blank's fields touches one function.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class BlankData:
    """Blank quantities used by the rating (mm, rad); subscript 1 = pinion, 2 = wheel.

    Hypoid pairs add the limit pressure angle ``alpha_lim``, the offset angles in the axial plane ``zeta_m`` and in
    the pitch plane ``zeta_mp`` and the mean cone distances ``Rm1, Rm2`` of ISO 23509 (all 0 or ``Rm`` without
    offset).

    ``x_hm1`` and ``x_sm1, x_sm2`` are the profile shift and thickness modification coefficients as ISO 10300-1
    defines them: x_hm1 = (ham1 - ham2)/(2 mmn) = -x_hm2 and, from the mean normal circular thickness (backlash
    included), smn = mmn (pi/2 + x_hm (tan alpha_nD + tan alpha_nC) + 2 x_sm).
    """

    z1: int
    z2: int
    Sigma: float
    a: float
    b: float
    Rm: float
    rc0: float
    dm1: float
    dm2: float
    delta1: float
    delta2: float
    beta_m1: float
    beta_m2: float
    mmn: float
    alpha_nD: float
    alpha_nC: float
    alpha_eD: float
    alpha_eC: float
    ham1: float
    ham2: float
    hfm1: float
    hfm2: float
    x_hm1: float
    x_sm1: float
    x_sm2: float
    alpha_lim: float = 0.0
    zeta_m: float = 0.0
    zeta_mp: float = 0.0
    Rm1: float = 0.0
    Rm2: float = 0.0

    @property
    def hypoid(self) -> bool:
        """True with a hypoid offset (a != 0)."""
        return abs(self.a) > 1e-9

    @property
    def x_hm2(self) -> float:
        return -self.x_hm1


def blank_data(blank) -> BlankData:
    """Read the rating's blank quantities from a ``BevelBlank``.

    Parameters
    ----------
    blank : spiralbevel.design.blank_result.BevelBlank

    Returns
    -------
    BlankData
    """
    mmn = blank.mmn
    x_hm1 = (blank.ham1 - blank.ham2) / (2.0 * mmn)
    tan_sum = math.tan(blank.alpha_nD) + math.tan(blank.alpha_nC)

    def x_sm(smn, x_hm):
        return 0.5 * (smn / mmn - 0.5 * math.pi - x_hm * tan_sum)

    return BlankData(
        z1=blank.z1, z2=blank.z2, Sigma=blank.Sigma, a=blank.a, b=min(blank.b1, blank.b2), Rm=blank.Rm,
        rc0=blank.rc0, dm1=blank.dm1, dm2=blank.dm2, delta1=blank.delta1, delta2=blank.delta2,
        beta_m1=blank.beta_m1, beta_m2=blank.beta_m2, mmn=mmn, alpha_nD=blank.alpha_nD, alpha_nC=blank.alpha_nC,
        alpha_eD=blank.alpha_eD, alpha_eC=blank.alpha_eC, ham1=blank.ham1, ham2=blank.ham2, hfm1=blank.hfm1,
        hfm2=blank.hfm2, x_hm1=x_hm1, x_sm1=x_sm(blank.smn1, x_hm1), x_sm2=x_sm(blank.smn2, -x_hm1),
        alpha_lim=blank.alpha_lim, zeta_m=blank.zeta_m, zeta_mp=blank.zeta_mp, Rm1=blank.Rm1, Rm2=blank.Rm2)
