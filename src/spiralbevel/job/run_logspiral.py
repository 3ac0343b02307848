"""The log-spiral branch of the main job."""

from __future__ import annotations

import math

import numpy as np

from ..conventions import Member
from . import logspiral as ls
from . import outputs
from .partial import attempt, mark_failed


def run_logspiral(spec, blank, out, steps, report, summary):
    """Design the log-spiral pair, evaluate its flanks and write every requested output into ``out``."""
    o = spec.output
    n_face, n_profile = o.grid
    with steps.step("log-spiral pair design"):
        pair = ls.design_pair(spec, blank)
    with steps.step("flank geometry and curvatures"):
        grids = ls.flank_grids(pair, n_face, n_profile)
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
    teeth = {Member.PINION: pair.pinion.teeth, Member.GEAR: pair.gear.teeth}
    tooth = {m: ls.tooth_grids(pair, grids, m) for m in ls.MEMBERS}
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
            report["toolpaths"] = _toolpaths(spec, pair, out, summary)
    if o.stl:
        with steps.step("STL"):
            summary.files += outputs.stl_files(tooth, teeth, out)
    if o.step:
        with steps.step("STEP"):
            summary.files += outputs.step_files(tooth, out)
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


def _toolpaths(spec, pair, out, summary):
    from ..io.toolpath_csv import write_toolpath_csv
    from ..manufacturing.toolpath import plan_toolpath

    mf = spec.manufacturing
    section = {"ball_radius_mm": mf.ball_radius, "scallop_height_mm": mf.scallop_height, "flanks": {}}
    for m in ls.MEMBERS:
        for s in ls.SIDES:
            f = pair.flank(m, s)
            tp = plan_toolpath(f.surface, f.domain, mf.ball_radius, mf.scallop_height)
            name = f"toolpath_{m.value}_{s.value}.csv"
            write_toolpath_csv(out / name, tp.rotated(f.rotation))
            summary.files.append(name)
            section["flanks"][f"{m.value}_{s.value}"] = {
                "file": name, "passes": len(tp), "points": int(sum(len(p.center) for p in tp.paths)),
                "max_predicted_scallop_mm": float(np.max(tp.predicted_scallop)) if len(tp) > 1 else 0.0,
            }
    return section
