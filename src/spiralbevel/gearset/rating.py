"""Design file -> ISO 10300 rating (``spiralbevel rate`` and the ``rating`` section of report.json).

Problems are reported with design-file field paths (``rating.pinion_speed`` ...).
"""

from __future__ import annotations

import math

import numpy as np

from ..conventions import Member, Side
from ..errors import DesignError, Problem
from ..io.design_schema import DesignFile

__all__ = ["rating_input_from_design", "rating_from_design", "rating_section", "rating_report", "rating_ltca_report",
           "rating_fe_root_report", "fe_root_stress_from_job"]

# RatingInput field -> design-file path
FIELD_PATHS = {
    "T1": "rating.pinion_torque", "n1": "rating.pinion_speed", "K_A": "rating.application_factor",
    "f_pt": "rating.pitch_deviation", "rho_a0": "rating.cutter_edge_radius", "sigma_Hlim": "rating.sigma_Hlim",
    "sigma_Flim": "rating.sigma_Flim", "nu40": "rating.oil_viscosity", "Rz_flank": "rating.flank_roughness",
    "Rz_root": "rating.root_roughness", "mounting": "rating.mounting", "contact_pattern": "rating.contact_pattern",
    "profile_crowning": "rating.profile_crowning",
    "E": "rating.youngs_modulus", "nu": "rating.poisson_ratio", "density": "rating.density",
    "S_Hmin": "rating.S_Hmin", "S_Fmin": "rating.S_Fmin", "material": "rating.material",
    "load_cycles": "rating.load_cycles", "Z_Hyp": "rating.hypoid_factor",
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
            S_Hmin=r.S_Hmin, S_Fmin=r.S_Fmin, material=r.material, load_cycles=r.load_cycles,
            Z_Hyp=r.hypoid_factor)
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


def rating_section(res) -> dict:
    """The ``rating`` section of report.json of a :class:`~spiralbevel.rating.RatingResult`: ISO 10300 symbols
    with the unit as a suffix (``sigma_H_N_per_mm2``; dimensionless factors bare), angles in degrees."""
    from .units import suffixed

    d = res.to_dict(degrees=True)
    units, notes = d.pop("units"), d.pop("notes")
    return {"standard": "ISO 10300:2014 Method B1", **suffixed(d, units), "notes": notes}


def rating_report(spec: DesignFile, blank, report: dict, summary) -> None:
    """Add the ``rating`` section to ``report`` when the design has ``[rating]`` (hook of the run driver)."""
    if spec.rating is None:
        return
    res = rating_from_design(spec, blank)
    report["rating"] = rating_section(res)
    summary.highlights.append(f"rating (ISO 10300 B1): S_H = {res['S_H']:.3f}, S_F1 = {res['S_F1']:.3f}, "
                              f"S_F2 = {res['S_F2']:.3f}")


def rating_ltca_report(spec: DesignFile, blank, report: dict, summary, ltca_result, setups=None, out=None,
                       plots: bool = False) -> None:
    """Add ``rating.ltca_comparison`` (LTCA peak pressure against sigma_H0, sigma_H at the LTCA torque) when the
    design has ``[rating]`` and the LTCA of the drive side ran (hook of the face-milled run after its LTCA); with the
    flank ``setups`` also ``rating.fe_root_stress`` (:func:`rating_fe_root_report`)."""
    if spec.rating is None or ltca_result is None or "rating" not in report:
        return
    assert spec.ltca is not None  # the LTCA ran, so the design has an [ltca] section
    if spec.ltca.side != "drive":
        report["rating"]["ltca_comparison"] = {"status": "not compared: the rating is of the drive side, the LTCA "
                                                         "of the coast side"}
        return
    from ..rating import compare_with_ltca
    from .units import suffixed

    cmp = compare_with_ltca(blank, rating_input_from_design(spec, blank), ltca_result)
    report["rating"]["ltca_comparison"] = {"status": "ok", **suffixed(cmp, LTCA_COMPARISON_UNITS)}
    summary.highlights.append(f"LTCA peak pressure {cmp['p_max_ltca']:.0f} N/mm^2 = {cmp['p_max/sigma_H0']:.2f} "
                              f"sigma_H0, {cmp['p_max/sigma_H']:.2f} sigma_H (ISO 10300 B1 at the LTCA torque)")
    if setups is not None:
        rating_fe_root_report(spec, blank, report, summary, ltca_result, setups, out, plots)


#: units of the figures of ``rating.ltca_comparison``
LTCA_COMPARISON_UNITS = {"T1_ltca": "N m", "p_max_ltca": "N/mm^2", "phi1_at_p_max": "deg", "pairs_at_p_max": "-",
                         "sigma_H0": "N/mm^2", "sigma_H": "N/mm^2", "p_max/sigma_H0": "-", "p_max/sigma_H": "-"}

#: units of the figures of ``rating.fe_root_stress`` (per member)
FE_ROOT_UNITS = {
    "T1_ltca": "N m", "sigma1_max": "N/mm^2", "face_fraction_from_toe": "-", "height_above_root_mm": "mm",
    "axial_section_radius_mm": "mm", "axial_section_z_mm": "mm", "pinion_angle_deg": "deg",
    "max_equilibrium_error_N": "N", "sigma_F0": "N/mm^2", "sigma_F": "N/mm^2", "sigma1/sigma_F0": "-",
    "sigma1/sigma_F": "-"}


