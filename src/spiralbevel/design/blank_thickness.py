"""Tooth thickness, virtual spur gear, top land and lengthwise spiral angle of a face-milled bevel blank.

Small closed-form helpers used by :func:`spiralbevel.design.blank.compute_blank`. Scalars in, scalars out;
lengths mm, angles rad.

References
----------
ISO 23509:2016 (tooth thickness: x_hm1, x_smn, x_sm1, x_sm2, smn, chordal values; spiral angle of a face-milled
tooth at any cone distance); ISO 10300-1 (virtual cylindrical gear in the normal section, cos²βvb = 1 − sin²βm·cos²αn).
"""

from __future__ import annotations

import math

__all__ = [
    "spiral_angle_at",
    "virtual_normal_diameter",
    "thickness_modification_coefficients",
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


def thickness_modification_coefficients(
    x_smn: float, jen: float, mmn: float, rm: float, re2: float, beta_m: float, beta_e2: float, alpha_n: float
) -> tuple[float, float]:
    """Thickness modification coefficients of pinion and wheel with the backlash allowance (ISO 23509).

    Parameters
    ----------
    x_smn : float
        Theoretical thickness modification coefficient (data type II: k_t / 2).
    jen : float, mm
        Outer normal backlash.
    mmn : float, mm
        Mean normal module.
    rm, re2 : float, mm
        Mean and outer cone distance of the wheel.
    beta_m, beta_e2 : float, rad
        Mean spiral angle and outer spiral angle of the wheel.
    alpha_n : float, rad
        Mean normal pressure angle (αnD + αnC)/2.

    Returns
    -------
    x_sm1, x_sm2 : float
        x_sm1 = x_smn − Δx and x_sm2 = −x_smn − Δx with Δx = jen·Rm·cos βm / (4·mmn·cos αn·Re2·cos βe2): the
        outer normal backlash is scaled to the mean point (Rm/Re2, cos βm/cos βe2), turned into a circular thickness
        in the normal section (1/cos αn) and taken half from each member.
    """
    dx = jen * rm * math.cos(beta_m) / (4.0 * mmn * math.cos(alpha_n) * re2 * math.cos(beta_e2))
    return x_smn - dx, -x_smn - dx


def mean_normal_thickness(mmn: float, x_hm1: float, x_sm1: float, x_sm2: float, alpha_n: float) -> tuple[float, float]:
    """Mean normal circular tooth thicknesses of pinion and wheel (ISO 23509), backlash included.

    Parameters
    ----------
    mmn : float, mm
        Mean normal module.
    x_hm1 : float
        Mean profile shift coefficient of the pinion, (ham1 − ham2)/(2·mmn).
    x_sm1, x_sm2 : float
        Thickness modification coefficients with backlash (:func:`thickness_modification_coefficients`).
    alpha_n : float, rad
        Mean normal pressure angle (αnD + αnC)/2.

    Returns
    -------
    smn1, smn2 : float, mm
        smn1 = π·mmn/2 + 2·mmn·(x_sm1 + x_hm1·tan αn), smn2 = π·mmn/2 + 2·mmn·(x_sm2 − x_hm1·tan αn).

    Notes
    -----
    The basic crown-gear (rack) argument: a profile shift x·m widens the tooth on the pitch line by
    x·m·(tan αD + tan αC); the standard writes 2·x·m·tan αn with the mean angle, which is the same for equal flank
    angles and differs by about 0.2 % of the shift term for αD − αC = 5°.
    """
    t = math.tan(alpha_n)
    return (0.5 * math.pi * mmn + 2.0 * mmn * (x_sm1 + x_hm1 * t),
            0.5 * math.pi * mmn + 2.0 * mmn * (x_sm2 - x_hm1 * t))


def chordal_values(smn: float, ham: float, dvn: float, delta: float) -> tuple[float, float]:
    """Mean normal chordal thickness and mean chordal addendum (ISO 23509).

    Parameters
    ----------
    smn : float, mm
        Mean normal circular thickness.
    ham : float, mm
        Mean addendum.
    dvn : float, mm
        Virtual normal reference diameter d_vn = dm / ((1 − sin²βm·cos²αn)·cos δ).
    delta : float, rad
        Pitch angle.

    Returns
    -------
    smnc, hamc : float, mm
        smnc = dvn·sin(smn/dvn); hamc = ham + ½·dvn·cos δ·(1 − cos(smn/dvn)). The standard takes the chord on the
        virtual gear and scales its sagitta with cos δ (like the Gleason chordal addendum a + t²·cos δ/(4·d) with the
        transverse pitch diameter d); for a crown wheel (δ = 90°) hamc = ham.
    """
    if not math.isfinite(dvn):
        return smn, ham
    half = smn / dvn
    return dvn * math.sin(half), ham + 0.5 * dvn * math.cos(delta) * (1.0 - math.cos(half))


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
