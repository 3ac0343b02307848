"""Files of the main job: plots, STL, STEP, tool-path CSV. Each writer returns the names it wrote."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..conventions import Member, Side


def save_figure(fig, path: Path) -> str:
    """Save a matplotlib figure as PNG (150 dpi) and close it."""
    import matplotlib.pyplot as plt

    fig.savefig(path, dpi=150)
    plt.close(fig)
    return path.name


def draft_maps(results, out: Path) -> str:
    """PNG of the forging-draft maps of several flanks: ``results`` is a list of (label, DraftResult)."""
    import matplotlib.pyplot as plt

    from ..viz.draft_plot import plot_draft

    n = len(results)
    cols = 2
    fig, axes = plt.subplots((n + 1) // cols, cols, figsize=(11, 4.2 * ((n + 1) // cols)), squeeze=False)
    for ax, (label, r) in zip(axes.flat, results):
        plot_draft(r, ax=ax)
        d = np.round(r.die_direction, 3)
        ax.set_title(f"{label}: n_out . v_d > 0 (no draft) on {100 * r.failing_area_fraction:.1f} % of the area, "
                     f"v_d = {tuple(float(c) for c in d)}", fontsize=8)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    fig.tight_layout()
    return save_figure(fig, out / "draft_map.png")


def curvature_maps(grids, out: Path, title: str, labels=("k1 (profile)", "k2 (lengthwise)")) -> str:
    """PNG of k1 and k2 over every flank, drawn on the projected tooth (convex = positive)."""
    from ..viz.flank_maps import plot_flank_fields

    panels = []
    for (m, s), g in grids.items():
        panels.append((f"{m.value} {s.value}: {labels[0]}", g.point, g.k1, "1/mm"))
        panels.append((f"{m.value} {s.value}: {labels[1]}", g.point, g.k2, "1/mm"))
    return save_figure(plot_flank_fields(panels, title=title), out / "curvature_maps.png")


def curvature_domain_maps(pair, grids, out: Path) -> str:
    """PNG of k1 and k2 of every log-spiral flank over its parameter domain (the parallelogram in (varphi, phi))."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 4, figsize=(17, 7.5), squeeze=False)
    for col, ((m, s), g) in enumerate(grids.items()):
        f = pair.flank(m, s)
        varphi = np.asarray(g.psi) / math.sin(f.surface.base_cone_angle) + _phi_of(f, g)
        phi = _phi_of(f, g)
        for row, (name, vals) in enumerate((("k1 (profile)", g.k1), ("k2 (lengthwise)", g.k2))):
            ax = axes[row, col]
            mesh = ax.pcolormesh(np.degrees(varphi), np.degrees(phi), vals, shading="gouraud", cmap="viridis")
            ax.set_title(f"{m.value} {s.value}: {name}", fontsize=9)
            ax.set_xlabel("rolling angle varphi [deg]")
            ax.set_ylabel("spiral parameter phi [deg]")
            fig.colorbar(mesh, ax=ax, label="1/mm (convex +)", shrink=0.85)
    fig.suptitle("Principal curvatures over the parallelogram domains (seed 000 Eq. (16))")
    fig.tight_layout()
    return save_figure(fig, out / "curvature_domain.png")


def _phi_of(flank, g):
    """phi of grid points (LogSpiralFlank.phi_of_rho)."""
    return flank.surface.phi_of_rho(np.asarray(g.rho))


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
    # look down the pitch line from beyond the heel: the tooth's cross-section between the two gear teeth
    elev = 90.0 - math.degrees(pair.pinion.pitch_angle)
    return save_figure(plot_surfaces_3d(surfaces, title="Meshing tooth pair (pair frame, zero roll), seen from the heel",
                                        elev=elev, azim=0.0), out / "meshing_pair_3d.png")


def _sphere_profile(points, radius):
    """One point per grid column where the toe->heel rows cross the sphere |r| = radius (linear interpolation)."""
    r = np.linalg.norm(points, axis=-1) - radius
    out = []
    for j in range(points.shape[1]):
        g = r[:, j]
        k = np.nonzero(np.diff(np.sign(g)))[0]
        if k.size:
            i = k[0]
            t = g[i] / (g[i] - g[i + 1])
            out.append(points[i, j] + t * (points[i + 1, j] - points[i, j]))
    return np.array(out).reshape(-1, 3)


def transverse_section(pair, grids, out: Path) -> str:
    """PNG of the tooth profiles of both members on the sphere of the mean cone distance, pair frame, zero roll."""
    from .._core.rotations import rot_z
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
                prof = _sphere_profile(grids[(member, s)].point @ R.T, Rm)
                if len(prof) < 2:
                    continue
                P = pair.to_pair_frame(member, prof)
                profiles.append((member.value, np.stack([P @ ex, P @ ey], -1), color))
    # shift so the pitch point (Rm p) is the origin of the height axis
    p = np.array([math.sin(g1), 0.0, math.cos(g1)]) * Rm
    profiles = [(lab, xy - np.array([0.0, p @ ey]), c) for lab, xy, c in profiles]
    fig = plot_transverse_section(profiles, title=f"Meshing teeth on the sphere R = {Rm:.3f} mm (zero roll)")
    return save_figure(fig, out / "transverse_section.png")


