"""STL and STEP of the teeth of a hypoid pair in the main job: whole teeth (generated fillets and root) of each
member in its own member frame, as for a spiral bevel pair (``gearset.outputs.cad_teeth``, ``stl_files``,
``step_files``); the whole member is the tooth patterned z times about the member axis. The derived edge radius is
the one the generated root slot holds (:mod:`spiralbevel.gearset.hypoid_fillet`)."""

from __future__ import annotations

from ..conventions import Member, Side

__all__ = ["hypoid_cad"]


def hypoid_cad(gs, out, steps, report, summary) -> None:
    """Write the STL / STEP files that the design's ``[output]`` asks for into ``out`` and the ``cad`` report
    section (fillet rows, warnings) of the hypoid gear set ``gs``."""
    from . import facemilled as fm
    from . import outputs

    spec, blank, setups = gs.design, gs.blank, gs.setups
    o = spec.output
    n_face, n_profile = o.grid
    grids = gs.grids(n_face, n_profile)
    tooth = {}
    for m in fm.MEMBERS:
        rot = fm.tooth_rotation(blank, setups, m)
        cx, cc = grids[(m, Side.CONVEX)], grids[(m, Side.CONCAVE)]
        tooth[m] = ((cx.points, cx.normals), fm.rotate_grid(cc.points, cc.normals, rot))
    teeth = {Member.PINION: blank.z1, Member.GEAR: blank.z2}
    cad, warnings = outputs.cad_teeth(spec, blank, setups, n_face, n_profile)
    report["cad"] = {"fillet_rows": outputs.CAD_FILLET_ROWS, "warnings": warnings,
                     "edge_radius_mm": {f"{m.value}_{s.value}": float(setups[(m, s)].cutter.edge_radius)
                                        for m in fm.MEMBERS for s in fm.SIDES}}
    summary.highlights += warnings
    if o.stl:
        with steps.step("STL"):
            summary.files += outputs.stl_files(tooth, teeth, out, cad=cad)
    if o.step:
        with steps.step("STEP"):
            summary.files += outputs.step_files(tooth, out, teeth=teeth, cad=cad)
