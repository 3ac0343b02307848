"""Result of an ISO 10300 rating: :class:`RatingResult`, values keyed by ISO symbol in ASCII."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

__all__ = ["RatingResult", "SYMBOLS"]

# symbol -> (section, description, unit); units "rad" are shown in degrees by to_dict
SYMBOLS = {
    "F_mt1": ("load", "nominal tangential force at the mean point", "N"),
    "F_vmt": ("load", "tangential force of the virtual cylindrical gear", "N"),
    "v_mt": ("load", "mean pitch line velocity, pinion", "m/s"),
    "v_mt2": ("load", "mean pitch line velocity, wheel", "m/s"),
    "d_v1": ("virtual", "reference diameter, pinion", "mm"), "d_v2": ("virtual", "reference diameter, wheel", "mm"),
    "u_v": ("virtual", "gear ratio", "-"), "a_v": ("virtual", "centre distance", "mm"),
    "beta_v": ("virtual", "helix angle", "rad"), "beta_vb": ("virtual", "base helix angle", "rad"),
    "alpha_vet": ("virtual", "transverse pressure angle", "rad"), "m_vt": ("virtual", "transverse module", "mm"),
    "z_v1": ("virtual", "number of teeth, pinion", "-"), "z_v2": ("virtual", "number of teeth, wheel", "-"),
    "d_va1": ("virtual", "tip diameter, pinion", "mm"), "d_va2": ("virtual", "tip diameter, wheel", "mm"),
    "d_vb1": ("virtual", "base diameter, pinion", "mm"), "d_vb2": ("virtual", "base diameter, wheel", "mm"),
    "p_vet": ("virtual", "transverse base pitch", "mm"), "g_valpha": ("virtual", "length of path of contact", "mm"),
    "eps_valpha": ("virtual", "transverse contact ratio", "-"), "b_v": ("virtual", "face width", "mm"),
    "b_veff": ("virtual", "effective face width", "mm"), "eps_vbeta": ("virtual", "face contact ratio", "-"),
    "eps_vgamma": ("virtual", "total contact ratio", "-"),
    "rho_rel": ("virtual", "relative radius of curvature normal to the contact line", "mm"),
    "z_vn1": ("virtual", "teeth of the normal-section spur gear, pinion", "-"),
    "z_vn2": ("virtual", "teeth of the normal-section spur gear, wheel", "-"),
    "d_vn1": ("virtual", "normal-section reference diameter, pinion", "mm"),
    "d_vn2": ("virtual", "normal-section reference diameter, wheel", "mm"),
    "d_van1": ("virtual", "normal-section tip diameter, pinion", "mm"),
    "d_van2": ("virtual", "normal-section tip diameter, wheel", "mm"),
    "gamma": ("virtual", "inclination of the tip and root boundaries of the zone of action (hypoid)", "rad"),
    "f_max": ("virtual", "distance of the corner of the zone of action from its centre", "mm"),
    "f_m": ("virtual", "distance of the middle contact line from the centre", "mm"),
    "f_t": ("virtual", "distance of the tip contact line from the centre", "mm"),
    "f_r": ("virtual", "distance of the root contact line from the centre", "mm"),
    "l_bm": ("virtual", "length of the middle contact line", "mm"),
    "l_bt": ("virtual", "length of the tip contact line", "mm"),
    "l_br": ("virtual", "length of the root contact line", "mm"),
    "x_hm1": ("virtual", "profile shift coefficient, pinion", "-"),
    "x_hm2": ("virtual", "profile shift coefficient, wheel", "-"),
    "x_sm1": ("virtual", "thickness modification coefficient, pinion", "-"),
    "x_sm2": ("virtual", "thickness modification coefficient, wheel", "-"),
    "K_A": ("factors", "application factor", "-"),
    "y_alpha": ("factors", "running-in allowance", "um"), "f_peff": ("factors", "effective pitch deviation", "um"),
    "m_red": ("factors", "reduced mass per face width", "kg/mm"), "n_E1": ("factors", "resonance speed", "1/min"),
    "N": ("factors", "resonance ratio", "-"), "K_v": ("factors", "dynamic factor", "-"),
    "K_Hbeta-be": ("factors", "mounting factor", "-"), "K_Hbeta": ("factors", "face load factor, contact", "-"),
    "K_F0": ("factors", "lengthwise curvature factor", "-"), "K_Fbeta": ("factors", "face load factor, root", "-"),
    "K_Halpha": ("factors", "transverse load factor, contact", "-"),
    "K_Falpha": ("factors", "transverse load factor, root", "-"),
    "K_Halpha*": ("factors", "transverse load factor, contact, before the hypoid offset", "-"),
    "K_Falpha*": ("factors", "transverse load factor, root, before the hypoid offset", "-"),
    "a_rel": ("factors", "relative hypoid offset 2a/dm2", "-"),
    "Z_M-B": ("pitting", "mid-zone factor", "-"),
    "p_m*": ("pitting", "related peak load, middle contact line", "-"),
    "p_t*": ("pitting", "related peak load, tip contact line", "-"),
    "p_r*": ("pitting", "related peak load, root contact line", "-"),
    "A_m*": ("pitting", "related area, middle contact line", "mm"),
    "A_t*": ("pitting", "related area, tip contact line", "mm"),
    "A_r*": ("pitting", "related area, root contact line", "mm"),
    "Z_LS": ("pitting", "load sharing factor", "-"),
    "F_n": ("pitting", "nominal normal force at the mean point", "N"),
    "Z_Hyp": ("pitting", "hypoid factor", "-"),
    "Z_E": ("pitting", "elasticity factor", "N^0.5/mm"),
    "Z_K": ("pitting", "bevel gear factor (permissible side)", "-"),
    "sigma_H0": ("pitting", "nominal contact stress", "N/mm^2"), "sigma_H": ("pitting", "contact stress", "N/mm^2"),
    "Z_L": ("pitting", "lubricant factor", "-"), "Z_v": ("pitting", "speed factor", "-"),
    "Z_R": ("pitting", "roughness factor", "-"), "Z_X": ("pitting", "size factor", "-"),
    "Z_W": ("pitting", "work hardening factor", "-"),
}
for _k in (1, 2):
    _m = "pinion" if _k == 1 else "wheel"
    SYMBOLS.update({
        f"Z_NT{_k}": ("pitting", f"life factor, {_m}", "-"),
        f"sigma_HG{_k}": ("pitting", f"pitting stress limit, {_m}", "N/mm^2"),
        f"sigma_HP{_k}": ("pitting", f"permissible contact stress, {_m}", "N/mm^2"),
        f"S_H{_k}": ("pitting", f"safety factor for pitting, {_m}", "-"),
    })
SYMBOLS["S_H"] = ("pitting", "safety factor for pitting (lower of the pair)", "-")
for _k in (1, 2):
    _m = "pinion" if _k == 1 else "wheel"
    SYMBOLS.update({
        f"h_a0{_k}": ("root", f"cutter addendum, {_m}", "mm"),
        f"rho_a0{_k}": ("root", f"cutter edge radius, {_m}", "mm"),
        f"theta{_k}": ("root", f"critical section angle, {_m}", "rad"),
        f"s_Fn{_k}": ("root", f"root chord in the critical section, {_m}", "mm"),
        f"rho_F{_k}": ("root", f"root fillet radius in the critical section, {_m}", "mm"),
        f"h_Fa{_k}": ("root", f"bending moment arm, load at the tip, {_m}", "mm"),
        f"alpha_Fan{_k}": ("root", f"load application angle at the tip, {_m}", "rad"),
        f"q_s{_k}": ("root", f"notch parameter, {_m}", "-"),
        f"Y_Fa{_k}": ("root", f"tooth form factor, {_m}", "-"),
        f"Y_Sa{_k}": ("root", f"stress correction factor, {_m}", "-"),
    })
SYMBOLS.update({
    "Y_eps": ("root", "contact ratio factor", "-"),
    "b_a": ("root", "developed face width of the tooth (Y_BS)", "mm"),
    "l_bb": ("root", "projected length of the middle contact line (Y_BS)", "mm"),
    "a_BS": ("root", "coefficient a of Y_BS", "-"), "b_BS": ("root", "coefficient b of Y_BS", "-"),
    "c_BS": ("root", "coefficient c of Y_BS", "-"),
    "Y_BS": ("root", "bevel spiral angle factor", "-"),
    "Y_LS": ("root", "load sharing factor", "-"), "Y_ST": ("root", "stress correction factor of the test gear", "-"),
})
for _k in (1, 2):
    _m = "pinion" if _k == 1 else "wheel"
    SYMBOLS.update({
        f"sigma_F0{_k}": ("root", f"nominal tooth root stress, {_m}", "N/mm^2"),
        f"sigma_F{_k}": ("root", f"tooth root stress, {_m}", "N/mm^2"),
        f"Y_NT{_k}": ("root", f"life factor, {_m}", "-"),
        f"Y_deltarelT{_k}": ("root", f"relative notch sensitivity factor, {_m}", "-"),
        f"Y_RrelT{_k}": ("root", f"relative surface factor, {_m}", "-"),
        f"Y_X{_k}": ("root", f"size factor, {_m}", "-"),
        f"sigma_FG{_k}": ("root", f"tooth root stress limit, {_m}", "N/mm^2"),
        f"sigma_FP{_k}": ("root", f"permissible tooth root stress, {_m}", "N/mm^2"),
        f"S_F{_k}": ("root", f"safety factor for bending, {_m}", "-"),
    })


@dataclass(frozen=True)
class RatingResult:
    """ISO 10300 Method B1 rating of a bevel pair.

    Attributes
    ----------
    values : dict
        ISO symbol in ASCII -> value (lengths mm, forces N, stresses N/mm^2, angles rad); member suffix 1 = pinion,
        2 = wheel. ``SYMBOLS`` gives the description and unit of each.
    notes : tuple of str
        Assumptions and the factors whose formula could not be confirmed.
    """

    values: dict
    notes: tuple = field(default=())

    def __getitem__(self, key: str) -> float:
        return self.values[key]

    @property
    def S_H(self) -> float:
        return self.values["S_H"]

    @property
    def S_F1(self) -> float:
        return self.values["S_F1"]

    @property
    def S_F2(self) -> float:
        return self.values["S_F2"]

    def to_dict(self, degrees: bool = True) -> dict:
        """``{ISO symbol: value}``, angles in degrees (default) or rad; plus ``"units"`` and ``"notes"``."""
        out, units = {}, {}
        for k, v in self.values.items():
            unit = SYMBOLS[k][2]
            if unit == "rad" and degrees:
                v, unit = math.degrees(v), "deg"
            out[k] = v
            units[k] = unit
        return {**out, "units": units, "notes": list(self.notes)}

    def rows(self):
        """``(section, symbol, description, unit, value)`` for a rating sheet, angles in degrees."""
        for k, v in self.values.items():
            section, desc, unit = SYMBOLS[k]
            if unit == "rad":
                v, unit = math.degrees(v), "deg"
            yield section, k, desc, unit, v
