"""Contact ratios of a bevel pair without offset from its blank: the virtual cylindrical gears of ISO 10300-1.

The pair is replaced at the mean point by the helical pair on the back cone (Tredgold): virtual reference diameters
d_v = d_m / cos(delta), the transverse pressure angle tan(alpha_vet) = tan(alpha_e) / cos(beta_v) and the mean
normal module m_mn. Then (ISO 10300-1, Method B1)

* transverse contact ratio eps_valpha = g_valpha / p_vet, with the length of the path of contact
  g_valpha = sum over both members of (sqrt(d_va^2 - d_vb^2) - d_v sin(alpha_vet)) / 2 (d_va = d_v + 2 h_am,
  d_vb = d_v cos(alpha_vet)) and the transverse base pitch p_vet = pi m_mn cos(alpha_vet) / cos(beta_v);
* face contact ratio eps_vbeta = b_eff sin(beta_v) / (pi m_mn), b_eff = 0.85 b when the contact pattern is verified;
* total contact ratio eps_vgamma = eps_valpha + eps_vbeta.
"""

from __future__ import annotations

import math

__all__ = ["contact_ratios", "contact_ratio_warnings", "MIN_TRANSVERSE", "MIN_TOTAL"]

#: below one, one tooth pair does not hand over to the next within the transverse section
MIN_TRANSVERSE = 1.0
#: a spiral bevel pair below a total contact ratio of 2 runs with a single pair in contact over part of the cycle
#: (ISO 10300-2/-3 change their formulas at eps_vgamma = 2 for that reason)
MIN_TOTAL = 2.0


def contact_ratios(bl, alpha_e: float | None = None, b_eff_fraction: float = 0.85) -> dict:
    """Transverse, face and total contact ratio of the virtual cylindrical gears (module docstring).

    Parameters
    ----------
    bl : BevelBlank
        Blank without hypoid offset (``a = 0``).
    alpha_e : float, rad, optional
        Normal pressure angle of the loaded side; default the blank's generated drive-side angle ``alpha_eD``. Pass an
        achieved mean-point angle to judge a developed pair.
    b_eff_fraction : float
        Effective face width over the face width (0.85: ISO 10300-1 for a verified contact pattern; 1.0: geometric).

    Returns
    -------
    dict
        ``eps_valpha, eps_vbeta, eps_vgamma`` (-), ``g_valpha`` (mm), ``p_vet`` (mm), ``alpha_vet`` (rad).
    """
    a = float(bl.alpha_eD if alpha_e is None else alpha_e)
    beta_v = 0.5 * (float(bl.beta_m1) + float(bl.beta_m2))
    alpha_vet = math.atan(math.tan(a) / math.cos(beta_v))
    g = 0.0
    for k in (1, 2):
        d_v = float(getattr(bl, f"dm{k}")) / math.cos(float(getattr(bl, f"delta{k}")))
        d_va = d_v + 2.0 * float(getattr(bl, f"ham{k}"))
        d_vb = d_v * math.cos(alpha_vet)
        g += 0.5 * (math.sqrt(d_va ** 2 - d_vb ** 2) - d_v * math.sin(alpha_vet))
    p_vet = math.pi * float(bl.mmn) / math.cos(beta_v) * math.cos(alpha_vet)
    b = min(float(bl.b1), float(bl.b2))
    eps_a = g / p_vet
    eps_b = b_eff_fraction * b * math.sin(abs(beta_v)) / (math.pi * float(bl.mmn))
    return {"eps_valpha": eps_a, "eps_vbeta": eps_b, "eps_vgamma": eps_a + eps_b, "g_valpha": g, "p_vet": p_vet,
            "alpha_vet": alpha_vet}


def contact_ratio_warnings(bl, alpha_e: float | None = None) -> list[str]:
    """Warnings on low contact ratios (ISO 10300-1 values, b_eff = 0.85 b), each with the design-file key to change.

    Parameters
    ----------
    bl : BevelBlank
    alpha_e : float, rad, optional
        Pressure angle of the loaded side (see :func:`contact_ratios`).

    Returns
    -------
    list of str
        Empty when eps_valpha >= 1 and eps_vgamma >= 2.
    """
    cr = contact_ratios(bl, alpha_e)
    out = []
    if cr["eps_valpha"] < MIN_TRANSVERSE:
        out.append(f"transverse contact ratio eps_valpha = {cr['eps_valpha']:.3f} < {MIN_TRANSVERSE:g} (ISO 10300-1 "
                   "virtual gears): the profile alone does not hand over to the next tooth pair; increase "
                   "gear_set.pinion_teeth / gear_set.gear_teeth at the same size or lower "
                   "gear_set.normal_pressure_angle")
    if cr["eps_vgamma"] < MIN_TOTAL:
        need = cr["eps_vgamma"] - cr["eps_vbeta"]
        b = min(float(bl.b1), float(bl.b2))
        # eps_vbeta is proportional to the face width: the face width that reaches the total MIN_TOTAL
        b_need = b * (MIN_TOTAL - need) / cr["eps_vbeta"] if cr["eps_vbeta"] > 0 else math.inf
        beta_need = math.degrees(_spiral_angle_for_total(bl, b))
        hint = (f"gear_set.face_width to at least {b_need:.1f} mm or gear_set.mean_spiral_angle to at least "
                f"{math.ceil(beta_need)} deg" if b_need <= 0.3 * float(bl.Re2)
                else f"gear_set.mean_spiral_angle to at least {math.ceil(beta_need)} deg")
        out.append(f"low total contact ratio eps_vgamma = {cr['eps_vgamma']:.3f} < {MIN_TOTAL:g} (eps_valpha = "
                   f"{cr['eps_valpha']:.3f}, face contact ratio eps_vbeta = {cr['eps_vbeta']:.3f}, ISO 10300-1 "
                   f"with b_eff = 0.85 b): a single tooth pair carries the load over part of the mesh cycle; "
                   f"increase {hint}")
    return out


def _spiral_angle_for_total(bl, b: float) -> float:
    """Mean spiral angle (rad) at which eps_vgamma reaches MIN_TOTAL at the same mean transverse module, face width,
    tooth counts and depth factors.

    eps_vbeta = 0.85 b tan(beta_v) / (pi m_mt) at a fixed mean transverse module m_mt; eps_valpha falls as beta grows
    (m_mn = m_mt cos(beta) and the ISO mean addenda scale with m_mn), so the angle is iterated with the blank's normal
    module and addenda scaled by cos(beta) / cos(beta_m).
    """
    from types import SimpleNamespace

    beta0 = 0.5 * (float(bl.beta_m1) + float(bl.beta_m2))
    beta = beta0
    for _ in range(30):
        f = math.cos(beta) / math.cos(beta0)
        shim = SimpleNamespace(alpha_eD=bl.alpha_eD, beta_m1=beta, beta_m2=beta, dm1=bl.dm1, dm2=bl.dm2,
                               delta1=bl.delta1, delta2=bl.delta2, ham1=f * float(bl.ham1), ham2=f * float(bl.ham2),
                               mmn=f * float(bl.mmn), b1=b, b2=b)
        eps_a = contact_ratios(shim)["eps_valpha"]
        new = math.atan(max(MIN_TOTAL - eps_a, 0.0) * math.pi * float(bl.mmt) / (0.85 * b))
        if abs(new - beta) < 1e-6:
            break
        beta = new
    return beta
