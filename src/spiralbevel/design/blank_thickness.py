"""Tooth thickness, virtual spur gear, top land and lengthwise spiral angle of a face-milled bevel blank.

Small closed-form helpers used by :func:`spiralbevel.design.blank.compute_blank`. Scalars in, scalars out;
lengths mm, angles rad.

References
----------
ISO 23509:2016 (tooth thickness: x_hm1, x_smn, smn, chordal values; spiral angle of a face-milled tooth at any cone
distance); ISO 10300-1 (virtual cylindrical gear in the normal section, cos²βvb = 1 − sin²βm·cos²αn).
"""

from __future__ import annotations

import math

__all__ = [
    "spiral_angle_at",
    "virtual_normal_diameter",
    "mean_normal_thickness",
    "chordal_values",
    "tip_thickness",
    "undercut_limit_depth",
]


def _inv(a: float) -> float:
    return math.tan(a) - a


def spiral_angle_at(r: float, rm: float, beta_m: float, rc0: float) -> float | None:
    """Spiral angle of a face-milled (circular-arc) tooth trace at cone distance ``r``.

    Parameters
    ----------
    r : float, mm
        Cone distance of the section (Re at the heel, Ri at the toe).
    rm : float, mm
        Mean cone distance.
    beta_m : float, rad
        Spiral angle at Rm.
    rc0 : float, mm
        Cutter radius.

    Returns
    -------
    float or None, rad
        β = asin((2·Rm·rc0·sin βm + R² − Rm²) / (2·R·rc0)), or None when the cutter circle through the mean point
        does not reach the cone distance ``r`` (|argument| > 1).

    Notes
    -----
    In the crown (generating) gear plane the tooth trace is the circle of radius rc0 whose centre lies at the
    distance S from the crown centre, S² = Rm² + rc0² − 2·Rm·rc0·sin βm. At a point of the circle at distance R the
    angle between the tangent and the radius obeys sin β = (R² + rc0² − S²)/(2·R·rc0) (law of cosines); ISO 23509
    writes the same expression for βe and βi.
    """
    s = (2.0 * rm * rc0 * math.sin(beta_m) + r * r - rm * rm) / (2.0 * r * rc0)
    if abs(s) > 1.0:
        return None
    return math.asin(s)


def virtual_normal_diameter(r: float, delta: float, beta: float, cos2_alpha: float) -> float:
    """Reference diameter of the virtual spur gear in the normal section at cone distance ``r``.

    Parameters
    ----------
    r : float, mm
        Cone distance of the section.
    delta : float, rad
        Pitch angle.
    beta : float, rad
        Spiral angle at the section.
    cos2_alpha : float
        cos² of the normal pressure angle.

    Returns
    -------
    float, mm
        dvn = dv / (1 − sin²β·cos²αn) with the Tredgold diameter dv = 2·R·sin δ / cos δ (ISO 10300-1).
    """
    if abs(math.cos(delta)) < 1e-12:  # crown gear: the virtual gear is a rack
        return math.inf
    dv = 2.0 * r * math.tan(delta)
    return dv / (1.0 - math.sin(beta) ** 2 * cos2_alpha)


def mean_normal_thickness(
    mmn: float, x_hm1: float, x_smn: float, tan_aD: float, tan_aC: float, jmt_n: float
) -> tuple[float, float]:
    """Mean normal circular tooth thicknesses of pinion and wheel.

    Parameters
    ----------
    mmn : float, mm
        Mean normal module.
    x_hm1 : float
        Mean profile shift coefficient of the pinion, (ham1 − ham2)/(2·mmn).
    x_smn : float
        Thickness modification coefficient (the thickness factor k_t).
    tan_aD, tan_aC : float
        Tangents of the drive and coast normal pressure angles.
    jmt_n : float, mm
        Backlash as circular thickness reduction in the mean normal section (both members together), mm.

    Returns
    -------
    smn1, smn2 : float, mm
        smn1 = π·mmn/2 + mmn·(2·x_smn + x_hm1·(tan αnD + tan αnC)) − jmt_n/2 and smn2 = π·mmn − smn1 − jmt_n
        (ISO 23509 smn1 = 0.5·π·mmn + 2·mmn·(x_smn + x_hm1·tan αn) for equal flank angles; the backlash is taken
        half from each member).
    """
    s1 = 0.5 * math.pi * mmn + mmn * (2.0 * x_smn + x_hm1 * (tan_aD + tan_aC))
    s2 = math.pi * mmn - s1
    return s1 - 0.5 * jmt_n, s2 - 0.5 * jmt_n


def chordal_values(smn: float, ham: float, dvn: float) -> tuple[float, float]:
    """Mean normal chordal thickness and chordal addendum on the virtual spur gear.

    Parameters
    ----------
    smn : float, mm
        Mean normal circular thickness.
    ham : float, mm
        Mean addendum.
    dvn : float, mm
        Virtual normal reference diameter.

    Returns
    -------
    smnc, hamc : float, mm
        smnc = dvn·sin(smn/dvn), hamc = ham + dvn/2·(1 − cos(smn/dvn)).
    """
    if not math.isfinite(dvn):
        return smn, ham
    half = smn / dvn
    return dvn * math.sin(half), ham + 0.5 * dvn * (1.0 - math.cos(half))


def tip_thickness(d: float, s: float, ha: float, alpha_D: float, alpha_C: float) -> float:
    """Arc tooth thickness on the tip circle of a spur gear with (possibly unequal) flank pressure angles.

    Parameters
    ----------
    d : float, mm
        Reference diameter.
    s : float, mm
        Circular thickness on the reference circle.
    ha : float, mm
        Addendum.
    alpha_D, alpha_C : float, rad
        Pressure angles of the two flanks on the reference circle.

    Returns
    -------
    float, mm
        sa = da·(s/d + ½(inv αD − inv αaD) + ½(inv αC − inv αaC)), da = d + 2·ha, cos αa = d·cos α / da. Negative
        when the flanks cross below the tip (pointed tooth). For an infinite (or very large) diameter the rack
        value s − ha·(tan αD + tan αC).
    """
    if not d < 1e9 * (abs(s) + abs(ha) + 1.0):
        return s - ha * (math.tan(alpha_D) + math.tan(alpha_C))
    da = d + 2.0 * ha
    aaD = math.acos(min(1.0, d * math.cos(alpha_D) / da))
    aaC = math.acos(min(1.0, d * math.cos(alpha_C) / da))
    return da * (s / d + 0.5 * (_inv(alpha_D) - _inv(aaD)) + 0.5 * (_inv(alpha_C) - _inv(aaC)))


def undercut_limit_depth(dvn: float, alpha: float) -> float:
    """Depth below the pitch line down to which a straight-sided rack generates an involute without undercut.

    Parameters
    ----------
    dvn : float, mm
        Virtual normal reference diameter.
    alpha : float, rad
        Normal pressure angle of the flank.

    Returns
    -------
    float, mm
        (dvn/2)·sin²α: the rack line below the interference point (tangency of the line of action with the base
        circle) undercuts the flank.
    """
    return 0.5 * dvn * math.sin(alpha) ** 2
