"""Contact lines in the zone of action of the virtual cylindrical gear (ISO 10300-1, Annex A, Method B1).

The zone of action of the virtual helical gear is a rectangle: g_valpha along the transverse path of contact by
b_veff across the face. The contact lines cross it inclined at the base helix angle beta_vb, one transverse base pitch
p_vet apart along the path (p_vet cos(beta_vb) apart normal to the lines). On a hypoid pair the tip and root
boundaries of the zone are inclined at gamma to the face (a parallelogram, still symmetric about its centre;
``gamma`` = 0 without offset). Method B1 follows three of them: the
middle line (distance f_m from the centre of the zone, measured normal to the lines) and its neighbours towards the
tip (f_t) and the root (f_r). Lengths mm.
"""

from __future__ import annotations

import math

__all__ = ["contact_line_layout", "contact_line_length"]


def contact_line_layout(v: dict) -> dict:
    """Distances of the middle, tip and root contact lines from the centre of the zone of action, and f_max.

    Parameters
    ----------
    v : dict
        Virtual gear quantities (``g_valpha, b_veff, beta_vb, p_vet, eps_valpha, eps_vbeta``, optionally ``gamma``;
        mm, rad).

    Returns
    -------
    dict
        ``f_max`` (distance of the farthest corner of the zone of action from its centre, normal to the contact
        lines), ``f_m``, ``f_t``, ``f_r`` (signed distances of the middle, tip and root contact lines), mm.

    Notes
    -----
    f_max = (g_valpha + b_veff (tan(gamma) + tan(beta_vb))) cos(beta_vb) / 2: the normal distance of the corner
    (face end, tip boundary) farthest from the centre; the other pair of corners lies at
    (g_valpha - b_veff (tan(gamma) + tan(beta_vb))) cos(beta_vb) / 2, never farther. For eps_vbeta >= 1 the middle
    line runs through the centre (f_m = 0) and f_t,r = +-p_vet cos(beta_vb); for eps_vbeta < 1 all three lines are
    shifted by -X, X = p_vet (1 - eps_valpha/2) cos(beta_vb) (1 - eps_vbeta), which vanishes at eps_vbeta = 1
    (continuous).
    """
    cb = math.cos(v["beta_vb"])
    tg = math.tan(v.get("gamma", 0.0)) + math.tan(v["beta_vb"])
    f_max = max(abs(0.5 * (v["g_valpha"] + v["b_veff"] * tg) * cb),
                abs(0.5 * (v["g_valpha"] - v["b_veff"] * tg) * cb))
    step = v["p_vet"] * cb
    eb = v["eps_vbeta"]
    shift = 0.0 if eb >= 1.0 else v["p_vet"] * (1.0 - 0.5 * v["eps_valpha"]) * cb * (1.0 - eb)
    return {"f_max": f_max, "f_m": -shift, "f_t": step - shift, "f_r": -step - shift}


def contact_line_length(f: float, v: dict, f_max: float) -> float:
    """Length l_b of the contact line at distance f from the centre of the zone of action, inside the contact
    pattern of Method B1.

    Parameters
    ----------
    f : float, mm
        Signed distance of the line from the centre of the zone of action, normal to the contact lines.
    v : dict
        Virtual gear quantities (``g_valpha, b_veff, b_v, beta_vb``, optionally ``gamma``; mm, rad).
    f_max : float, mm
        See :func:`contact_line_layout`.

    Returns
    -------
    float, mm
        l_b >= 0 (0 at and beyond f_max).

    Notes
    -----
    l_b0, the line between the tip and root boundaries of the zone of action, is
    g_valpha/(cos(beta_vb) (tan(gamma) + tan(beta_vb))) (g_valpha/sin(beta_vb) without offset; b_veff for
    beta_vb = gamma = 0). The contact pattern shortens it to l_b = l_b0 (1 - C_lb) with
    C_lb = sqrt((f/f_max)^2 + k^2 (1 - (f/f_max)^2)), k = 1 - sqrt(b_veff/b_v): on the middle line
    l_bm = l_b0 sqrt(b_veff/b_v), and the line shrinks to nothing at the corner of the zone (f = f_max). The middle
    line's length is that of ISO 10300-1 and reproduces ISO/TR 10300-30 Sample 1 (22.442 mm); the form of C_lb away
    from the middle line is the one that reproduces that report's load sharing factor (see docs/rating.md).
    """
    bvb = v["beta_vb"]
    tg = math.tan(v.get("gamma", 0.0)) + math.tan(bvb)
    l_b0 = v["g_valpha"] / (math.cos(bvb) * tg) if tg > 0.0 else v["b_veff"]
    r2 = min((f / f_max) ** 2, 1.0) if f_max > 0.0 else 0.0
    k = 1.0 - math.sqrt(v["b_veff"] / v["b_v"])
    return l_b0 * (1.0 - math.sqrt(r2 + k * k * (1.0 - r2)))
