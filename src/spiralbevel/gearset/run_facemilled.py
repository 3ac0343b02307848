"""The face-milled branch of the main job."""

from __future__ import annotations

from ..conventions import Member, Side
from . import facemilled as fm
from . import outputs
from .partial import attempt, mark_failed
from .units import synthesis_units


def run_facemilled(gs, out, steps, report, summary):
    """Set up the cutters and settings of the gear set ``gs``, generate its four flanks, and write the requested
    outputs into ``out``."""
    spec, blank = gs.design, gs.blank
    o = spec.output
    n_face, n_profile = o.grid
    with steps.step("cutters and machine settings"):
        setups, synth = gs.setups, gs.synthesis
        if synth:
            report["synthesis"] = {name: synthesis_units(r.summary()) for name, r in synth.items()}
        cmc = {name: d for name, d in synth.items() if hasattr(d, "multipoint")}
    with steps.step("generated flanks and curvatures"):
        grids = gs.grids(n_face, n_profile)
        flanks, machines = fm.flank_report(setups, blank, spec)
        from .slot_check import slot_report

        slot_report(spec, blank, setups, flanks)      # each cutter's opposite blade against the opposite flank
        from .root_cone import root_cone_report

        root_cone_report(spec, setups, flanks)        # each generated root against the blank's root cone
        report["flanks"] = flanks
        report["machine_settings"] = machines
    with steps.step("tooth assembly"):
        tooth = {}
        for m in fm.MEMBERS:
            rot = fm.tooth_rotation(blank, setups, m)
            cx, cc = grids[(m, Side.CONVEX)], grids[(m, Side.CONCAVE)]
            tooth[m] = ((cx.points, cx.normals), fm.rotate_grid(cc.points, cc.normals, rot))
    with steps.step("tooth contact analysis"):
        from .tca import run_pair_tca

        from .tca import SENSITIVITY, misalignment_sensitivity

        n_pos = spec.tca.positions
        tca_results, report["tca"], tca_outlines = run_pair_tca(blank, setups, grids, n_positions=n_pos)
        for name in ("drive", "coast"):
            mark_failed(summary.partial, report["tca"][name], f"TCA, {name} side")
            _tca_checks(report, name, tca_results.get(name), synth, blank.z1, spec)
            iso_contact_ratio(report["tca"][name], blank, name)
        from .fillet_top import fillet_top_report

        fillet_top_report(spec, blank, setups, report["flanks"], report["tca"])   # each fillet against the mate's tip
        sens, failed = attempt(summary.partial, "misalignment sensitivity", misalignment_sensitivity, blank, setups,
                               "drive", n_positions=n_pos)
        report["tca"]["misalignment_sensitivity"] = failed or sens
        if failed is None:
            mark_failed(summary.partial, sens, "misalignment sensitivity, aligned")
            for case in SENSITIVITY:
                if isinstance(sens.get(case[0]), dict):
                    mark_failed(summary.partial, sens[case[0]], f"misalignment sensitivity, {case[0]} case")
        if cmc:
            from ..meshing.synthesis.cmc_design import te_summary

            name, design = next(iter(cmc.items()))
            # seed 001 §5 computes the TE in its own model (straight blades continued to the tip, Eq. (16)): that is
            # the figure to compare with the paper; the same design with the real edge radii is reported beside it
            paper = fm.cmc_paper_model(spec, blank, setups, name)
            real = te_summary(design.tca, design.multipoint) if design.tca is not None else None
            paper = synthesis_units(paper)
            real = synthesis_units(real) if real is not None else None
            report["tca"]["cmc"] = {"side": name, "paper_model": paper, "real_flanks": real}
            # both top-level figures from the paper's model, the one seed 001 reports (the real-flank design beside)
            report["tca"]["control_point_errors_arcsec"] = paper["control_point_errors_arcsec"]
            if "max_transmission_error_arcsec" in paper:
                report["tca"]["max_transmission_error_arcsec"] = paper["max_transmission_error_arcsec"]
                summary.highlights.append(
                    f"CMC ({name}): max TE {paper['max_transmission_error_arcsec']:.4f} arcsec (paper's model; "
                    f"real edge radii {real['max_transmission_error_arcsec'] if real else float('nan'):.4f}) against "
                    f"the predesigned {paper['predesigned_magnitude_arcsec']:.4f}; control-point errors <= "
                    f"{max(report['tca']['control_point_errors_arcsec']):.2e} arcsec")
    ltca_result = None
    if spec.ltca is not None:
        with steps.step("loaded TCA (FE compliance, load sharing)"):
            from .ltca import run_ltca_job

            out_lt, failed = attempt(summary.partial, f"loaded TCA, {spec.ltca.side} side", run_ltca_job, spec,
                                     blank, setups)
            ltca_result, report["ltca"] = out_lt if failed is None else (None, failed)
            lt = report["ltca"]
            mark_failed(summary.partial, lt, f"loaded TCA, {spec.ltca.side} side")
            if lt.get("status") == "failed":
                summary.highlights.append(f"LTCA {spec.ltca.side}: failed ({lt['reason']})")
            else:
                summary.highlights.append(
                    f"LTCA {lt['side']}: torque {lt['torque_N_m']:.2f} N m (approach 0.00635 mm at "
                    f"{lt['torque_for_approach_N_m']:.2f} N m), loaded TE "
                    f"{lt['loaded_transmission_error_largest_magnitude_arcsec']:.3f} "
                    f"arcsec, max pressure {lt['max_contact_pressure_N_per_mm2']:.0f} N/mm^2")
            from .rating import rating_ltca_report

            rating_ltca_report(spec, blank, report, summary, ltca_result, setups=setups, out=out, plots=o.plots)
    with steps.step("ease-off and measurement grids"):
        from .inspection import easeoff_maps, measurement_files

        report["easeoff"], files = easeoff_maps(blank, setups, out, o.plots)
        summary.files += files
        report["measurement"], files = measurement_files(setups, out)
        summary.files += files
    if o.plots:
        with steps.step("plots"):
            if ltca_result is not None:
                fig = ltca_result.plot(outline=tca_outlines.get(spec.ltca.side, (None, None))[1],
                                       title=f"Loaded TCA, {spec.ltca.side} side: {spec.title}")
                summary.files.append(outputs.save_figure(fig, out / "ltca.png"))
            for name, res in tca_results.items():
                if res is not None:
                    fig = res.plot(outline1=tca_outlines[name][0], outline2=tca_outlines[name][1],
                                   title=f"TCA, {name} side: {spec.title}")
                    summary.files.append(outputs.save_figure(fig, out / f"tca_{name}.png"))
            summary.files.append(outputs.axial_section(grids, out, spec.title, tooth, blank))
            summary.files.append(outputs.curvature_maps(
                {k: _Geo(g.points, g.k1, g.k2) for k, g in grids.items()}, out, spec.title, ordered=True))
    teeth = {Member.PINION: blank.z1, Member.GEAR: blank.z2}
    cad = None
    if o.stl or o.step:  # whole teeth: flanks with their generated fillets
        cad, warnings = outputs.cad_teeth(spec, blank, setups, n_face, n_profile)
        report["cad"] = {"fillet_rows": outputs.CAD_FILLET_ROWS, "warnings": warnings}
        summary.highlights += warnings
    if o.stl:
        with steps.step("STL"):
            summary.files += outputs.stl_files(tooth, teeth, out, cad=cad)
    if o.step:
        with steps.step("STEP"):
            summary.files += outputs.step_files(tooth, out, teeth=teeth, cad=cad)
    summary.highlights += tca_and_flank_highlights(report, flanks, machines)


