"""Surface durability (pitting) factors of ISO 10300-2, Method B1.

Stresses N/mm^2, lengths mm, roughness um, viscosity mm^2/s, velocity m/s.
"""

from __future__ import annotations

import math

__all__ = ["mid_zone_factor", "load_sharing_factor", "elasticity_factor", "lubrication_factors", "life_factor_H",
           "Z_K"]

Z_K = 1.2  # bevel gear factor of ISO 10300-2:2014, on the permissible side (the 2001 edition: 0.85 on the stress)
E_LS = {"low": 3.0, "high": 1.5}  # exponent of the peak loads over the contact lines, by profile crowning


def mid_zone_factor(v: dict) -> float:
    """Z_M-B: converts the contact stress at the pitch point to the decisive point of the middle contact line.

    Notes
    -----
    Z_M-B = tan(alpha_vet) / sqrt((sqrt(d_va1^2/d_vb1^2 - 1) - F1 pi/z_v1)(sqrt(d_va2^2/d_vb2^2 - 1) - F2 pi/z_v2))
    with F1 = 2, F2 = 2 (eps_valpha - 1) for eps_vbeta = 0; F1 = 2 + (eps_valpha - 2) eps_vbeta,
    F2 = 2 eps_valpha - 2 + (2 - eps_valpha) eps_vbeta for 0 < eps_vbeta < 1; F1 = F2 = eps_valpha for
    eps_vbeta >= 1.
    """
    ea, eb = v["eps_valpha"], v["eps_vbeta"]
    if eb >= 1.0:
        F1 = F2 = ea
    else:
        F1 = 2.0 + (ea - 2.0) * eb
        F2 = 2.0 * ea - 2.0 + (2.0 - ea) * eb
    t1 = math.sqrt((v["d_va1"] / v["d_vb1"]) ** 2 - 1.0) - F1 * math.pi / v["z_v1"]
    t2 = math.sqrt((v["d_va2"] / v["d_vb2"]) ** 2 - 1.0) - F2 * math.pi / v["z_v2"]
    return math.tan(v["alpha_vet"]) / math.sqrt(t1 * t2)


def load_sharing_factor(v: dict, profile_crowning: str = "low") -> dict:
    """Z_LS, the share of the load carried by the middle contact line (as a stress factor), ISO 10300-2 Method B1.

    Parameters
    ----------
    v : dict
        Virtual gear quantities with the contact lines (``f_max, f_m, f_t, f_r, l_bm, l_bt, l_br``; mm).
    profile_crowning : str
        ``"low"`` or ``"high"``: the exponent e_LS = 3 or 1.5 of the peak load distribution.

    Returns
    -------
    dict
        ``Z_LS`` and the related peak loads ``p_m*, p_t*, p_r*`` (-) and areas ``A_m*, A_t*, A_r*`` (mm).

    Notes
    -----
    Each contact line carries a semi-elliptical load of peak p* = 1 - |f/f_max|^e_LS (the peak falls off from the
    middle of the zone of action to its corners), so its related area is A* = pi/4 p* l_b; the middle line's share
    of the load is A_m*/(A_t* + A_m* + A_r*) and Z_LS = sqrt(A_m*/(A_t* + A_m* + A_r*)). Lines at or beyond f_max
    carry nothing.
    """
    e_ls = E_LS[profile_crowning]
    out = {}
    for key in ("m", "t", "r"):
        p = max(1.0 - abs(v[f"f_{key}"] / v["f_max"]) ** e_ls, 0.0)
        out[f"p_{key}*"] = p
        out[f"A_{key}*"] = 0.25 * math.pi * p * v[f"l_b{key}"]
    out["Z_LS"] = math.sqrt(out["A_m*"] / (out["A_t*"] + out["A_m*"] + out["A_r*"]))
    return out


def elasticity_factor(E: float, nu: float) -> float:
    """Z_E = sqrt(E/(2 pi (1 - nu^2))), N^0.5/mm (both members of the same material): the Hertzian line contact
    pressure is Z_E sqrt(F_n/(l rho_rel))."""
    return math.sqrt(E / (2.0 * math.pi * (1.0 - nu * nu)))


def lubrication_factors(sigma_Hlim: float, nu40: float, v_mt: float, Rz: float, rho_rel: float) -> dict:
    """Lubricant, speed and roughness factors Z_L, Z_v, Z_R (ISO 10300-2 as ISO 6336-2).

    Parameters
    ----------
    sigma_Hlim : float, N/mm^2
        The lower allowable contact stress number of the pair.
    nu40 : float, mm^2/s
    v_mt : float, m/s
        Mean pitch line velocity.
    Rz : float, um
        Mean flank roughness of the pair, (Rz1 + Rz2)/2.
    rho_rel : float, mm

    Notes
    -----
    C_ZL = 0.83 (sigma_Hlim < 850), sigma_Hlim/4375 + 0.6357 (850 ... 1200), 0.91 (> 1200);
    Z_L = C_ZL + 4 (1 - C_ZL)/(1.2 + 134/nu40)^2; C_Zv = C_ZL + 0.02, Z_v = C_Zv + 2 (1 - C_Zv)/sqrt(0.8 + 32/v);
    Rz10 = Rz (10/rho_rel)^(1/3); C_ZR = 0.15 (< 850), 0.32 - 0.0002 sigma_Hlim (850 ... 1200), 0.08 (> 1200);
    Z_R = (3/Rz10)^C_ZR.
    """
    s = min(max(sigma_Hlim, 850.0), 1200.0)
    C_ZL = s / 4375.0 + 0.6357
    Z_L = C_ZL + 4.0 * (1.0 - C_ZL) / (1.2 + 134.0 / nu40) ** 2
    C_Zv = C_ZL + 0.02
    Z_v = C_Zv + 2.0 * (1.0 - C_Zv) / math.sqrt(0.8 + 32.0 / v_mt)
    Rz10 = Rz * (10.0 / rho_rel) ** (1.0 / 3.0)
    C_ZR = 0.32 - 0.0002 * s
    return {"Z_L": Z_L, "Z_v": Z_v, "Z_R": (3.0 / Rz10) ** C_ZR, "Rz10": Rz10}


def life_factor_H(N_L: "float | None") -> float:
    """Z_NT of case- or through-hardened steel (pitting permitted curve of ISO 6336-2): 1.6 up to 1e5 cycles,
    (5e7/N_L)^0.0756 up to 5e7, 1 beyond; None = long life (1)."""
    if N_L is None or N_L >= 5e7:
        return 1.0
    if N_L <= 1e5:
        return 1.6
    return (5e7 / N_L) ** 0.0756
