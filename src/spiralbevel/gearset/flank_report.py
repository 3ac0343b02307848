"""Report sections of face-milled flanks: the flank and machine-setting sheets with design against achieved and the
design checks, and the TE of the CMC design in seed 001's own model."""

from __future__ import annotations

import math
import warnings

from ..conventions import Member, Side
from ..errors import DesignWarning
from ..meshing.tca_result import ARCSEC
from .default_candidates import _FREE
from .default_synthesis import PAIR_SIDES
from .flank_checks import flank_checks
from .flank_setup import MEMBERS
from .tooth_assembly import tooth_rotation

def flank_report(setups, blank=None, spec=None):
    """``flanks`` and ``machine_settings`` report sections (degrees, mm, 1/mm); with the blank, each flank's design
    against achieved mean-point angles and root position (``design_vs_achieved``); with the design ``spec``, the
    checks of a synthesized flank say whether the default synthesis produced it (``flank_checks``)."""
    from ..generation.basic_settings_solve import flank_fit
    from .units import MACHINE_SETTING_UNITS, suffixed

    flanks, machines = {}, {}
    for (m, s), st in setups.items():
        mp = st.flank.mean_point()
        res = abs(float(st.flank.meshing_residual(mp.u, mp.theta, mp.psi_c)))
        flanks.setdefault(m.value, {})[s.value] = {
            "mean_point_mm": mp.point, "mean_normal": mp.normal,
            "spiral_angle_deg": math.degrees(mp.spiral_angle), "pressure_angle_deg": math.degrees(mp.pressure_angle),
            "pressure_angle_root_deg": math.degrees(mp.pressure_angle_root),
            "hand": "RH" if mp.hand_sign > 0 else "LH",
            "k1_per_mm": mp.k1, "k2_per_mm": mp.k2, "meshing_residual": res,
            "surface_parameters": {"u_mm": mp.u, "theta_deg": math.degrees(mp.theta),
                                   "psi_c_deg": math.degrees(mp.psi_c)},
        }
        c = st.cutter
        machines.setdefault(m.value, {})[s.value] = {
            "source": st.source,
            "settings": suffixed(st.settings.to_dict(degrees=True), MACHINE_SETTING_UNITS),
            "cutter": {"blade": c.blade.value, "point_radius_mm": c.point_radius,
                       "blade_angle_deg": math.degrees(c.blade_angle), "point_width_mm": c.point_width,
                       "edge_radius_mm": c.edge_radius,
                       "profile_radius_mm": c.profile_radius if math.isfinite(c.profile_radius) else None},
            "summary": [list(r) for r in st.settings.summary_rows(c, m, s)],
        }
        fit = st.fit if st.fit is not None else (flank_fit(blank, st.flank) if blank is not None else None)
        if fit is not None:
            flanks[m.value][s.value]["design_vs_achieved"] = fit.to_dict()
            flanks[m.value][s.value]["checks"] = flank_checks(fit, m, s, st.source, spec)
    if blank is not None:   # the concave flank of each tooth turned to the mean normal thickness (tooth_rotation)
        for m in MEMBERS:
            if (m, Side.CONVEX) in setups and (m, Side.CONCAVE) in setups:
                rot = tooth_rotation(blank, setups, m)
                flanks[m.value]["concave"]["tooth_rotation_deg"] = float(rot * 180.0 / 3.141592653589793)
    if blank is not None and "pinion" in flanks and {"concave", "convex"} <= set(flanks["pinion"]):
        from ..design.blank_checks import achieved_undercut

        p = flanks["pinion"]
        found = achieved_undercut(blank, math.radians(p["concave"]["pressure_angle_deg"]),
                                  math.radians(p["convex"]["pressure_angle_deg"]))
        for side in ("concave", "convex"):
            p[side].setdefault("checks", []).extend(found)
    if blank is not None:
        from ..design.blank_checks import achieved_top_land

        for m_name, sides in flanks.items():   # drive = pinion concave / gear convex
            if {"concave", "convex"} <= set(sides):
                drive, coast = ("concave", "convex") if m_name == "pinion" else ("convex", "concave")
                found = achieved_top_land(blank, 1 if m_name == "pinion" else 2,
                                          math.radians(sides[drive]["pressure_angle_deg"]),
                                          math.radians(sides[coast]["pressure_angle_deg"]))
                for side in (drive, coast):
                    sides[side].setdefault("checks", []).extend(found)
    for m_name, sides in flanks.items():
        for side, d in sides.items():
            for text in d.get("checks", ()):
                warnings.warn(f"{m_name} {side}: {text}", DesignWarning, stacklevel=2)
    return flanks, machines


def cmc_paper_model(spec, blank, setups, name):
    """TE summary of the CMC design in seed 001's own model: both cutters straight blades down to the tip (no edge
    radius), TCA over the whole cycle (for comparison with the paper's -3.1527 arcsec)."""
    from ..meshing import synthesis as syn
    from ..meshing.synthesis.cmc_design import design_seed001_style, te_summary

    from .default_synthesis import effective_synthesis

    sy = effective_synthesis(spec, blank)   # the section's keys over the developed-pair defaults
    s1, s2 = PAIR_SIDES[name]
    gear = setups[(Member.GEAR, s2)]
    d = design_seed001_style(gear.cutter, gear.settings, blank, side=s1, eta=math.radians(sy.path_direction),
                             semi_major_axis=sy.semi_major_axis, te_magnitude=sy.te_magnitude * ARCSEC,
                             n_control=sy.control_points, interpolation=sy.offset_interpolation, approach=sy.approach,
                             free=getattr(syn, _FREE[sy.free]), straight_blades=True)
    if d.tca is None:
        return {"control_point_errors_rad": d.multipoint.control_point_errors.tolist()}
    ts = te_summary(d.tca, d.multipoint)
    keep = ("max_transmission_error_arcsec", "predesigned_magnitude_arcsec", "controlled_range_deviation_arcsec",
            "control_point_errors_rad", "transfer_points_deg", "pinion_rotation_deg", "transmission_error_arcsec")
    out = {k: ts[k] for k in keep}
    e = d.multipoint.offsets
    out["blank_offset_range_mm"] = [float(min(e)), float(max(e))]
    return out