def rating_fe_root_report(spec: DesignFile, blank, report: dict, summary, ltca_result, setups, out=None,
                          plots: bool = False) -> None:
    """Add ``rating.fe_root_stress``: the maximum principal stress along the root fillets of pinion and gear in the
    FE tooth model under the LTCA's contact forces, against sigma_F0 and sigma_F of Method B1 at the LTCA torque
    (and ``root_stress.png`` in ``out`` with ``plots``)."""
    if (spec.rating is None or spec.ltca is None or ltca_result is None or "rating" not in report
            or spec.ltca.side != "drive"):
        return
    from ..errors import SpiralBevelError
    from ..rating.fe_root_stress import compare_root_stress

    try:
        stresses = fe_root_stress_from_job(spec, blank, setups, ltca_result)
    except SpiralBevelError as err:
        report["rating"]["fe_root_stress"] = {"status": f"not computed: {err}"}
        summary.highlights.append(f"FE root stress not computed: {err}")
        return
    cmp = compare_root_stress(blank, rating_input_from_design(spec, blank), ltca_result, stresses)
    from .units import suffixed

    section = {k: (suffixed(v, FE_ROOT_UNITS) if isinstance(v, dict) else v) for k, v in
               suffixed(cmp, FE_ROOT_UNITS).items()}
    report["rating"]["fe_root_stress"] = {
        "status": "ok", **section, "fillet_rows": FE_ROOT_FILLET_ROWS,
        "model": "3-tooth segments with their generated root fillets, quadratic tetrahedra clamped at the rim, the "
                 "LTCA's normal contact forces (no friction); maximum principal stress nodal-averaged, largest over "
                 "every mesh position with tooth 0 in the role of each loaded pair"}
    p, g = cmp["pinion"], cmp["gear"]
    summary.highlights.append(
        f"FE root stress at T1 = {cmp['T1_ltca']:.1f} N m: pinion {p['sigma1_max']:.0f} N/mm^2 "
        f"({p['sigma1/sigma_F0']:.2f} sigma_F01), gear {g['sigma1_max']:.0f} N/mm^2 ({g['sigma1/sigma_F0']:.2f} "
        f"sigma_F02)")
    if plots and out is not None:
        from ..viz.root_stress_plot import plot_root_stress
        from .outputs import save_figure

        fig = plot_root_stress(stresses, f"FE tooth root stress at T1 = {cmp['T1_ltca']:.1f} N m: {spec.title}",
                               sigma_F0={"pinion": p["sigma_F0"], "gear": g["sigma_F0"]})
        summary.files.append(save_figure(fig, out / "root_stress.png"))


#: fillet rows of the flank grids of the FE root-stress model (from the cutter-tip root line to the blade junction)
FE_ROOT_FILLET_ROWS = 4


def fe_root_stress_from_job(spec: DesignFile, blank, setups, ltca_result, fe_options=None):
    """FE root stress of pinion and gear (:func:`~spiralbevel.rating.fe_root_stress.fe_root_stress`) under the
    contact forces of the job's LTCA: the flank grids of the LTCA's FE model (``[ltca] flank_grid``) with
    ``FE_ROOT_FILLET_ROWS`` fillet rows below, in the same (phased) member frames."""
    from ..meshing.pair import meshing_pair
    from ..rating.fe_root_stress import fe_root_stress
    from .facemilled import tooth_rotation
    from .ltca import _tooth_grids
    from .tca import SIDES

    lt = spec.ltca
    assert lt is not None  # called after the LTCA of the job, which needs [ltca]
    s1, s2 = SIDES[lt.side]
    pair = meshing_pair(setups[(Member.PINION, s1)].flank, setups[(Member.GEAR, s2)].flank, blank)
    c1, c2 = pair.pinion, pair.gear
    nf, npf = lt.flank_grid
    # the last fillet row and the first blade row of ToothFlank.grid coincide: keep one of them
    grids = {k: np.delete(st.flank.grid(nf, npf, n_fillet=FE_ROOT_FILLET_ROWS, curvature=False).points,
                          FE_ROOT_FILLET_ROWS, axis=1) for k, st in setups.items()}
    pin = _tooth_grids(grids, Member.PINION, s1, c1.rotation, tooth_rotation(blank, setups, Member.PINION))
    gear = _tooth_grids(grids, Member.GEAR, s2, c2.rotation, tooth_rotation(blank, setups, Member.GEAR))
    # the LTCA names its pairs "pair %+d" after the TCA's tooth-pair index k
    pairs = [int(name.split()[-1]) for name in ltca_result.pair_names]
    return fe_root_stress(ltca_result, pin, gear, blank.z1, blank.z2, pairs=pairs, sides=(s1.value, s2.value),
                          n_fillet=FE_ROOT_FILLET_ROWS, youngs_modulus=lt.youngs_modulus,
                          poisson_ratio=lt.poisson_ratio, fe_options=fe_options)