def stl_files(tooth_grids_by_member, teeth, out: Path) -> list[str]:
    """STL of one tooth and of the whole gear for each member."""
    from ..geometry.solid import gear_mesh, tooth_mesh
    from ..io.stl import write_stl

    names = []
    for member, (convex, concave) in tooth_grids_by_member.items():
        write_stl(out / f"{member.value}_tooth.stl", tooth_mesh(convex, concave), name=f"{member.value} tooth")
        write_stl(out / f"{member.value}.stl", gear_mesh(convex, concave, teeth[member]), name=member.value)
        names += [f"{member.value}_tooth.stl", f"{member.value}.stl"]
    return names


def step_files(tooth_grids_by_member, out: Path) -> list[str]:
    """STEP with exact B-spline flank surfaces of one tooth per member (extra ``cad``)."""
    from ..io.step import write_step

    names = []
    for member, (convex, concave) in tooth_grids_by_member.items():
        name = f"{member.value}_tooth.step"
        write_step(out / name, convex, concave, solid=True)
        names.append(name)
    return names


def as_points(values) -> np.ndarray:
    return np.asarray(values, float)


def axial_section(grids, out: Path, title: str, tooth=None, blank=None) -> str:
    """PNG of every generated flank grid drawn in its member's axial section (axial position vs radius), with the
    blank outline; with ``tooth`` ({member: (convex, concave) grids of one tooth}) also the tooth profile on the
    sphere of the mean cone distance."""
    import matplotlib.pyplot as plt

    rows = 2 if tooth is not None else 1
    fig, axes = plt.subplots(rows, 2, figsize=(11, 4.6 * rows), squeeze=False)
    if tooth is not None:
        for ax, member in zip(axes[1], (Member.PINION, Member.GEAR)):
            _tooth_profile(ax, member, tooth[member], blank.Rm)
    for ax, member in zip(axes[0], (Member.PINION, Member.GEAR)):
        if blank is not None:
            _blank_outline(ax, blank, member)
        for side, color in ((Side.CONVEX, "tab:blue"), (Side.CONCAVE, "tab:red")):
            g = grids.get((member, side))
            if g is None:
                continue
            z, r = g.points[..., 2], np.hypot(g.points[..., 0], g.points[..., 1])
            ax.plot(z, r, color=color, lw=0.4)
            ax.plot(z.T, r.T, color=color, lw=0.4)
            ax.plot([], [], color=color, label=side.value)
        ax.set_title(f"{member.value}: flank grids in the axial section")
        ax.set_xlabel("axial position z [mm]")
        ax.set_ylabel("radius [mm]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    return save_figure(fig, out / "axial_section.png")


def _blank_outline(ax, blank, member):
    """Face cone, root cone, toe and heel of the blank in the axial section (front/back cones normal to the pitch
    cone), dashed."""
    i = member.index
    d, da, df = (getattr(blank, f"{n}{i}") for n in ("delta", "delta_a", "delta_f"))
    Ri, Re, Rm = getattr(blank, f"Ri{i}"), getattr(blank, f"Re{i}"), blank.Rm
    ham, hfm = getattr(blank, f"ham{i}"), getattr(blank, f"hfm{i}")
    R = np.array([Ri, Re])
    top = ham + (R - Rm) * math.tan(da - d)
    root = -hfm - (R - Rm) * math.tan(d - df)

    def zr(R, h):
        return R * math.cos(d) - h * math.sin(d), R * math.sin(d) + h * math.cos(d)

    corners = [zr(R[0], root[0]), zr(R[1], root[1]), zr(R[1], top[1]), zr(R[0], top[0]), zr(R[0], root[0])]
    ax.plot([c[0] for c in corners], [c[1] for c in corners], "k--", lw=0.8, label="blank")


def _tooth_profile(ax, member, grids, radius):
    """Both flank profiles of one tooth on the sphere |r| = radius, in (arc from the tooth centre, radius) mm."""
    pts = [_sphere_profile(np.asarray(g[0], float), radius) for g in grids]
    if any(len(p) < 2 for p in pts):
        ax.set_visible(False)
        return
    allp = np.concatenate(pts)
    az0 = float(np.angle(np.mean(np.exp(1j * np.arctan2(allp[:, 1], allp[:, 0])))))
    for p, side, color in zip(pts, (Side.CONVEX, Side.CONCAVE), ("tab:blue", "tab:red")):
        az = np.angle(np.exp(1j * (np.arctan2(p[:, 1], p[:, 0]) - az0)))
        rr = np.hypot(p[:, 0], p[:, 1])
        ax.plot(az * rr, rr, color=color, label=side.value)
    ax.set_title(f"{member.value}: tooth profile on the sphere R = {radius:.3f} mm")
    ax.set_xlabel("arc from the tooth centre [mm]")
    ax.set_ylabel("radius from the axis [mm]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(fontsize=8)
