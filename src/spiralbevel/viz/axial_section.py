"""Flank grids in the axial section of each member, with the blank outline and the tooth profile."""

from __future__ import annotations

import numpy as np

_COLORS = {"convex": "tab:blue", "concave": "tab:red"}


def plot_axial_section(members, title=""):
    """One column per member: the flank grids projected into the axial section, and the tooth profile.

    Parameters
    ----------
    members : list of dict
        Per member: ``name``; ``grids`` {side name: (n, m, 3) points, mm}; ``outline`` (k, 2) (axial, radius) mm of
        the blank, or None; ``profile`` (convex, concave) list of (k, 2) (arc, radius) mm, or None; ``radius`` mm of
        the profile's sphere.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    rows = 2 if any(m.get("profile") is not None for m in members) else 1
    fig, axes = plt.subplots(rows, len(members), figsize=(5.5 * len(members), 4.6 * rows), squeeze=False)
    for col, m in enumerate(members):
        ax = axes[0, col]
        if m.get("outline") is not None:
            o = np.asarray(m["outline"])
            ax.plot(o[:, 0], o[:, 1], "k--", lw=0.8, label="blank")
        for side, pts in m["grids"].items():
            z, r = pts[..., 2], np.hypot(pts[..., 0], pts[..., 1])
            ax.plot(z, r, color=_COLORS[side], lw=0.4)
            ax.plot(z.T, r.T, color=_COLORS[side], lw=0.4)
            ax.plot([], [], color=_COLORS[side], label=side)
        ax.set_title(f"{m['name']}: flank grids in the axial section")
        ax.set_xlabel("axial position z [mm]")
        ax.set_ylabel("radius [mm]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.legend(fontsize=8)
        if rows == 2:
            ax = axes[1, col]
            if m.get("profile") is None:
                ax.set_visible(False)
                continue
            for xy, side in zip(m["profile"], ("convex", "concave")):
                ax.plot(xy[:, 0], xy[:, 1], color=_COLORS[side], label=side)
            ax.set_title(f"{m['name']}: tooth profile on the sphere R = {m['radius']:.3f} mm")
            ax.set_xlabel("arc from the tooth centre [mm]")
            ax.set_ylabel("radius from the axis [mm]")
            ax.set_aspect("equal", adjustable="datalim")
            ax.legend(fontsize=8)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig
