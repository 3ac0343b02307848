"""Files of the main job: plots, STL, STEP, tool-path CSV. Each writer returns the names it wrote."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..conventions import Member, Side


#: resolution of the PNG plots: the figures are sized in inches for 7-10 pt text (10-14 px at 100 dpi, as legible as
#: on screen); the pixel count sets the cost of drawing the colour maps and of the PNG encoding
PLOT_DPI = 100
#: zlib level of the PNG encoding (Pillow's default 6 takes a third longer for 5-10 % smaller files)
PNG_COMPRESS_LEVEL = 3


def save_figure(fig, path: Path) -> str:
    """Save a matplotlib figure as PNG (:data:`PLOT_DPI`) and close it."""
    import matplotlib.pyplot as plt

    fig.savefig(path, dpi=PLOT_DPI, pil_kwargs={"compress_level": PNG_COMPRESS_LEVEL})
    plt.close(fig)
    return path.name


def draft_maps(results, out: Path) -> str:
    """PNG of the forging-draft maps of several flanks: ``results`` is a list of (label, DraftResult)."""
    from ..viz.draft_plot import plot_draft_maps

    return save_figure(plot_draft_maps(results), out / "draft_map.png")


def curvature_maps(grids, out: Path, title: str, labels=("k1 (profile)", "k2 (lengthwise)"), ordered=False) -> str:
    """PNG of k1 and k2 over every flank, drawn on the projected tooth (convex = positive). With ``ordered`` the
    panels show kappa_max = max(k1, k2) and kappa_min = min(k1, k2), continuous over the flank where the principal
    directions turn past the labels' reference directions (no step where k1 and k2 swap names)."""
    from ..viz.flank_maps import ordered_curvatures, plot_flank_fields

    panels = []
    for (m, s), g in grids.items():
        if ordered:
            kmax, kmin = ordered_curvatures(g.k1, g.k2)
            panels.append((f"{m.value} {s.value}: κ_max", g.point, kmax, "1/mm (convex +)"))
            panels.append((f"{m.value} {s.value}: κ_min", g.point, kmin, "1/mm (convex +)"))
            continue
        panels.append((f"{m.value} {s.value}: {labels[0]}", g.point, g.k1, "1/mm"))
        panels.append((f"{m.value} {s.value}: {labels[1]}", g.point, g.k2, "1/mm"))
    return save_figure(plot_flank_fields(panels, title=title), out / "curvature_maps.png")


def curvature_domain_maps(pair, grids, out: Path) -> str:
    """PNG of k1 and k2 of every log-spiral flank over its parameter domain (the parallelogram in (varphi, phi))."""
    from ..viz.flank_maps import plot_domain_fields

    k1: list[tuple] = []
    k2: list[tuple] = []
    for (m, s), g in grids.items():
        sf = pair.flank(m, s).surface
        phi = sf.phi_of_rho(np.asarray(g.rho))
        varphi = sf.varphi_of(np.asarray(g.psi), phi)
        x, y = np.degrees(varphi), np.degrees(phi)
        for lst, name, vals in ((k1, "k1 (profile)", g.k1), (k2, "k2 (lengthwise)", g.k2)):
            lst.append((f"{m.value} {s.value}: {name}", x, y, vals, "rolling angle varphi [deg]",
                        "spiral parameter phi [deg]", "1/mm (convex +)"))
    fig = plot_domain_fields(k1 + k2, title="Principal curvatures over the parallelogram domains (seed 000 Eq. (16))")
    return save_figure(fig, out / "curvature_domain.png")


def pitch_traces(grids, pitch_angles, out: Path) -> str:
    """PNG of the tooth traces on the developed pitch cones."""
    from ..viz.traces import pitch_cone_trace, plot_pitch_traces

    traces = [(m.value, f"{m.value} {s.value}", pitch_cone_trace(g.point, pitch_angles[m]), pitch_angles[m])
              for (m, s), g in grids.items()]
    return save_figure(plot_pitch_traces(traces), out / "pitch_traces.png")


