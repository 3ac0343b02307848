"""Load factors of ISO 10300-1 for a bevel pair: K_v (Method B), K_Hbeta, K_Fbeta, K_Halpha, K_Falpha.

Forces N, lengths mm, deviations um, stiffnesses N/(mm um), speeds 1/min.
"""

from __future__ import annotations

import math

from ._blank import BlankData

__all__ = ["nominal_forces", "running_in", "dynamic_factor", "face_load_factors", "transverse_load_factor"]

C_PRIME = 14.0   # single stiffness c', N/(mm um)
C_GAMMA = 20.0   # mesh stiffness c_gamma, N/(mm um)

# ISO 10300-1 mounting factor K_Hbeta-be: [contact pattern][mounting]
K_HBETA_BE = {
    "full-load": {"both-straddle": 1.00, "one-cantilever": 1.00, "both-cantilever": 1.00},
    "light-load": {"both-straddle": 1.05, "one-cantilever": 1.10, "both-cantilever": 1.25},
    "sample-estimated": {"both-straddle": 1.20, "one-cantilever": 1.32, "both-cantilever": 1.50},
}


def nominal_forces(g: BlankData, T1: float, n1: float) -> dict:
    """Nominal tangential force and pitch line velocity at the mean point.

    Returns
    -------
    dict
        ``F_mt1`` = 2000 T1/dm1 (N, T1 in N m); ``F_vmt`` = F_mt1 cos(beta_v)/cos(beta_m1), the tangential force of
        the virtual gear (the same normal force in the pitch plane at the mean spiral angle beta_v; = F_mt1 without
        offset); ``v_mt`` = pi dm1 n1/60000 and ``v_mt2`` = pi dm2 n2/60000 (m/s), the pitch line velocities of
        pinion and wheel at the mean point (equal without offset; a hypoid pinion's is larger by
        cos(beta_m2)/cos(beta_m1)).
    """
    F_mt1 = 2000.0 * T1 / g.dm1
    beta_v = 0.5 * (g.beta_m1 + g.beta_m2)
    n2 = n1 * g.z1 / g.z2
    return {"F_mt1": F_mt1, "F_vmt": F_mt1 * math.cos(beta_v) / math.cos(g.beta_m1),
            "v_mt": math.pi * g.dm1 * n1 / 60000.0, "v_mt2": math.pi * g.dm2 * n2 / 60000.0}


def running_in(f_pt: float, material: str, sigma_Hlim: float, v: float) -> float:
    """Running-in allowance y_alpha = y_p, um, of the pitch deviation ``f_pt`` (um) (ISO 10300-1 as ISO 6336-1).

    Case-hardened: 0.075 f_pt, at most 3 um. Through-hardened: 160/sigma_Hlim f_pt, at most 12800/sigma_Hlim for
    5 < v <= 10 m/s and 6400/sigma_Hlim above.
    """
    if material == "case-hardened":
        return min(0.075 * f_pt, 3.0)
    y = 160.0 / sigma_Hlim * f_pt
    if v > 10.0:
        return min(y, 6400.0 / sigma_Hlim)
    if v > 5.0:
        return min(y, 12800.0 / sigma_Hlim)
    return y


def _cv(eps_vgamma: float) -> dict:
    e = eps_vgamma
    big = e > 2.0
    cv1 = 0.32
    cv2 = 0.57 / (e - 0.3) if big else 0.34
    cv3 = 0.096 / (e - 1.56) if big else 0.23
    cv4 = (0.57 - 0.05 * e) / (e - 1.44) if big else 0.90
    cv5 = 0.47
    cv6 = 0.12 / (e - 1.74) if big else 0.47
    if e <= 1.5:
        cv7 = 0.75
    elif e <= 2.5:
        cv7 = 0.125 * math.sin(math.pi * (e - 2.0)) + 0.875
    else:
        cv7 = 1.0
    return {"c_v1": cv1, "c_v2": cv2, "c_v3": cv3, "c_v4": cv4, "c_v5": cv5, "c_v6": cv6, "c_v7": cv7}


