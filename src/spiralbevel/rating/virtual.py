"""Virtual cylindrical gears of a bevel or hypoid pair (ISO 10300-1, Annex A, Method B1).

A bevel gear is rated through the helical gear pair it resembles at the mean point (Tredgold's approximation on the
back cone), and through that gear's virtual spur gear in the normal section. A hypoid pair has two mean spiral angles
(beta_m1 != beta_m2): the virtual pair takes their mean, and the offset shears its zone of action (the angle gamma of
the tip and root boundaries, ``contact_lines``), narrows its face width and changes the relative curvature.
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
        rho_rel, z_vn1, z_vn2, d_vn1, d_vn2, d_van1, d_van2, gamma, f_max, f_m, f_t, f_r, l_bm, l_bt, l_br``.

    Notes
    -----
    d_v = dm/cos(delta); beta_v = (beta_m1 + beta_m2)/2; tan(alpha_vet) = tan(alpha_e)/cos(beta_v) with the
    generated pressure angle of the drive side; m_vt = mmn/cos(beta_v); sin(beta_vb) = sin(beta_v) cos(alpha_e);
    d_va = d_v + 2 ham; d_vb = d_v cos(alpha_vet); p_vet = pi m_vt cos(alpha_vet);
    g_valpha = sum over members of (sqrt(d_va^2 - d_vb^2) - d_v sin(alpha_vet))/2; eps_valpha = g_valpha/p_vet;
    eps_vbeta = b_v,eff sin(beta_v)/(pi mmn); eps_vgamma = eps_valpha + eps_vbeta; rho_rel is the relative radius of
    curvature normal to the contact line at the pitch point, a_v sin(alpha_vet) u_v/((1 + u_v)^2 cos(beta_vb));
    z_vn = z_v/(cos^2(beta_vb) cos(beta_v)).

    With a hypoid offset (ISO 10300-1:2023 Annex A, the general forms, which reduce to the above for a = 0):
    the effective face width b_v,eff = (b_eff/cos(zeta_mp/2) - g_valpha cos(alpha_vet) tan(zeta_mp/2)) /
    (1 - tan(gamma') tan(zeta_mp/2)) with b_eff = 0.85 b, gamma' = theta_mp - zeta_mp/2 and
    tan(theta_mp) = sin(delta2) tan(zeta_m); the face width b_v = b b_v,eff/b_eff; the tip and root boundaries of the
    zone of action are inclined at gamma, tan(gamma) = tan(gamma')/cos(alpha_vet); the relative radius of curvature
    normal to the contact line rho_rel = rho_t cos^2(beta_B) with tan(beta_B) = tan(beta_v) sin(alpha_eD) and
    rho_t = (cos(alpha_nD) (tan(alpha_nD) - tan(alpha_lim)) + tan(zeta_mp) tan(beta_B)) cos(zeta_mp) /
    (cos(beta_m1) cos(beta_m2) (1/(Rm1 tan(delta1)) + 1/(Rm2 tan(delta2)))), the relative normal curvature of the
    two pitch cones at the mean point in the direction normal to the contact line. Without offset rho_rel equals the
    helical form above (``tests/rating/test_hypoid_sample2.py`` checks the identity).

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
    b_eff = b_eff_fraction * g.b
    if g.hypoid:
        t = math.tan(0.5 * g.zeta_mp)
        gamma_p = math.atan(math.sin(g.delta2) * math.tan(g.zeta_m)) - 0.5 * g.zeta_mp
        b_veff = ((b_eff / math.cos(0.5 * g.zeta_mp) - g_valpha * math.cos(alpha_vet) * t)
                  / (1.0 - math.tan(gamma_p) * t))
        b_v = g.b * b_veff / b_eff
        gamma = math.atan(math.tan(gamma_p) / math.cos(alpha_vet))
        beta_B = math.atan(math.tan(beta_v) * math.sin(g.alpha_eD))
        rho_t = ((math.cos(g.alpha_nD) * (math.tan(g.alpha_nD) - math.tan(g.alpha_lim))
                  + math.tan(g.zeta_mp) * math.tan(beta_B)) * math.cos(g.zeta_mp)
                 / (math.cos(g.beta_m1) * math.cos(g.beta_m2)
                    * (1.0 / (g.Rm1 * math.tan(g.delta1)) + 1.0 / (g.Rm2 * math.tan(g.delta2)))))
        rho_rel = abs(rho_t) * math.cos(beta_B) ** 2
    else:
        b_v, b_veff, gamma = g.b, b_eff, 0.0
        rho_rel = a_v * s * u_v / ((1.0 + u_v) ** 2 * math.cos(beta_vb))
    eps_vbeta = b_veff * math.sin(beta_v) / (math.pi * g.mmn)
    eps_vgamma = eps_valpha + eps_vbeta
    cn = math.cos(beta_vb) ** 2 * math.cos(beta_v)
    z_v1, z_v2 = d_v1 / m_vt, d_v2 / m_vt
    z_vn1, z_vn2 = z_v1 / cn, z_v2 / cn
    d_vn1, d_vn2 = z_vn1 * g.mmn, z_vn2 * g.mmn
    out = {
        "d_v1": d_v1, "d_v2": d_v2, "u_v": u_v, "a_v": a_v, "beta_v": beta_v, "beta_vb": beta_vb,
        "alpha_vet": alpha_vet, "m_vt": m_vt, "z_v1": z_v1, "z_v2": z_v2, "d_va1": d_va1, "d_va2": d_va2,
        "d_vb1": d_vb1, "d_vb2": d_vb2, "p_vet": p_vet, "g_valpha": g_valpha, "eps_valpha": eps_valpha,
        "b_v": b_v, "b_veff": b_veff, "eps_vbeta": eps_vbeta, "eps_vgamma": eps_vgamma, "rho_rel": rho_rel,
        "z_vn1": z_vn1, "z_vn2": z_vn2, "d_vn1": d_vn1, "d_vn2": d_vn2, "gamma": gamma,
        "d_van1": d_vn1 + 2.0 * g.ham1, "d_van2": d_vn2 + 2.0 * g.ham2,
    }
    lines = contact_line_layout(out)
    out.update(lines)
    for key in ("m", "t", "r"):
        out[f"l_b{key}"] = contact_line_length(lines[f"f_{key}"], out, lines["f_max"])
    return out