class _Geo:
    """Adapter: the attributes the curvature-map plot reads."""

    def __init__(self, point, k1, k2):
        self.point, self.k1, self.k2 = point, k1, k2


def tca_and_flank_highlights(report, flanks, machines) -> list[str]:
    """Console lines of a face-milled run (spiral bevel or hypoid): TE and edge contacts per side, achieved mean-point
    angles per flank."""
    lines = []
    for name in ("drive", "coast"):
        sec = report["tca"][name]
        level = (f" (parabolic level {sec['te_level_arcsec']:.3f} arcsec at the mean contact)"
                 if sec.get("te_level_arcsec") is not None else "")
        lines.append(f"TCA {name}: " + (sec["error"] if "error" in sec else
                     f"TE peak-to-peak {sec['peak_to_peak_arcsec']:.3f} arcsec{level}, "
                     f"{len(sec['edge_contact_positions_deg'])} edge-contact positions"))
    for m in fm.MEMBERS:
        for s in fm.SIDES:
            f = flanks[m.value][s.value]
            source = machines[m.value][s.value]["source"]
            lines.append(f"{m.value} {s.value}: mean spiral angle {f['spiral_angle_deg']:.4f} deg, "
                         f"normal pressure angle {f['pressure_angle_deg']:.4f} deg ({source})")
    return lines


