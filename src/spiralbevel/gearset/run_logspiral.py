"""The log-spiral branch of the main job."""

from __future__ import annotations


import numpy as np

from ..conventions import Member
from . import logspiral as ls
from . import outputs
from .partial import attempt, mark_failed


def run_logspiral(gs, out, steps, report, summary):
    """Design the log-spiral pair of the gear set ``gs``, evaluate its flanks and write every requested output into
    ``out``."""
    spec = gs.design
    o = spec.output
    n_face, n_profile = o.grid
    with steps.step("log-spiral pair design"):
        pair = gs.logspiral_pair
    with steps.step("flank geometry and curvatures"):
        grids = gs.grids(n_face, n_profile)
        report["logspiral"] = ls.flank_report(pair, grids)
    with steps.step("conjugacy check (envelope solver)"):
        from .conjugacy import conjugacy_report

        cj, failed = attempt(summary.partial, "conjugacy check (envelope solver)", conjugacy_report, pair)
        report["logspiral"]["conjugacy"] = failed or cj
    with steps.step("tooth contact analysis"):
        from .logspiral_tca import logspiral_tca

        tca, failed = attempt(summary.partial, "log-spiral tooth contact analysis", logspiral_tca, pair)
        report["logspiral"]["tca"] = failed or tca[1]
        for name, sec in ({} if failed else tca[1]).items():
            mark_failed(summary.partial, sec, f"log-spiral TCA, {name} side")
    crowning = reliefs = None
    if spec.crowning is not None or o.draft and spec.manufacturing.forging_relief:
        from . import logspiral_production as lp

        if spec.crowning is not None:
            with steps.step("mismatched pair: pinion crowning from the mean-point targets"):
                crowning = lp.design_crowning(spec, pair)
        if o.draft and spec.manufacturing.forging_relief:
            with steps.step("forging relief (two feature parameters)"):
                reliefs = lp.design_reliefs(spec, pair, crowning)
                report["forging"] = lp.forging_section(spec, pair, reliefs, crowning, out, summary, o.plots)
        if crowning is not None:
            with steps.step("TCA and misalignment sensitivity of the modified flanks"):
                _, report["mismatch"] = lp.mismatch_section(spec, pair, crowning, reliefs, out, summary, o.plots)
    teeth = {Member.PINION: pair.pinion.teeth, Member.GEAR: pair.gear.teeth}
    if crowning is None and reliefs is None:
        tooth = {m: ls.tooth_grids(pair, grids, m) for m in ls.MEMBERS}
    else:  # STL, STEP and the tool-path report carry the modified flanks
        tooth = {m: lp.modified_tooth_grids(pair, m, n_face, n_profile, crowning, reliefs) for m in ls.MEMBERS}
    if o.plots:
        with steps.step("plots"):
            summary.files.append(outputs.curvature_maps(grids, out, spec.title))
            summary.files.append(outputs.curvature_domain_maps(pair, grids, out))
            summary.files.append(outputs.pitch_traces(
                grids, {Member.PINION: pair.pinion.pitch_angle, Member.GEAR: pair.gear.pitch_angle}, out))
            summary.files.append(outputs.meshing_pair_3d(pair, grids, out))
            summary.files.append(outputs.transverse_section(pair, grids, out))
    if o.draft:
        with steps.step("forging draft"):
            report["draft"] = _draft(spec, pair, out, summary, o.plots)
    if o.toolpaths:
        with steps.step("5-axis tool paths"):
            report["toolpaths"] = _toolpaths(spec, pair, out, summary, crowning, reliefs)
    if o.stl:
        with steps.step("STL"):
            summary.files += outputs.stl_files(tooth, teeth, out)
    if o.step:
        with steps.step("STEP"):
            summary.files += outputs.step_files(tooth, out, teeth=teeth)
    if "mismatch" in report:
        t = report["mismatch"]["tca"]
        summary.highlights.append(
            f"mismatched pair: TE {t['te_level_arcsec']:.2f} arcsec (target {spec.crowning.te_level:g}), ellipse a = "
            f"{t['semi_major_axis_mm']:.3f} mm (target {spec.crowning.semi_major_axis:g}), point contact inside the "
            f"flanks: {t['point_contact_inside_flanks']}")
    if "draft" in report:
        bad = {k: v["failing_area_fraction"] for k, v in report["draft"]["flanks"].items() if not v["passes"]}
        summary.highlights.append(
            "forging draft: FAILS on " + ", ".join(f"{k.replace('_', ' ')} ({100 * f:.1f}% of the area)"
                                                   for k, f in bad.items()) + " (draft_map.png, report 'draft')"
            if bad else "forging draft: passes on every flank")
    if "forging" in report:
        ok = all(v["passes"] for v in report["forging"]["flanks"].values())
        summary.highlights.append(f"forging relief: draft {spec.manufacturing.draft_angle:g} deg passes on every "
                                  f"flank: {ok}")
    cj = report["logspiral"]["conjugacy"]
    summary.highlights.append("conjugacy (envelope of the pinion vs the gear flank): " + (
        f"failed ({cj['reason']})" if cj.get("status") == "failed" else ", ".join(
            f"{s} {v.get('max_distance_mm', float('nan')):.2e} mm" for s, v in cj.items())))
    k = report["logspiral"]["members"]
    summary.highlights.append(
        f"log-spiral: base cones {k['pinion']['base_cone_angle_deg']:.4f} / {k['gear']['base_cone_angle_deg']:.4f} deg,"
        f" plane spiral angle {report['logspiral']['plane_spiral_angle_deg']:.4f} deg")


