"""Tooth traces on the developed pitch cone."""

from __future__ import annotations

import numpy as np


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


def develop(points, pitch_angle):
    """Develop points on a cone of half-angle ``pitch_angle`` into the plane: (x, y) mm in the development."""
    points = np.asarray(points, float)
    R = np.linalg.norm(points, axis=-1)
    theta = np.unwrap(np.arctan2(points[..., 1], points[..., 0])) * np.sin(pitch_angle)
    return R * np.cos(theta), R * np.sin(theta)


def plot_pitch_traces(traces, title="Tooth traces on the developed pitch cones"):
    """Plot developed tooth traces.

    Parameters
    ----------
    traces : list of (label : str, points : (k, 3) float mm, pitch_angle : float rad)
    """
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 5))
    for label, pts, gamma in traces:
        if len(pts) < 2:
            continue
        x, y = develop(pts, gamma)
        ax.plot(x, y, label=label)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("developed x [mm]")
    ax.set_ylabel("developed y [mm]")
    ax.legend(fontsize=8)
    ax.set_title(title)
    fig.tight_layout()
    return fig
