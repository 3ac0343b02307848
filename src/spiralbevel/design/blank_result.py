"""Result object of the ISO 23509 blank computation: :class:`BevelBlank`.

Every quantity is an attribute named by its ISO 23509 symbol in ASCII (``delta1`` = δ1, ``theta_f2`` = θf2,
``hae1`` = hae1 ...). Angles rad, lengths mm. ``spiralbevel.design.blank_meta.QUANTITIES`` gives the description and
unit of each one; ``docs/glossary.md`` maps them to the symbols of the source papers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..conventions import Hand
from .blank_meta import QUANTITIES, attribute_names, metadata

__all__ = ["BevelBlank"]

_KIND = {
    name: kind
    for base, _d, kind, scope in QUANTITIES
    for name in ([base] if scope == "pair" else [base + "1", base + "2"])
}


@dataclass(frozen=True)
class BevelBlank:
    """Blank geometry of a spiral bevel (ISO 23509 Method 0) or hypoid pair (Method 1), face milling.

    Built by :func:`spiralbevel.design.blank.compute_blank`. Subscript 1 = pinion, 2 = wheel. Attributes are grouped as
    in
    ``blank_meta.QUANTITIES``: basic data (``z1, z2, u, Sigma, hand1, hand2, rc0``, factors), pitch cone (``delta1,
    delta2, Re1, Re2, Rm, Rm1, Rm2, Ri1, Ri2, b1, b2, be*, bi*, de*, dm*, di*, met, mmt, mmn``), hypoid offset
    (``eta, zeta_m, zeta_mp, ap, zeta_R, zeta_o, c_be2, rho_lim``), spiral and
    pressure angles (``beta_m*, beta_e*`` heel, ``beta_i*`` toe, ``alpha_nD, alpha_nC, alpha_lim, alpha_eD,
    alpha_eC, alpha_e``), mean depths (``hmw, c, hm, x_hm1, x_smn, ham*, hfm*``), taper (``theta_a*, theta_f*,
    delta_a*, delta_f*``, the dedendum angle sums), heel/toe depths and diameters (``hae*, hfe*, he*, hai*, hfi*,
    hi*, ht*, dae*, dai*, dfe*, dfi*``), axial positions measured from the crossing point (``tzm*`` crossing point
    to mean point, ``tz*`` pitch apex, ``txo*, txi*`` crown points, ``tzF*, tzR*`` face and root apex), thickness
    (``jen, jet, jmn, x_sm*, smn*, smt*, dvn*, smnc*, hamc*``), top lands at toe/mean/heel (``sai*, sam*, sae*``)
    and the pinion undercut limit (``hlim*``).

    Attributes
    ----------
    warnings : tuple of str
        Every :class:`~spiralbevel.errors.DesignWarning` message raised while computing the blank.
    """

    z1: int
    z2: int
    u: float
    Sigma: float
    a: float
    hand1: Hand
    hand2: Hand
    taper: str
    rc0: float
    c_ham: float
    k_d: float
    k_c: float
    k_t: float
    delta1: float
    delta2: float
    zp: float
    b1: float
    b2: float
    be1: float
    be2: float
    bi1: float
    bi2: float
    Re1: float
    Re2: float
    Rm: float
    Rm1: float
    Rm2: float
    Ri1: float
    Ri2: float
    de1: float
    de2: float
    dm1: float
    dm2: float
    di1: float
    di2: float
    met: float
    mmt: float
    mmn: float
    eta: float
    zeta_m: float
    zeta_mp: float
    ap: float
    zeta_R: float
    zeta_o: float
    c_be2: float
    rho_lim: float
    beta_m1: float
    beta_m2: float
    beta_e1: float
    beta_e2: float
    beta_i1: float
    beta_i2: float
    alpha_nD: float
    alpha_nC: float
    alpha_lim: float
    alpha_eD: float
    alpha_eC: float
    alpha_e: float
    hmw: float
    c: float
    hm: float
    x_hm1: float
    x_smn: float
    ham1: float
    ham2: float
    hfm1: float
    hfm2: float
    sum_theta_f: float
    sum_theta_fS: float
    sum_theta_fC: float
    sum_theta_fM: float
    theta_a1: float
    theta_a2: float
    theta_f1: float
    theta_f2: float
    delta_a1: float
    delta_a2: float
    delta_f1: float
    delta_f2: float
    hae1: float
    hae2: float
    hfe1: float
    hfe2: float
    he1: float
    he2: float
    hai1: float
    hai2: float
    hfi1: float
    hfi2: float
    hi1: float
    hi2: float
    ht1: float
    ht2: float
    dae1: float
    dae2: float
    dai1: float
    dai2: float
    dfe1: float
    dfe2: float
    dfi1: float
    dfi2: float
    tzm1: float
    tzm2: float
    tz1: float
    tz2: float
    txo1: float
    txo2: float
    txi1: float
    txi2: float
    tzF1: float
    tzF2: float
    tzR1: float
    tzR2: float
    jen: float
    jet: float
    jmn: float
    x_sm1: float
    x_sm2: float
    smn1: float
    smn2: float
    smt1: float
    smt2: float
    dvn1: float
    dvn2: float
    smnc1: float
    smnc2: float
    hamc1: float
    hamc2: float
    sai1: float
    sai2: float
    sam1: float
    sam2: float
    sae1: float
    sae2: float
    hlim1: float
    hlim2: float
    warnings: tuple[str, ...] = ()
    inp: Any = field(default=None, repr=False, compare=False)

    def to_dict(self, degrees: bool = True) -> dict[str, Any]:
        """All quantities as ``{ISO symbol: value}``.

        Parameters
        ----------
        degrees : bool
            Angles in degrees (default) or radians. Lengths are always mm; hands are ``"RH"``/``"LH"``.

        Returns
        -------
        dict
            Ordered as ``blank_meta.QUANTITIES``.
        """
        out: dict[str, Any] = {}
        for name in attribute_names():
            v = getattr(self, name)
            if isinstance(v, Hand):
                v = v.value
            elif _KIND[name] == "angle" and degrees:
                v = math.degrees(v)
            out[name] = v
        return out

    @staticmethod
    def metadata(degrees: bool = True) -> list[tuple[str, str, str]]:
        """``(symbol, description, unit)`` of every quantity in ``to_dict`` order."""
        return metadata(degrees)
