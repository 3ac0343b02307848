"""3-D view of meshing tooth flanks in the pair frame."""

from __future__ import annotations

import numpy as np


def plot_surfaces_3d(surfaces, title="", elev=25, azim=-60):
    """Draw point grids as shaded surfaces.

    Parameters
    ----------
    surfaces : list of (label : str, points : (n, m, 3) float mm, color : str)
    title : str

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(7.5, 6.5))
    ax = fig.add_subplot(projection="3d")
    allpts = []
    for label, pts, color in surfaces:
        pts = np.asarray(pts, float)
        ax.plot_surface(pts[..., 0], pts[..., 1], pts[..., 2], color=color, alpha=0.85, linewidth=0.2,
                        edgecolor="k", shade=True)
        ax.plot([], [], color=color, lw=6, label=label)
        allpts.append(pts.reshape(-1, 3))
    allpts = np.concatenate(allpts)
    lo, hi = allpts.min(0), allpts.max(0)
    c, half = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(c[0] - half, c[0] + half)
    ax.set_ylim(c[1] - half, c[1] + half)
    ax.set_zlim(c[2] - half, c[2] + half)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_zlabel("z [mm]")
    ax.view_init(elev=elev, azim=azim)
    ax.legend(loc="upper left", fontsize=8)
    if title:
        ax.set_title(title)
    fig.tight_layout()
    return fig


def plot_transverse_section(profiles, title=""):
    """Tooth profiles of a meshing pair in the transverse (spherical) section, projected on the pitch-point plane.

    Parameters
    ----------
    profiles : list of (label : str, xy : (k, 2) float mm, color : str)
        Profile polylines in the plane tangent to the sphere at the mean pitch point: x across the teeth, y along
        the pinion's addendum direction.
    """
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    seen = set()
    for label, xy, color in profiles:
        xy = np.asarray(xy, float)
        ax.plot(xy[:, 0], xy[:, 1], color=color, lw=1.6, label=None if label in seen else label)
        seen.add(label)
    ax.axhline(0.0, color="0.5", lw=0.6, ls="--")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("across the teeth [mm]")
    ax.set_ylabel("toward the pinion tip [mm]")
    ax.legend(fontsize=8, loc="upper right")
    if title:
        ax.set_title(title)
    fig.tight_layout()
    return fig
