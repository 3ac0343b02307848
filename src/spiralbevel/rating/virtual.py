"""Virtual cylindrical gears of a bevel pair without offset (ISO 10300-1, Annex A, Method B1).

A bevel gear is rated through the helical gear pair it resembles at the mean point (Tredgold's approximation on the
back cone), and through that gear's virtual spur gear in the normal section.
"""

from __future__ import annotations

import math

from ._blank import BlankData
from .contact_lines import contact_line_layout, contact_line_length

__all__ = ["virtual_gears"]


def virtual_gears(g: BlankData, b_eff_fraction: float = 0.85) -> dict:
    """Virtual cylindrical gears in the transverse and normal sections.

    Parameters
    ----------
    g : BlankData
        Blank quantities (mm, rad).
    b_eff_fraction : float
        Effective face width b_v,eff / b (0.85: contact pattern verified, ISO 10300-1).

    Returns
    -------
    dict
        ISO symbol -> value (lengths mm, angles rad): ``d_v1, d_v2, u_v, a_v, beta_v, beta_vb, alpha_vet, m_vt,
        z_v1, z_v2, d_va1, d_va2, d_vb1, d_vb2, p_vet, g_valpha, eps_valpha, b_v, b_veff, eps_vbeta, eps_vgamma,
        rho_rel, z_vn1, z_vn2, d_vn1, d_vn2, d_van1, d_van2, f_max, f_m, f_t, f_r, l_bm, l_bt, l_br``.

    Notes
    -----
    d_v = dm/cos(delta); beta_v = (beta_m1 + beta_m2)/2; tan(alpha_vet) = tan(alpha_e)/cos(beta_v) with the
    generated pressure angle of the drive side; m_vt = mmn/cos(beta_v); sin(beta_vb) = sin(beta_v) cos(alpha_e);
    d_va = d_v + 2 ham; d_vb = d_v cos(alpha_vet); p_vet = pi m_vt cos(alpha_vet);
    g_valpha = sum over members of (sqrt(d_va^2 - d_vb^2) - d_v sin(alpha_vet))/2; eps_valpha = g_valpha/p_vet;
    eps_vbeta = b_v,eff sin(beta_v)/(pi mmn); eps_vgamma = eps_valpha + eps_vbeta; rho_rel is the relative radius of
    curvature normal to the contact line at the pitch point, a_v sin(alpha_vet) u_v/((1 + u_v)^2 cos(beta_vb));
    z_vn = z_v/(cos^2(beta_vb) cos(beta_v)).

    l_bm, l_bt, l_br are the lengths of the middle, tip and root contact lines inside the contact pattern, at the
    distances f_m, f_t, f_r from the centre of the zone of action (``contact_lines``).
    """
    alpha_e = g.alpha_eD
    d_v1 = g.dm1 / math.cos(g.delta1)
    d_v2 = g.dm2 / math.cos(g.delta2)
    u_v = d_v2 / d_v1
    a_v = 0.5 * (d_v1 + d_v2)
    beta_v = 0.5 * (g.beta_m1 + g.beta_m2)
    alpha_vet = math.atan(math.tan(alpha_e) / math.cos(beta_v))
    beta_vb = math.asin(math.sin(beta_v) * math.cos(alpha_e))
    m_vt = g.mmn / math.cos(beta_v)
    d_va1, d_va2 = d_v1 + 2.0 * g.ham1, d_v2 + 2.0 * g.ham2
    d_vb1, d_vb2 = d_v1 * math.cos(alpha_vet), d_v2 * math.cos(alpha_vet)
    p_vet = math.pi * m_vt * math.cos(alpha_vet)
    s = math.sin(alpha_vet)
    g_valpha = 0.5 * (math.sqrt(d_va1 ** 2 - d_vb1 ** 2) - d_v1 * s) + 0.5 * (math.sqrt(d_va2 ** 2 - d_vb2 ** 2)
                                                                              - d_v2 * s)
    eps_valpha = g_valpha / p_vet
    b_v = g.b
    b_veff = b_eff_fraction * b_v
    eps_vbeta = b_veff * math.sin(beta_v) / (math.pi * g.mmn)
    eps_vgamma = eps_valpha + eps_vbeta
    rho_rel = a_v * s * u_v / ((1.0 + u_v) ** 2 * math.cos(beta_vb))
    cn = math.cos(beta_vb) ** 2 * math.cos(beta_v)
    z_v1, z_v2 = d_v1 / m_vt, d_v2 / m_vt
    z_vn1, z_vn2 = z_v1 / cn, z_v2 / cn
    d_vn1, d_vn2 = z_vn1 * g.mmn, z_vn2 * g.mmn
    out = {
        "d_v1": d_v1, "d_v2": d_v2, "u_v": u_v, "a_v": a_v, "beta_v": beta_v, "beta_vb": beta_vb,
        "alpha_vet": alpha_vet, "m_vt": m_vt, "z_v1": z_v1, "z_v2": z_v2, "d_va1": d_va1, "d_va2": d_va2,
        "d_vb1": d_vb1, "d_vb2": d_vb2, "p_vet": p_vet, "g_valpha": g_valpha, "eps_valpha": eps_valpha,
        "b_v": b_v, "b_veff": b_veff, "eps_vbeta": eps_vbeta, "eps_vgamma": eps_vgamma, "rho_rel": rho_rel,
        "z_vn1": z_vn1, "z_vn2": z_vn2, "d_vn1": d_vn1, "d_vn2": d_vn2,
        "d_van1": d_vn1 + 2.0 * g.ham1, "d_van2": d_vn2 + 2.0 * g.ham2,
    }
    lines = contact_line_layout(out)
    out.update(lines)
    for key in ("m", "t", "r"):
        out[f"l_b{key}"] = contact_line_length(lines[f"f_{key}"], out, lines["f_max"])
    return out
