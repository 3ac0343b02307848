"""Plausibility checks of a computed blank: impossible geometry (errors) and poor practice (warnings).

Criteria (all evaluated on the computed :class:`~spiralbevel.design.blank_result.BevelBlank`):

* **Face width** (warning): b2 > 0.3·Re2 or b2 > 10·met (ISO 23509 / AGMA design recommendation).
* **Dedendum / addendum** (error): a dedendum that is not positive at toe, mean point or heel, or a mean addendum
  that is negative; an addendum that vanishes at the toe; a root angle δf <= 0.
* **Pointed teeth**: the normal top land at the mean point (virtual spur gear in the normal section) must be positive
  (error); at the toe or heel, or below 0.2·m_n of the section anywhere, it is a warning. The toe and heel thickness
  follows the face-milling completing process (constant slot width at the root, :func:`normal_thickness`).
* **Undercut of the pinion**: virtual spur gear in the normal section (dvn, ISO 10300-1); a straight rack flank
  generates involute only down to h_lim = (dvn/2)·sin²αn (αn the smaller flank angle) below the pitch line.
  Error if the depth that must be active at the mean point, ham2 (the wheel's tip reaches it), exceeds h_lim;
  warning if the full mean dedendum hfm1 exceeds it (root undercut) or if the active depth exceeds it at the toe.
* **Toe depth** (warning): whole depth at the toe below half the mean whole depth (steep taper, small cutter).
* **Spiral angle** (warning): the toe spiral angle changes sign while βm > 0 (cutter radius small for the face).
* **Contact ratio** (warning, no hypoid offset): ISO 10300-1 virtual cylindrical gears, transverse contact ratio
  below 1 or total contact ratio below 2 (:mod:`~spiralbevel.design.contact_ratio`).
"""

from __future__ import annotations

import math

from ..errors import Problem
from .blank_result import BevelBlank
from .blank_thickness import tip_thickness, undercut_limit_depth, virtual_normal_diameter

__all__ = ["check_blank", "normal_thickness", "top_land", "section_limit_depth", "achieved_undercut",
           "achieved_top_land"]

_MEMBER = {1: "pinion", 2: "wheel"}
_MIN_TOPLAND = 0.2  # fraction of the normal module of the section


def _g(bl: BevelBlank, name: str, k: int):
    return getattr(bl, f"{name}{k}")


def _section(bl: BevelBlank, k: int, where: str) -> tuple[float, float, float, float]:
    """Cone distance, spiral angle, addendum and dedendum of member k at 'i' (toe), 'm' or 'e' (heel)."""
    if where == "m":
        return _rm(bl, k), _g(bl, "beta_m", k), _g(bl, "ham", k), _g(bl, "hfm", k)
    return (_g(bl, f"R{where}", k), _g(bl, f"beta_{where}", k), _g(bl, f"ha{where}", k), _g(bl, f"hf{where}", k))


def _rm(bl: BevelBlank, k: int) -> float:
    """Mean cone distance of member k (Rm for a = 0, Rm1 or Rm2 for a hypoid)."""
    return bl.Rm if bl.a == 0.0 else _g(bl, "Rm", k)


def _mmt(bl: BevelBlank, k: int) -> float:
    """Mean transverse module of member k (mmt for a = 0; dm_k/z_k for a hypoid, whose spiral angles differ)."""
    return bl.mmt if bl.a == 0.0 else _g(bl, "dm", k) / _g(bl, "z", k)


def _cos2_alpha(bl: BevelBlank) -> float:
    return math.cos(0.5 * (bl.alpha_nD + bl.alpha_nC)) ** 2