def dynamic_factor(g: BlankData, v: dict, F_mt1: float, K_A: float, n1: float, f_p_eff: float,
                   density: float) -> dict:
    """Dynamic factor K_v, Method B (resonance ratio N = n1/n_E1).

    Parameters
    ----------
    g : BlankData
    v : dict
        Virtual gears (:func:`~spiralbevel.rating.virtual.virtual_gears`).
    F_mt1 : float, N
        Tangential force of the virtual gear, F_vmt (= F_mt1 without offset).
    K_A : float
    n1 : float, 1/min
    f_p_eff : float, um
        Effective pitch deviation f_pt - y_p (the larger f_pt of the pair).
    density : float, kg/mm^3

    Returns
    -------
    dict
        ``m_red`` (kg/mm), ``n_E1`` (1/min), ``N``, ``K_v`` and the c_v coefficients.

    Notes
    -----
    m_red = pi rho dm1^2/(8 cos^2 alpha_n) u^2/(1 + u^2), the masses of both members per unit face width reduced to
    the line of action; n_E1 = 30000/(pi z1) sqrt(c_gamma/m_red) with c_gamma = 20 N/(mm um); with the load term
    B = b c' f_p,eff/(F_mt K_A), c' = 14 N/(mm um) and F_mt K_A/b at least 100 N/mm:
    subcritical N <= 0.75: K_v = N (B c_v12 + c_v3) + 1; main resonance 0.75 < N <= 1.25: K_v = B c_v12 + c_v4 + 1;
    supercritical N >= 1.5: K_v = B c_v56 + c_v7; linear between 1.25 and 1.5.
    """
    u = g.z2 / g.z1
    m_red = math.pi * density * g.dm1 ** 2 / (8.0 * math.cos(g.alpha_nD) ** 2) * u * u / (1.0 + u * u)
    n_E1 = 30000.0 / (math.pi * g.z1) * math.sqrt(C_GAMMA / m_red)
    N = n1 / n_E1
    c = _cv(v["eps_vgamma"])
    line_load = max(F_mt1 * K_A / v["b_v"], 100.0)
    B = C_PRIME * f_p_eff / line_load
    c12, c56 = c["c_v1"] + c["c_v2"], c["c_v5"] + c["c_v6"]

    def sub(n):
        return n * (B * c12 + c["c_v3"]) + 1.0

    main = B * c12 + c["c_v4"] + 1.0
    sup = B * c56 + c["c_v7"]
    if N <= 0.75:
        K_v = sub(N)
    elif N <= 1.25:
        K_v = main
    elif N < 1.5:
        K_v = main + (sup - main) * (N - 1.25) / 0.25
    else:
        K_v = sup
    return {"m_red": m_red, "n_E1": n_E1, "N": N, "K_v": K_v, **c}


def face_load_factors(g: BlankData, mounting: str, contact_pattern: str) -> dict:
    """Face load factors K_Hbeta = 1.5 K_Hbeta-be and K_Fbeta = K_Hbeta/K_F0.

    Notes
    -----
    K_F0, the lengthwise curvature factor of spiral bevel gears, is 0.211 (rc0/Rm2)^q + 0.789 with
    q = 0.279/log10(sin beta_m2), limited to 1 ... 1.15 (1 for beta_m2 = 0): the wheel's mean cone distance and
    spiral angle (Rm2 = Rm, beta_m2 = beta_m without offset).
    """
    K_be = K_HBETA_BE[contact_pattern][mounting]
    K_Hbeta = 1.5 * K_be
    beta = g.beta_m2
    Rm2 = g.Rm2 if g.Rm2 > 0.0 else g.Rm
    if beta > 1e-9:
        q = 0.279 / math.log10(math.sin(beta))
        K_F0 = min(max(0.211 * (g.rc0 / Rm2) ** q + 0.789, 1.0), 1.15)
    else:
        K_F0 = 1.0
    return {"K_Hbeta-be": K_be, "K_Hbeta": K_Hbeta, "K_F0": K_F0, "K_Fbeta": K_Hbeta / K_F0}


def transverse_load_factor(v: dict, F_mtH: float, f_pt: float, y_alpha: float, Z_LS: float, Y_eps: float,
                           a_rel: float = 0.0) -> dict:
    """Transverse load factors K_Halpha and K_Falpha (Method B).

    Parameters
    ----------
    v : dict
        Virtual gears.
    F_mtH : float, N
        F_mt1 K_A K_v K_Hbeta.
    f_pt : float, um
        The larger single pitch deviation of the pair.
    y_alpha : float, um
        Running-in allowance.
    Z_LS, Y_eps : float
        Load sharing and contact ratio factors (for the upper limits).
    a_rel : float
        Relative hypoid offset 2|a|/dm2 (0 without offset).

    Notes
    -----
    X = c_gamma (f_pt - y_alpha)/(F_mtH/b); eps_vgamma <= 2: K = eps_vgamma/2 (0.9 + 0.4 X); eps_vgamma > 2:
    K = 0.9 + 0.4 sqrt(2 (eps_vgamma - 1)/eps_vgamma) X. K_Halpha = K limited to 1 ... eps_vgamma/(eps_valpha Z_LS^2);
    K_Falpha = K limited to 1 ... eps_vgamma/(eps_valpha Y_eps). A hypoid pair's lengthwise sliding evens out the
    pitch deviations: with a_rel = 2|a|/dm2 both factors fall linearly from these values at a_rel = 0 to 1 at
    a_rel >= 0.1 (K - (K - 1) min(a_rel/0.1, 1); ``K_Halpha*``, ``K_Falpha*`` are the values before). This is
    the reading that gives ISO/TR 10300-30 Sample 2's K_Halpha = 1.000 at a_rel = 0.211 (docs/rating.md).
    """
    e, ea = v["eps_vgamma"], v["eps_valpha"]
    X = C_GAMMA * (f_pt - y_alpha) / (F_mtH / v["b_v"])
    K = e / 2.0 * (0.9 + 0.4 * X) if e <= 2.0 else 0.9 + 0.4 * math.sqrt(2.0 * (e - 1.0) / e) * X
    KH = min(max(K, 1.0), e / (ea * Z_LS ** 2))
    KF = min(max(K, 1.0), e / (ea * Y_eps))
    w = min(a_rel / 0.1, 1.0)
    return {"K_Halpha": KH - (KH - 1.0) * w, "K_Falpha": KF - (KF - 1.0) * w, "K_Halpha*": KH, "K_Falpha*": KF,
            "a_rel": a_rel}