def pinion_settings_given(spec, name) -> bool:
    """The design file gives the machine settings of the pinion flank of side ``name`` (``face_milling.pinion_<flank>
    .machine``); else they are synthesized or the basic settings from the blank."""
    flank = "concave" if name == "drive" else "convex"
    return getattr(getattr(spec.face_milling, f"pinion_{flank}"), "machine", None) is not None


def tca_side_checks(res, name, synth, z1, given: bool = True, default: bool = False) -> list[str]:
    """Bearing and TE-level checks of one side (:func:`spiralbevel.meshing.tca_checks.tca_checks`): the parabolic TE
    level of a local synthesis is checked against its design value; a CMC design against its own curve (tca.cmc).
    ``given``: the pinion flank's machine settings come from the design file (:func:`pinion_settings_given`);
    ``default``: the design file has no ``[synthesis]`` section."""
    from ..meshing.tca_checks import tca_checks

    local = name in synth and not hasattr(synth[name], "multipoint")
    design = synthesis_units(synth[name].summary()).get("te_magnitude_arcsec") if local else None
    return tca_checks(res, name, name in synth, design, z1, given, default)


def add_te_level(section, res, synth, name, z1) -> None:
    """``te_level_arcsec`` of a side whose pinion is locally synthesized (parabolic motion curve): the parabolic TE
    level at the mean contact (``meshing.tca_checks.te_level``), the level the synthesis designs; the peak to peak is
    lower when the next pair takes over before the parabola reaches it."""
    if res is not None and name in synth and not hasattr(synth[name], "multipoint"):
        from ..meshing.tca_checks import te_level

        section["te_level_arcsec"] = te_level(res, z1)


def _tca_checks(report, name, res, synth, z1, spec=None):
    """Bearing and TE-level checks of one side into ``tca.<side>.checks`` (and as design warnings); ``spec`` the
    design file (which pinion settings it gives)."""
    import warnings

    from ..errors import DesignWarning

    given = True if spec is None else pinion_settings_given(spec, name)
    found = tca_side_checks(res, name, synth, z1, given, spec is not None and spec.synthesis is None)
    report["tca"][name]["checks"] = found
    add_te_level(report["tca"][name], res, synth, name, z1)
    for text in found:
        warnings.warn(text, DesignWarning, stacklevel=2)


def iso_contact_ratio(section, blank, name):
    """ISO 10300-1 transverse and total contact ratios of the loaded side beside the TCA's (``contact_ratio_from_tca``):
    a bearing whose path crosses the profile spans about the transverse ratio, one turned lengthwise more, up to
    the total ratio of the full face."""
    from ..design.contact_ratio import contact_ratios

    if "error" in section:
        return
    cr = contact_ratios(blank, blank.alpha_eD if name == "drive" else blank.alpha_eC)
    section["contact_ratio_iso10300_transverse"] = cr["eps_valpha"]
    section["contact_ratio_iso10300_total"] = cr["eps_vgamma"]