def normal_thickness(bl: BevelBlank, k: int, where: str) -> float:
    """Normal circular tooth thickness of member ``k`` on its pitch cone at ``where`` = 'i' (toe), 'm' or 'e' (heel).

    Parameters
    ----------
    bl : BevelBlank
        Computed blank.
    k : {1, 2}
        Member (1 pinion, 2 wheel).
    where : {"i", "m", "e"}
        Section: toe (Ri), mean point (Rm) or heel (Re).

    Returns
    -------
    float, mm
        s_n(R) = p_n(R) − e_n(R): normal circular pitch p_n(R) = π·mmt·(R/Rm)·cos β(R) minus the space width
        e_n(R) = (π·mmn − smn) + (hf(R) − hfm)·(tan αnD + tan αnC).

    Notes
    -----
    Face milling, completing process: the inner and outer blades of one head cut both flanks of a space and move on
    concentric circles of the generating crown gear, so the space width at the root (the cutter point width) is the
    same along the face; at the pitch line it is wider by the dedendum times the flank slopes. The duplex dedendum
    angle sum of ISO 23509 is exactly the condition that the two members' spaces then grow with the pitch to first
    order at the mean point (tests/design/test_blank_crosscheck.py checks this), which is why the same model gives
    the toe and heel thickness behind the AGMA 929-style top lands below.
    """
    r, beta, _ha, hf = _section(bl, k, where)
    pn = math.pi * _mmt(bl, k) * r / _rm(bl, k) * math.cos(beta)
    space_m = math.pi * bl.mmn - _g(bl, "smn", k)
    return pn - space_m - (hf - _g(bl, "hfm", k)) * (math.tan(bl.alpha_nD) + math.tan(bl.alpha_nC))


def top_land(bl: BevelBlank, k: int, where: str) -> float:
    """Normal top land width of member ``k`` (1, 2) at ``where`` = 'i' (toe), 'm' (mean) or 'e' (heel), mm.

    Tip thickness of the virtual spur gear in the normal section of that cone distance (see
    ``blank_thickness.tip_thickness``) with the pitch-line thickness of :func:`normal_thickness` and the local
    addendum.
    """
    r, beta, ha, _hf = _section(bl, k, where)
    delta = _g(bl, "delta", k)
    dvn = virtual_normal_diameter(r, delta, beta, _cos2_alpha(bl))
    return tip_thickness(dvn, normal_thickness(bl, k, where), ha, bl.alpha_nD, bl.alpha_nC)


def section_limit_depth(bl: BevelBlank, k: int, where: str) -> float:
    """Undercut limit depth (dvn/2)·sin²αn,min of member ``k`` at section ``where``, mm."""
    r, beta, _ha, _hf = _section(bl, k, where)
    dvn = virtual_normal_diameter(r, _g(bl, "delta", k), beta, _cos2_alpha(bl))
    return undercut_limit_depth(dvn, min(bl.alpha_nD, bl.alpha_nC))


def _thicker_tip(k: int) -> str:
    """Design-file keys that widen the top land of member ``k`` (k_t > 0 thickens the pinion and thins the wheel;
    c_ham above its default moves addendum from the pinion to the wheel)."""
    m = _MEMBER[k]
    way = "raise" if k == 1 else "lower"
    return (f"{way} gear_set.depth.thickness_factor (a thicker {m}) or {way} gear_set.depth.mean_addendum_factor "
            f"(a shorter {m} addendum)")


