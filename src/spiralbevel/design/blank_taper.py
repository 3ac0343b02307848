"""Depthwise taper of a spiral bevel pair without offset: addendum and dedendum angles (ISO 23509 Method 0).

All five taper systems use uniform clearance, θa1 = θf2 and θa2 = θf1: the face cone of each member is parallel to
the root cone of its mate (ISO 23509:2016, dedendum and addendum angles, a = 0).

References
----------
ISO 23509:2016 Annex C (addendum and dedendum angles of the wheel), dedendum angle sums ΣθfS (standard depth),
ΣθfC (constant slot width: duplex, face milling, completing), ΣθfM = min(ΣθfC, 1.3·ΣθfS) (modified slot width,
Gleason's tilted root line, TRL), ΣθfU = 0 (uniform depth); Annex F.2 Sample 1 (ΣθfC = 8.6277°).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = [
    "TaperAngles",
    "dedendum_angle_sum_standard",
    "dedendum_angle_sum_duplex",
    "dedendum_angle_sum_modified",
    "taper_angles",
]


@dataclass(frozen=True)
class TaperAngles:
    """Addendum and dedendum angles of both members, rad, plus the dedendum angle sums for reference.

    Attributes
    ----------
    theta_a1, theta_a2, theta_f1, theta_f2 : float, rad
        Addendum and dedendum angles.
    sum_theta_fS : float, rad
        Dedendum angle sum of the standard taper (computed for every taper, used by the checks).
    sum_theta_fC : float, rad
        Dedendum angle sum of the duplex taper for the given cutter radius.
    sum_theta_fM : float, rad
        Dedendum angle sum of the tilted root line (modified slot width) taper, min(ΣθfC, 1.3·ΣθfS).
    """

    theta_a1: float
    theta_a2: float
    theta_f1: float
    theta_f2: float
    sum_theta_fS: float
    sum_theta_fC: float
    sum_theta_fM: float


def dedendum_angle_sum_standard(hfm1: float, hfm2: float, rm: float) -> float:
    """Dedendum angle sum of the standard depth taper (root lines through the pitch apex).

    Parameters
    ----------
    hfm1, hfm2 : float, mm
        Mean dedenda of pinion and wheel.
    rm : float, mm
        Mean cone distance.

    Returns
    -------
    float, rad
        ΣθfS = atan(hfm1/Rm) + atan(hfm2/Rm) (ISO 23509, standard taper, a = 0).
    """
    return math.atan(hfm1 / rm) + math.atan(hfm2 / rm)


def dedendum_angle_sum_duplex(met: float, re: float, rm: float, beta_m: float, tan_alpha: float, rc0: float) -> float:
    """Dedendum angle sum of the duplex taper (face milling, completing process).

    Parameters
    ----------
    met : float, mm
        Outer transverse module of the wheel.
    re, rm : float, mm
        Outer and mean cone distances of the wheel.
    beta_m : float, rad
        Mean spiral angle.
    tan_alpha : float
        Tangent of the normal pressure angle; for unequal flank angles ISO 23509 takes the mean angle
        αn = (αnD + αnC)/2 (the slot-width argument behind the formula would give (tan αnD + tan αnC)/2, larger by
        about 0.2 % for αnD − αnC = 5°).
    rc0 : float, mm
        Cutter radius.

    Returns
    -------
    float, rad
        ΣθfC = (π·met / (2·Re·tan αn·cos βm))·(1 − Rm·sin βm / rc0); in degrees the standard writes the factor
        90 instead of π/2 (ISO 23509 duplex taper; ISO 23509:2016 Annex F, Sample 1 gives 8.6277°).
    """
    return (0.5 * math.pi * met / (re * tan_alpha * math.cos(beta_m))) * (1.0 - rm * math.sin(beta_m) / rc0)


def dedendum_angle_sum_modified(sum_standard: float, sum_duplex: float) -> float:
    """Dedendum angle sum of the tilted root line taper (ISO 23509 Annex C: modified slot width).

    Parameters
    ----------
    sum_standard, sum_duplex : float, rad
        ΣθfS and ΣθfC.

    Returns
    -------
    float, rad
        ΣθfM = min(ΣθfC, 1.3·ΣθfS): the duplex taper, with the root line tilted about the mean point where the
        constant-slot-width sum would exceed 1.3 times the standard one (small cutters, wide faces); the slot width
        then varies along the face.
    """
    return min(sum_duplex, 1.3 * sum_standard)


def taper_angles(
    taper: str,
    *,
    hfm1: float,
    hfm2: float,
    rm: float,
    re2: float,
    met: float,
    beta_m: float,
    tan_alpha: float,
    rc0: float,
    c_ham: float,
    given: dict[str, float | None] | None = None,
) -> TaperAngles:
    """Addendum and dedendum angles for a taper system (uniform clearance).

    Parameters
    ----------
    taper : {"duplex", "trl", "standard", "uniform", "given"}
        Taper system (``"trl"``: tilted root line, ISO modified slot width).
    hfm1, hfm2 : float, mm
        Mean dedenda.
    rm, re2 : float, mm
        Mean cone distance and outer cone distance of the wheel.
    met : float, mm
        Outer transverse module.
    beta_m : float, rad
        Mean spiral angle.
    tan_alpha : float
        Tangent of the mean normal pressure angle (αnD + αnC)/2.
    rc0 : float, mm
        Cutter radius.
    c_ham : float
        Mean addendum factor; the duplex and TRL sums Σ are split θf1 = c_ham·Σ, θf2 = (1 − c_ham)·Σ (the standard's
        θa2 = Σ·ham2/hmw).
    given : dict or None
        ``theta_a1 .. theta_f2`` (rad or None) for ``taper="given"``; θf1 from θf1 or θa2, θf2 from θf2 or θa1.

    Returns
    -------
    TaperAngles
    """
    s_std = dedendum_angle_sum_standard(hfm1, hfm2, rm)
    s_dup = dedendum_angle_sum_duplex(met, re2, rm, beta_m, tan_alpha, rc0)
    if taper == "standard":
        tf1, tf2 = math.atan(hfm1 / rm), math.atan(hfm2 / rm)
    elif taper == "uniform":
        tf1 = tf2 = 0.0
    elif taper == "duplex":
        tf1, tf2 = c_ham * s_dup, (1.0 - c_ham) * s_dup
    elif taper == "trl":
        s_mod = dedendum_angle_sum_modified(s_std, s_dup)
        tf1, tf2 = c_ham * s_mod, (1.0 - c_ham) * s_mod
    elif taper == "given":
        g = given or {}
        f1 = g.get("theta_f1") if g.get("theta_f1") is not None else g.get("theta_a2")
        f2 = g.get("theta_f2") if g.get("theta_f2") is not None else g.get("theta_a1")
        if f1 is None or f2 is None:
            raise ValueError('taper "given" needs theta_f1 or theta_a2, and theta_f2 or theta_a1')
        tf1, tf2 = float(f1), float(f2)
    else:  # pragma: no cover - BlankInput validates the name
        raise ValueError(taper)
    return TaperAngles(theta_a1=tf2, theta_a2=tf1, theta_f1=tf1, theta_f2=tf2, sum_theta_fS=s_std, sum_theta_fC=s_dup,
                       sum_theta_fM=dedendum_angle_sum_modified(s_std, s_dup))