def meshing_pair_3d(pair, grids, out: Path) -> str:
    """PNG of a pinion tooth between two gear teeth, in the pair frame at zero roll."""
    from .._core.rotations import rot_z
    from ..viz.pair3d import plot_surfaces_3d

    z2 = pair.gear.teeth
    surfaces = []
    for s, color in ((Side.CONVEX, "tab:blue"), (Side.CONCAVE, "tab:cyan")):
        surfaces.append((f"pinion {s.value}", pair.to_pair_frame(Member.PINION, grids[(Member.PINION, s)].point),
                         color))
    for k, shade in ((0, ("tab:red", "tab:orange")), (-1, ("tab:red", "tab:orange"))):
        R = rot_z(2 * math.pi * k / z2)
        for s, color in zip((Side.CONVEX, Side.CONCAVE), shade):
            pts = grids[(Member.GEAR, s)].point @ R.T
            label = f"gear {s.value}" if k == 0 else None
            surfaces.append((label or "", pair.to_pair_frame(Member.GEAR, pts), color))
    surfaces = [(lab if lab else "_", p, c) for lab, p, c in surfaces]
    # two cameras on the pinion axis side (the pinion tooth in front of the gear flanks), azimuths either side of
    # the tooth's lengthwise direction
    views = [("from the pinion axis side: the pinion tooth in front of the gear teeth", 20.0, 150.0),
             ("from the pinion axis side, higher and 50° further round", 50.0, 200.0)]
    return save_figure(plot_surfaces_3d(surfaces, title="Meshing tooth pair (pair frame, zero roll)", views=views),
                       out / "meshing_pair_3d.png")


def transverse_section(pair, grids, out: Path) -> str:
    """PNG of the tooth profiles of both members on the sphere of the mean cone distance, pair frame, zero roll."""
    from .._core.rotations import rot_z
    from ..geometry.sections import sphere_section
    from ..viz.pair3d import plot_transverse_section

    g1 = pair.pinion.pitch_angle
    Rm = pair.pinion.mean_cone_distance
    ex, ey = np.array([0.0, 1.0, 0.0]), np.array([math.cos(g1), 0.0, -math.sin(g1)])
    profiles = []
    # one pinion tooth (its neighbours would be seen too obliquely in this projection) between gear teeth
    for member, color, z, ks in ((Member.PINION, "tab:blue", pair.pinion.teeth, (0,)),
                                 (Member.GEAR, "tab:red", pair.gear.teeth, (-1, 0, 1))):
        for k in ks:
            R = rot_z(2 * math.pi * k / z)
            for s in (Side.CONVEX, Side.CONCAVE):
                prof = sphere_section(grids[(member, s)].point @ R.T, Rm)
                if len(prof) < 2:
                    continue
                P = pair.to_pair_frame(member, prof)
                profiles.append((member.value, np.stack([P @ ex, P @ ey], -1), color))
    # shift so the pitch point (Rm p) is the origin of the height axis
    p = np.array([math.sin(g1), 0.0, math.cos(g1)]) * Rm
    profiles = [(lab, xy - np.array([0.0, p @ ey]), c) for lab, xy, c in profiles]
    fig = plot_transverse_section(profiles, title=f"Meshing teeth on the sphere R = {Rm:.3f} mm (zero roll)")
    return save_figure(fig, out / "transverse_section.png")


#: fillet rows of the CAD grids, cutter-tip line to fillet/blade junction: with 9 rows the B-spline fillet face stays
#: within 5e-4 mm of the generated fillet (tests/io/test_step_generated.py)
CAD_FILLET_ROWS = 9


def cad_teeth(spec, blank, setups, n_face: int, n_profile: int) -> tuple[dict, list[str]]:
    """Grids of one whole tooth per member for STL/STEP, the generated fillets included.

    Returns ({member: {"tooth": (convex, concave), "fillet_rows": k, "gear": ..., "gear_fillet_rows": ...}},
    warnings). Each grid is (points, normals) with rows 0..k on the fillet (row k the junction, held once). Where the
    root edges of neighbouring teeth cross (the cutter is wider than the tooth space at the root), the warning names
    the design-file key of the point width and the whole gear is built from the flanks above the fillets.
    """
    from ..geometry.solid import root_slot_width
    from . import facemilled as fm

    k = CAD_FILLET_ROWS
    keep = np.r_[0:k - 1, k:k + n_profile]  # drop the blade's copy of the junction row
    out, warnings = {}, []
    for m in fm.MEMBERS:
        grids = {}
        for s in fm.SIDES:
            g = setups[(m, s)].flank.grid(n_face, n_profile, n_fillet=k)
            grids[s] = (g.points[:, keep], g.normals[:, keep])
        rot = fm.tooth_rotation(blank, setups, m)
        tooth = (grids[Side.CONVEX], fm.rotate_grid(*grids[Side.CONCAVE], rot))
        z = int(blank.z1 if m is Member.PINION else blank.z2)
        entry = {"tooth": tooth, "fillet_rows": k - 1, "gear": tooth, "gear_fillet_rows": k - 1}
        width = float(root_slot_width(tooth[0][0], tooth[1][0], z).min())
        if width <= 0.0:
            keys = [f"face_milling.{m.value}_{s.value}.cutter.point_width" for s in fm.SIDES
                    if getattr(spec.face_milling, f"{m.value}_{s.value}").cutter is not None]
            key = " / ".join(keys) or "face_milling.point_width"
            warnings.append(
                f"{m.value}: the cutter does not fit the tooth space at the root (the root edges of neighbouring "
                f"teeth cross by {-width:.3f} mm): reduce {key}; the whole {m.value} (STL, STEP) is built from the "
                f"flanks above the fillets, the tooth files keep them")
            blade = tuple((p[:, k - 1:], n[:, k - 1:]) for p, n in tooth)
            entry.update(gear=blade, gear_fillet_rows=0)
        out[m] = entry
    return out, warnings