def check_blank(bl: BevelBlank) -> tuple[list[Problem], list[str]]:
    """Run every check.

    Parameters
    ----------
    bl : BevelBlank
        Computed blank (its ``warnings`` are ignored).

    Returns
    -------
    errors : list of Problem
        Impossible geometry; :func:`compute_blank` raises them as one ``GeometryError``.
    warnings : list of str
        Messages for :class:`~spiralbevel.errors.DesignWarning`.
    """
    err: list[Problem] = []
    warn: list[str] = []

    if bl.b2 > 0.3 * bl.Re2:
        warn.append(f"face width b2 = {bl.b2:.4g} mm exceeds 0.3*Re2 = {0.3 * bl.Re2:.4g} mm: lower "
                    "gear_set.face_width")
    if bl.b2 > 10.0 * bl.met:
        warn.append(f"face width b2 = {bl.b2:.4g} mm exceeds 10*met = {10.0 * bl.met:.4g} mm: lower "
                    "gear_set.face_width")

    for k in (1, 2):
        m = _MEMBER[k]
        for where, label in (("i", "toe"), ("m", "mean point"), ("e", "heel")):
            _r, _b, ha, hf = _section(bl, k, where)
            sym = "hfm" if where == "m" else f"hf{where}"
            if not hf > 0.0:
                err.append(Problem(f"{sym}{k}", round(hf, 6), "> 0", "mm",
                                   f"vanishing dedendum at the {label} of the {m}: reduce the dedendum angles "
                                   "(gear_set.depth.taper), gear_set.face_width or "
                                   "gear_set.depth.clearance_factor"))
            if where == "m" and not ha >= 0.0:
                err.append(Problem(f"ham{k}", round(ha, 6), ">= 0", "mm", f"negative mean addendum of the {m}: "
                                   "check gear_set.depth.mean_addendum_factor (c_ham) and "
                                   "gear_set.depth.depth_factor (k_d)"))
            if where == "i" and not ha > 0.0:
                err.append(Problem(f"hai{k}", round(ha, 6), "> 0", "mm",
                                   f"vanishing addendum at the toe of the {m}: reduce the addendum angle "
                                   "(gear_set.depth.taper) or gear_set.face_width"))
        df = _g(bl, "delta_f", k)
        if not df > 0.0:
            err.append(Problem(f"delta_f{k}", f"{math.degrees(df):.6g}", "> 0", "deg",
                               f"root angle of the {m} is not positive: dedendum angle larger than the pitch angle; "
                               "change gear_set.depth.taper (or its dedendum angles; duplex: a smaller "
                               "gear_set.cutter_radius lowers the taper)"))

    if err:  # the remaining checks need sound depths
        return err, warn

    for k in (1, 2):
        m = _MEMBER[k]
        for where, label in (("i", "toe"), ("m", "mean point"), ("e", "heel")):
            r, beta, _ha, _hf = _section(bl, k, where)
            sa = top_land(bl, k, where)
            mxn = _mmt(bl, k) * r / _rm(bl, k) * math.cos(beta)
            sym = f"sa{where}{k}"
            if not sa > 0.0:
                if where == "m":
                    err.append(Problem(sym, round(sa, 6), "> 0", "mm", f"pointed teeth: the {m} flanks meet below "
                                       f"the tip at the mean point; {_thicker_tip(k)}"))
                else:
                    warn.append(f"pointed teeth: top land of the {m} at the {label} {sym} = {sa:.4g} mm <= 0; "
                                f"{_thicker_tip(k)}, or lower gear_set.face_width")
            elif sa < _MIN_TOPLAND * mxn:
                warn.append(f"small top land of the {m} at the {label}: {sym} = {sa:.4g} mm < "
                            f"{_MIN_TOPLAND}*m_n = {_MIN_TOPLAND * mxn:.4g} mm; {_thicker_tip(k)}"
                            + ("" if where == "m" else ", or lower gear_set.face_width"))

    # undercut of the pinion (criterion in the module docstring)
    hlim_m = section_limit_depth(bl, 1, "m")
    if bl.ham2 > hlim_m:
        err.append(Problem("hlim1", round(hlim_m, 6), f">= ham2 = {bl.ham2:.6g}", "mm",
                           "pinion undercut: the active flank at the mean point reaches below the interference "
                           "point (dvn1/2)*sin^2(alpha_n); increase gear_set.pinion_teeth or "
                           "gear_set.normal_pressure_angle, or lengthen the pinion addendum (lower "
                           "gear_set.depth.mean_addendum_factor)"))
    elif bl.hfm1 > hlim_m:
        warn.append(f"pinion root undercut at the mean point: hfm1 = {bl.hfm1:.4g} mm > limit depth "
                    f"(dvn1/2)*sin^2(alpha_n) = {hlim_m:.4g} mm; increase gear_set.normal_pressure_angle or "
                    "gear_set.pinion_teeth to clear it")
    hlim_i = section_limit_depth(bl, 1, "i")
    active_i = bl.hfi1 - bl.c
    if active_i > hlim_i:
        warn.append(f"pinion undercut at the toe: active depth hfi1 - c = {active_i:.4g} mm > limit depth "
                    f"{hlim_i:.4g} mm; lower gear_set.face_width or increase gear_set.normal_pressure_angle or "
                    "gear_set.pinion_teeth")

    for k in (1, 2):
        hi = _g(bl, "hi", k)
        if hi < 0.5 * bl.hm:
            warn.append(f"whole depth of the {_MEMBER[k]} at the toe hi{k} = {hi:.4g} mm is less than half the mean "
                        f"whole depth hm = {bl.hm:.4g} mm (steep depthwise taper): lower gear_set.face_width or change "
                        "gear_set.depth.taper (duplex: a smaller gear_set.cutter_radius lowers the taper)")
    if bl.a == 0.0:
        from .contact_ratio import contact_ratio_warnings

        warn.extend(contact_ratio_warnings(bl))
    if bl.beta_m1 > 0.0 and bl.beta_i1 < 0.0:
        warn.append(f"the toe spiral angle changes sign (beta_i = {math.degrees(bl.beta_i1):.4g} deg): cutter radius "
                    f"rc0 = {bl.rc0:.4g} mm is small for this face width: raise gear_set.cutter_radius or lower "
                    "gear_set.face_width")
    return err, warn