def _draft(spec, pair, out, summary, plots):
    from ..manufacturing.draft import draft_map

    die = spec.manufacturing.die_direction
    section = {"die_direction": list(die), "flanks": {}}
    results = []
    for m in ls.MEMBERS:
        for s in ls.SIDES:
            f = pair.flank(m, s)
            r = draft_map(f.surface, f.domain, die_direction=die)
            results.append((f"{m.value} {s.value}", r))
            section["flanks"][f"{m.value}_{s.value}"] = {
                "failing_area_fraction": r.failing_area_fraction,
                "analytic_failing_fraction": r.analytic_fraction,
                "passes": bool(r.passes),
            }
    if plots:
        summary.files.append(outputs.draft_maps(results, out))
    return section


def _toolpaths(spec, pair, out, summary, crowning=None, reliefs=None):
    from ..io.toolpath_csv import write_toolpath_csv
    from ..manufacturing.toolpath import follow_lines_of_curvature, plan_toolpath

    mf = spec.manufacturing
    section = {"ball_radius_mm": mf.ball_radius, "scallop_height_mm": mf.scallop_height, "flanks": {}}
    for m in ls.MEMBERS:
        for s in ls.SIDES:
            f = pair.flank(m, s)
            tp = plan_toolpath(f.surface, f.domain, mf.ball_radius, mf.scallop_height)
            name = f"toolpath_{m.value}_{s.value}.csv"
            modified = (crowning is not None and m is Member.PINION and s is crowning.side) or (
                reliefs is not None and reliefs[(m, s)].relief is not None)
            if modified:  # along the lines of curvature of the crowned / relieved flank (member frame already)
                from .logspiral_production import contact_surface

                tp = follow_lines_of_curvature(contact_surface(pair, m, s, crowning, reliefs), tp)
            else:
                tp = tp.rotated(f.rotation)
            write_toolpath_csv(out / name, tp)
            summary.files.append(name)
            section["flanks"][f"{m.value}_{s.value}"] = {
                "along": "lines of curvature of the modified flank" if modified else "varphi-curves (lines of "
                         "curvature of the theoretical flank)",
                "file": name, "passes": len(tp), "points": int(sum(len(p.center) for p in tp.paths)),
                "max_predicted_scallop_mm": float(np.max(tp.predicted_scallop)) if len(tp) > 1 else 0.0,
            }
    return section