def _cad(tooth_grids_by_member, cad):
    if cad is not None:
        return cad
    return {m: {"tooth": t, "fillet_rows": 0, "gear": t, "gear_fillet_rows": 0}
            for m, t in tooth_grids_by_member.items()}


def stl_files(tooth_grids_by_member, teeth, out: Path, cad=None) -> list[str]:
    """STL of one tooth and of the whole gear for each member (``cad``: :func:`cad_teeth`, with the fillets)."""
    from ..geometry.solid import gear_mesh, tooth_mesh
    from ..io.stl import write_stl

    names = []
    for member, c in _cad(tooth_grids_by_member, cad).items():
        write_stl(out / f"{member.value}_tooth.stl", tooth_mesh(*c["tooth"]), name=f"{member.value} tooth")
        gear = gear_mesh(*c["gear"], teeth[member])  # type: ignore[call-arg]  # c["gear"] = (convex, concave)
        write_stl(out / f"{member.value}.stl", gear, name=member.value)
        names += [f"{member.value}_tooth.stl", f"{member.value}.stl"]
    return names


def step_files(tooth_grids_by_member, out: Path, teeth=None, cad=None) -> list[str]:
    """STEP solids (extra ``cad``) per member: one tooth (exact B-spline flank and fillet faces), and with ``teeth``
    ({member: z}) the whole gear, that tooth placed z times and fused with the body."""
    from ..io.step import write_step

    names = []
    for member, c in _cad(tooth_grids_by_member, cad).items():
        name = f"{member.value}_tooth.step"
        (cx, _), (cc, _) = c["tooth"]
        write_step(out / name, cx, cc, solid=True, fillet_rows=c["fillet_rows"])
        names.append(name)
        if teeth is not None:
            (gx, _), (gc, _) = c["gear"]
            write_step(out / f"{member.value}.step", gx, gc, solid=True, z=int(teeth[member]),
                       fillet_rows=c["gear_fillet_rows"])
            names.append(f"{member.value}.step")
    return names


def axial_section(grids, out: Path, title: str, tooth=None, blank=None) -> str:
    """PNG of every generated flank grid drawn in its member's axial section (axial position vs radius), with the
    blank outline; with ``tooth`` ({member: (convex, concave) grids of one tooth}) also the tooth profile on the
    sphere of the mean cone distance."""
    from ..geometry.sections import tooth_profile
    from ..viz.axial_section import plot_axial_section

    members = []
    for member in (Member.PINION, Member.GEAR):
        members.append({
            "name": member.value,
            "grids": {s.value: grids[(member, s)].points for s in (Side.CONVEX, Side.CONCAVE) if (member, s) in grids},
            "outline": blank_outline(blank, member) if blank is not None else None,
            "profile": (tooth_profile(np.asarray(tooth[member][0][0]), np.asarray(tooth[member][1][0]), blank.Rm)
                        if tooth is not None else None),
            "radius": blank.Rm if blank is not None else None,
        })
    return save_figure(plot_axial_section(members, title), out / "axial_section.png")


def blank_outline(blank, member):
    """(5, 2) axial position and radius, mm, of the blank's root, face, toe and heel lines in the axial section
    (front and back cones perpendicular to the pitch cone), closed."""
    i = member.index
    d, da, df = (getattr(blank, f"{n}{i}") for n in ("delta", "delta_a", "delta_f"))
    Ri, Re, Rm = getattr(blank, f"Ri{i}"), getattr(blank, f"Re{i}"), blank.Rm
    ham, hfm = getattr(blank, f"ham{i}"), getattr(blank, f"hfm{i}")
    R = np.array([Ri, Re, Re, Ri, Ri])
    h = np.array([-hfm - (Ri - Rm) * math.tan(d - df), -hfm - (Re - Rm) * math.tan(d - df),
                  ham + (Re - Rm) * math.tan(da - d), ham + (Ri - Rm) * math.tan(da - d),
                  -hfm - (Ri - Rm) * math.tan(d - df)])
    return np.stack([R * math.cos(d) - h * math.sin(d), R * math.sin(d) + h * math.cos(d)], -1)