def achieved_undercut(bl: BevelBlank, alpha_drive: float, alpha_coast: float) -> list[str]:
    """Pinion undercut at the mean point with the pressure angles the generated pinion flanks achieve.

    The same criterion as :func:`check_blank` (the active flank, down to the gear's mean addendum ham2, and the full
    dedendum hfm1 against the limit depth (dvn1/2) sin^2(alpha)), with alpha the smaller of the achieved mean-point
    normal pressure angles of the pinion's drive (concave) and coast (convex) flanks instead of the nominal one.

    Parameters
    ----------
    bl : BevelBlank
    alpha_drive, alpha_coast : float, rad
        Achieved mean-point normal pressure angles of the pinion concave and convex flanks.

    Returns
    -------
    list of str
        Warnings, each with the reason and the design-file key to change (empty: no undercut).
    """
    r, beta, _ha, _hf = _section(bl, 1, "m")
    dvn = virtual_normal_diameter(r, bl.delta1, beta, _cos2_alpha(bl))
    alpha = min(alpha_drive, alpha_coast)
    hlim = undercut_limit_depth(dvn, alpha)
    what = (f"at the achieved pinion pressure angle {math.degrees(alpha):.3f} deg (mean point): limit depth "
            f"(dvn1/2)*sin^2(alpha) = {hlim:.4g} mm")
    if bl.ham2 > hlim:
        return [f"pinion undercut {what} < gear addendum ham2 = {bl.ham2:.4g} mm: the active flank reaches below the "
                "interference point; increase gear_set.pinion_teeth or gear_set.normal_pressure_angle"]
    if bl.hfm1 > hlim:
        return [f"pinion root undercut {what} < dedendum hfm1 = {bl.hfm1:.4g} mm (below the active flank); "
                "increase gear_set.normal_pressure_angle to clear it"]
    return []


def achieved_top_land(bl: BevelBlank, k: int, alpha_drive: float, alpha_coast: float) -> list[str]:
    """Pointed teeth of member ``k`` at the mean point with the pressure angles its generated flanks achieve.

    The top land of :func:`top_land` at the mean point (virtual spur gear in the normal section, pitch-line thickness
    smn, mean addendum), with the achieved mean-point normal pressure angles of the member's drive and coast flanks
    instead of the nominal ones: a flank generated steeper than designed thins the tooth toward its tip.

    Parameters
    ----------
    bl : BevelBlank
    k : {1, 2}
        Member (1 pinion, 2 wheel).
    alpha_drive, alpha_coast : float, rad
        Achieved mean-point normal pressure angles of the drive flank (pinion concave, gear convex) and the coast
        flank (pinion convex, gear concave).

    Returns
    -------
    list of str
        A warning with the top land, the limit and the design-file keys to change; empty when the top land is at
        least 0.2 m_n.
    """
    r, beta, ha, _hf = _section(bl, k, "m")
    dvn = virtual_normal_diameter(r, _g(bl, "delta", k), beta, _cos2_alpha(bl))
    sa = tip_thickness(dvn, _g(bl, "smn", k), ha, alpha_drive, alpha_coast)
    limit = _MIN_TOPLAND * _mmt(bl, k) * math.cos(beta)
    if sa >= limit:
        return []
    m = _MEMBER[k]
    what = "pointed teeth" if sa <= 0.0 else "small top land"
    # k_t > 0 thickens the pinion and thins the wheel; c_ham > its default moves addendum from the pinion to the wheel
    thicker, shorter = ("raise", "raise") if k == 1 else ("lower", "lower")
    return [f"{what} of the {m} at the achieved pressure angles {math.degrees(alpha_drive):.3f} / "
            f"{math.degrees(alpha_coast):.3f} deg (drive / coast, mean point): top land sam{k} = {sa:.4g} mm < "
            f"{_MIN_TOPLAND}*m_n = {limit:.4g} mm; {thicker} gear_set.depth.thickness_factor (a thicker {m}), "
            f"{shorter} gear_set.depth.mean_addendum_factor (a shorter {m} addendum) or lower "
            "gear_set.normal_pressure_angle"]
