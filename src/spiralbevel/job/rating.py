"""Design file -> ISO 10300 rating (``spiralbevel rate`` and the ``rating`` section of report.json).

Problems are reported with design-file field paths (``rating.pinion_speed`` ...).
"""

from __future__ import annotations

import math

from ..conventions import Member, Side
from ..errors import DesignError, Problem
from ..io.design_schema import DesignFile

__all__ = ["rating_input_from_design", "rating_from_design", "rating_report", "rating_ltca_report"]

# RatingInput field -> design-file path
FIELD_PATHS = {
    "T1": "rating.pinion_torque", "n1": "rating.pinion_speed", "K_A": "rating.application_factor",
    "f_pt": "rating.pitch_deviation", "rho_a0": "rating.cutter_edge_radius", "sigma_Hlim": "rating.sigma_Hlim",
    "sigma_Flim": "rating.sigma_Flim", "nu40": "rating.oil_viscosity", "Rz_flank": "rating.flank_roughness",
    "Rz_root": "rating.root_roughness", "mounting": "rating.mounting", "contact_pattern": "rating.contact_pattern",
    "profile_crowning": "rating.profile_crowning",
    "E": "rating.youngs_modulus", "nu": "rating.poisson_ratio", "density": "rating.density",
    "S_Hmin": "rating.S_Hmin", "S_Fmin": "rating.S_Fmin", "material": "rating.material",
    "load_cycles": "rating.load_cycles",
}


def _edge_radius(spec: DesignFile, blank, member: Member) -> float:
    """Edge radius of the cutter that cuts the root of ``member``'s drive flank (pinion concave, gear convex)."""
    side = Side.CONCAVE if member is Member.PINION else Side.CONVEX
    given = getattr(spec.face_milling, f"{member.value}_{side.value}").cutter
    if spec.flank.kind == "face-milled" and given is not None:
        return given.edge_radius
    from .facemilled import _default_cutter

    try:
        return _default_cutter(spec, blank, member, side).edge_radius
    except DesignError as err:
        raise DesignError([Problem("rating.cutter_edge_radius", "<missing>", "[rho_a01, rho_a02] > 0", "mm",
                                   f"no cutter of the {member.value} to take it from: {err}")]) from err


def rating_input_from_design(spec: DesignFile, blank):
    """The :class:`~spiralbevel.rating.RatingInput` of a design file's ``[rating]`` section."""
    from ..rating import RatingInput, pitch_deviation_from_grade

    r = spec.rating
    if r is None:
        raise DesignError.single("rating", "<missing>", "a [rating] section", "", "the design has no [rating] section")
    T1 = r.pinion_torque if r.pinion_torque is not None else 30000.0 * r.power / (math.pi * r.pinion_speed)  # type: ignore[operator]  # schema: one is set
    if r.pitch_deviation is not None:
        f_pt = tuple(r.pitch_deviation)
    else:
        grade = r.accuracy_grade
        assert grade is not None  # the schema requires exactly one of pitch_deviation and accuracy_grade
        f_pt = (pitch_deviation_from_grade(grade, blank.dm1, blank.mmn),
                pitch_deviation_from_grade(grade, blank.dm2, blank.mmn))
    rho = tuple(r.cutter_edge_radius) if r.cutter_edge_radius is not None else (
        _edge_radius(spec, blank, Member.PINION), _edge_radius(spec, blank, Member.GEAR))
    try:
        return RatingInput(
            T1=T1, n1=r.pinion_speed, f_pt=f_pt, rho_a0=rho, sigma_Hlim=tuple(r.sigma_Hlim),
            sigma_Flim=tuple(r.sigma_Flim), nu40=r.oil_viscosity, Rz_flank=tuple(r.flank_roughness),
            Rz_root=tuple(r.root_roughness), K_A=r.application_factor, mounting=r.mounting,
            contact_pattern=r.contact_pattern, profile_crowning=r.profile_crowning, E=r.youngs_modulus,
            nu=r.poisson_ratio, density=r.density,
            S_Hmin=r.S_Hmin, S_Fmin=r.S_Fmin, material=r.material, load_cycles=r.load_cycles)
    except DesignError as err:
        raise DesignError([Problem(FIELD_PATHS.get(p.field, p.field), p.value, p.allowed, p.unit, p.reason)
                           for p in err.problems]) from err


def rating_from_design(spec: DesignFile, blank=None):
    """ISO 10300 Method B1 rating (:class:`~spiralbevel.rating.RatingResult`) of a design file."""
    from ..rating import rate_iso10300
    from .blank import blank_from_design

    if blank is None:
        blank = blank_from_design(spec)
    return rate_iso10300(blank, rating_input_from_design(spec, blank))


def rating_report(spec: DesignFile, blank, report: dict, summary) -> None:
    """Add the ``rating`` section to ``report`` when the design has ``[rating]`` (hook of the run driver)."""
    if spec.rating is None:
        return
    res = rating_from_design(spec, blank)
    report["rating"] = {"standard": "ISO 10300:2014 Method B1", **res.to_dict()}
    summary.highlights.append(f"rating (ISO 10300 B1): S_H = {res['S_H']:.3f}, S_F1 = {res['S_F1']:.3f}, "
                              f"S_F2 = {res['S_F2']:.3f}")


def rating_ltca_report(spec: DesignFile, blank, report: dict, summary, ltca_result) -> None:
    """Add ``rating.ltca_comparison`` (LTCA peak pressure against sigma_H0, sigma_H at the LTCA torque) when the
    design has ``[rating]`` and the LTCA of the drive side ran (hook of the face-milled run after its LTCA)."""
    if spec.rating is None or ltca_result is None or "rating" not in report:
        return
    assert spec.ltca is not None  # the LTCA ran, so the design has an [ltca] section
    if spec.ltca.side != "drive":
        report["rating"]["ltca_comparison"] = {"status": "not compared: the rating is of the drive side, the LTCA "
                                                         "of the coast side"}
        return
    from ..rating import compare_with_ltca

    cmp = compare_with_ltca(blank, rating_input_from_design(spec, blank), ltca_result)
    report["rating"]["ltca_comparison"] = {"status": "ok", **cmp, "units": {
        "T1_ltca": "N m", "p_max_ltca": "N/mm^2", "phi1_at_p_max": "deg", "pairs_at_p_max": "-",
        "sigma_H0": "N/mm^2", "sigma_H": "N/mm^2", "p_max/sigma_H0": "-", "p_max/sigma_H": "-"}}
    summary.highlights.append(f"LTCA peak pressure {cmp['p_max_ltca']:.0f} N/mm^2 = {cmp['p_max/sigma_H0']:.2f} "
                              f"sigma_H0, {cmp['p_max/sigma_H']:.2f} sigma_H (ISO 10300 B1 at the LTCA torque)")
