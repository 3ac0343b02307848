"""ISO 10300 Method B1 rating of a spiral bevel pair without offset: :func:`rate_iso10300`."""

from __future__ import annotations

import math

from ..errors import DesignError
from ._blank import blank_data
from .inputs import RatingInput
from .load_factors import dynamic_factor, face_load_factors, nominal_forces, running_in, transverse_load_factor
from .pitting import (Z_K, elasticity_factor, life_factor_H, load_sharing_factor, lubrication_factors,
                      mid_zone_factor)
from .result import RatingResult
from .root import (contact_ratio_factor, life_factor_F, notch_sensitivity_factor, size_factor_F, surface_factor,
                   tooth_form)
from .virtual import virtual_gears

__all__ = ["rate_iso10300"]

Y_ST = 2.0  # stress correction factor of the standard test gear

NOTES = (
    "l_bm: length of the contact line through the centre of the rectangular zone of action; the standard's formula "
    "could not be confirmed",
    "Z_LS: ISO 10300-2:2001 form; the current edition's form could not be confirmed",
    "Y_BS: the bevel spiral angle factor's formula could not be confirmed; taken as 1",
    "Z_X = 1, Z_W = 1 (both members surface-hardened), Y_ST = 2",
)


def rate_iso10300(blank, inp: RatingInput) -> RatingResult:
    """Rate a spiral bevel pair for pitting and tooth root bending, ISO 10300 Method B1.

    Parameters
    ----------
    blank : spiralbevel.design.blank_result.BevelBlank
        ISO 23509 blank (no offset).
    inp : RatingInput
        Load, accuracy, mounting, material and lubricant data.

    Returns
    -------
    RatingResult
        Every virtual gear quantity, factor and stress keyed by its ISO symbol; safety factors
        S_H = sigma_HG/sigma_H (lower of the pair) and S_F1, S_F2 = sigma_FG/sigma_F.

    Notes
    -----
    sigma_H0 = sqrt(F_n/(l_bm rho_rel)) Z_M-B Z_LS Z_E Z_K with F_n = F_vmt/(cos(alpha_vet) cos(beta_vb));
    sigma_H = sigma_H0 sqrt(K_A K_v K_Hbeta K_Halpha); sigma_HG = sigma_Hlim Z_NT Z_L Z_v Z_R Z_X Z_W;
    sigma_HP = sigma_HG/S_Hmin. sigma_F0 = F_vmt/(b_v mmn) Y_Fa Y_Sa Y_eps Y_BS Y_LS;
    sigma_F = sigma_F0 K_A K_v K_Fbeta K_Falpha; sigma_FG = sigma_Flim Y_ST Y_NT Y_deltarelT Y_RrelT Y_X;
    sigma_FP = sigma_FG/S_Fmin. The formulas of each factor are in the docstrings of ``virtual``, ``load_factors``,
    ``pitting`` and ``root``; docs/rating.md says which were checked against ISO/TR 10300-30 Sample 1.
    """
    g = blank_data(blank)
    if abs(g.a) > 1e-9:
        raise DesignError.single("gear_set.hypoid_offset", g.a, "0 (the hypoid rating is not implemented)", "mm")
    v = virtual_gears(g)
    out = {}
    forces = nominal_forces(g, inp.T1, inp.n1)
    out.update(forces)
    out.update(v)
    out.update(x_hm1=g.x_hm1, x_hm2=g.x_hm2, x_sm1=g.x_sm1, x_sm2=g.x_sm2)

    sHlim = min(inp.sigma_Hlim)
    f_pt = max(inp.f_pt)
    y_alpha = running_in(f_pt, inp.material, sHlim, forces["v_mt"])
    f_peff = max(f_pt - y_alpha, 0.0)
    dyn = dynamic_factor(g, v, forces["F_mt1"], inp.K_A, inp.n1, f_peff, inp.density)
    face = face_load_factors(g, inp.mounting, inp.contact_pattern)
    Z_LS = load_sharing_factor(v)
    Y_eps = contact_ratio_factor(v["eps_valpha"], v["eps_vbeta"])
    F_mtH = forces["F_mt1"] * inp.K_A * dyn["K_v"] * face["K_Hbeta"]
    trans = transverse_load_factor(v, F_mtH, f_pt, y_alpha, Z_LS, Y_eps)
    out.update(K_A=inp.K_A, y_alpha=y_alpha, f_peff=f_peff, m_red=dyn["m_red"], n_E1=dyn["n_E1"], N=dyn["N"],
               K_v=dyn["K_v"], **face, **trans)

    # pitting (ISO 10300-2)
    Z_MB = mid_zone_factor(v)
    Z_E = elasticity_factor(inp.E, inp.nu)
    F_n = forces["F_vmt"] / (math.cos(v["alpha_vet"]) * math.cos(v["beta_vb"]))
    sigma_H0 = math.sqrt(F_n / (v["l_bm"] * v["rho_rel"])) * Z_MB * Z_LS * Z_E * Z_K
    sigma_H = sigma_H0 * math.sqrt(inp.K_A * dyn["K_v"] * face["K_Hbeta"] * trans["K_Halpha"])
    lub = lubrication_factors(sHlim, inp.nu40, forces["v_mt"], 0.5 * sum(inp.Rz_flank), v["rho_rel"])
    out.update({"Z_M-B": Z_MB, "Z_LS": Z_LS, "Z_E": Z_E, "Z_K": Z_K, "sigma_H0": sigma_H0, "sigma_H": sigma_H,
                "Z_L": lub["Z_L"], "Z_v": lub["Z_v"], "Z_R": lub["Z_R"], "Z_X": 1.0, "Z_W": 1.0})
    u = g.z2 / g.z1
    cycles = (inp.load_cycles, None if inp.load_cycles is None else inp.load_cycles / u)
    S_H = []
    for k in (1, 2):
        Z_NT = life_factor_H(cycles[k - 1])
        sigma_HG = inp.sigma_Hlim[k - 1] * Z_NT * lub["Z_L"] * lub["Z_v"] * lub["Z_R"]
        S_H.append(sigma_HG / sigma_H)
        out.update({f"Z_NT{k}": Z_NT, f"sigma_HP{k}": sigma_HG / inp.S_Hmin, f"S_H{k}": S_H[-1]})
    out["S_H"] = min(S_H)

    # tooth root (ISO 10300-3)
    Y_LS = Z_LS ** 2
    Y_BS = 1.0
    forms = {}
    for k, x_hm, x_sm, hfm in ((1, g.x_hm1, g.x_sm1, g.hfm1), (2, g.x_hm2, g.x_sm2, g.hfm2)):
        h_a0 = hfm + x_hm * g.mmn
        tf = tooth_form(v[f"z_vn{k}"], g.mmn, g.alpha_nD, inp.rho_a0[k - 1], h_a0, x_hm, x_sm, v[f"d_van{k}"])
        forms[k] = tf
        out.update({f"h_a0{k}": h_a0, f"rho_a0{k}": inp.rho_a0[k - 1], f"theta{k}": tf["theta"],
                    f"s_Fn{k}": tf["s_Fn"], f"rho_F{k}": tf["rho_F"], f"h_Fa{k}": tf["h_Fa"],
                    f"alpha_Fan{k}": tf["alpha_Fan"], f"q_s{k}": tf["q_s"], f"Y_Fa{k}": tf["Y_Fa"],
                    f"Y_Sa{k}": tf["Y_Sa"]})
    out.update(Y_eps=Y_eps, Y_BS=Y_BS, Y_LS=Y_LS, Y_ST=Y_ST)
    load = inp.K_A * dyn["K_v"] * face["K_Fbeta"] * trans["K_Falpha"]
    for k in (1, 2):
        tf = forms[k]
        sigma_F0 = forces["F_vmt"] / (v["b_v"] * g.mmn) * tf["Y_Fa"] * tf["Y_Sa"] * Y_eps * Y_BS * Y_LS
        sigma_F = sigma_F0 * load
        Y_NT = life_factor_F(cycles[k - 1], inp.material)
        Y_d = notch_sensitivity_factor(tf["q_s"], inp.material)
        Y_R = surface_factor(inp.Rz_root[k - 1])
        Y_X = size_factor_F(g.mmn, inp.material)
        sigma_FG = inp.sigma_Flim[k - 1] * Y_ST * Y_NT * Y_d * Y_R * Y_X
        out.update({f"sigma_F0{k}": sigma_F0, f"sigma_F{k}": sigma_F, f"Y_NT{k}": Y_NT, f"Y_deltarelT{k}": Y_d,
                    f"Y_RrelT{k}": Y_R, f"Y_X{k}": Y_X, f"sigma_FP{k}": sigma_FG / inp.S_Fmin,
                    f"S_F{k}": sigma_FG / sigma_F})
    bad = [k for k, x in out.items() if not math.isfinite(x)]
    if bad:
        raise DesignError.single("rating", ", ".join(bad), "finite values", "",
                                 "the virtual gear of this blank is outside the range of ISO 10300")
    return RatingResult(values=out, notes=NOTES)
