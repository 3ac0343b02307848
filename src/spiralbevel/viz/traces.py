"""Tooth traces on the developed pitch cone."""

from __future__ import annotations

import numpy as np

from .layout import fixed_layout


def pitch_cone_trace(points, pitch_angle):
    """Intersect a flank grid with the pitch cone (apex at the origin, half-angle ``pitch_angle``).

    Parameters
    ----------
    points : (n, m, 3) float, mm
        Flank grid, toe→heel along axis 0, root→top along axis 1 (member frame).
    pitch_angle : float, rad

    Returns
    -------
    (k, 3) float, mm
        Points of the trace (rows of the grid where the flank crosses the cone, linear interpolation across the
        profile). Rows that do not cross the cone are skipped.
    """
    points = np.asarray(points, float)
    cone = np.arctan2(np.hypot(points[..., 0], points[..., 1]), points[..., 2]) - pitch_angle
    out = []
    for row, g in zip(points, cone):
        s = np.nonzero(np.diff(np.sign(g)))[0]
        if s.size:
            j = s[0]
            t = g[j] / (g[j] - g[j + 1])
            out.append(row[j] + t * (row[j + 1] - row[j]))
    return np.array(out).reshape(-1, 3)


def develop(points, pitch_angle, azimuth0=0.0):
    """Develop points on a cone of half-angle ``pitch_angle`` into the plane: (x, y) mm in the development.

    The axial plane at azimuth ``azimuth0`` (rad) maps onto the developed x-axis.
    """
    points = np.asarray(points, float)
    R = np.linalg.norm(points, axis=-1)
    az = np.angle(np.exp(1j * (np.arctan2(points[..., 1], points[..., 0]) - azimuth0)))
    theta = np.unwrap(az) * np.sin(pitch_angle)
    return R * np.cos(theta), R * np.sin(theta)


def plot_pitch_traces(traces, title="Tooth traces on the developed pitch cones"):
    """Plot developed tooth traces.

    Parameters
    ----------
    traces : list of (group : str, label : str, points : (k, 3) float mm, pitch_angle : float rad)
        One subplot per group (e.g. per member); each group is developed about the mean azimuth of its points so
        that its tooth lies along the developed x-axis (cone distance).
    """
    import matplotlib.pyplot as plt

    groups = list(dict.fromkeys(t[0] for t in traces))
    fig, axes = plt.subplots(1, len(groups), figsize=(5.5 * len(groups), 4.5), squeeze=False)
    for ax, group in zip(axes[0], groups):
        members = [t for t in traces if t[0] == group and len(t[2]) >= 2]
        if not members:
            continue
        allpts = np.concatenate([t[2] for t in members])
        az0 = float(np.angle(np.mean(np.exp(1j * np.arctan2(allpts[:, 1], allpts[:, 0])))))
        for _, label, pts, gamma in members:
            x, y = develop(pts, gamma, az0)
            ax.plot(x, y, label=label)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("cone distance along the developed axis [mm]")
        ax.set_ylabel("developed arc [mm]")
        ax.set_title(group)
        ax.legend(fontsize=8)
    fig.suptitle(title)
    fixed_layout(fig, 1, len(groups), left=0.75, right=0.2, wspace=0.95, suptitle=True)
    return fig
