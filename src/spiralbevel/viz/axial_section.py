"""Flank grids in the axial section of each member, with the blank outline and the tooth profile."""

from __future__ import annotations

import numpy as np

from .layout import fixed_layout

_COLORS = {"convex": "tab:blue", "concave": "tab:red"}


def plot_axial_section(members, title=""):
    """One column per member; one row per flank side (its grid projected into the axial section, with the blank
    outline), and a row with the tooth profile of both sides.

    The convex and concave grids cover nearly the same region of the axial section, so each has its own panel
    instead of being drawn over the other.

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

    sides = [s for s in ("convex", "concave") if any(s in m["grids"] for m in members)]
    profile = any(m.get("profile") is not None for m in members)
    rows = len(sides) + int(profile)
    fig, axes = plt.subplots(rows, len(members), figsize=(5.8 * len(members), 4.3 * rows), squeeze=False)
    for col, m in enumerate(members):
        for row, side in enumerate(sides):
            ax = axes[row, col]
            if m.get("outline") is not None:
                o = np.asarray(m["outline"])
                ax.plot(o[:, 0], o[:, 1], "k--", lw=0.8, label="blank")
            pts = m["grids"].get(side)
            if pts is None:
                ax.set_visible(False)
                continue
            z, r = pts[..., 2], np.hypot(pts[..., 0], pts[..., 1])
            ax.plot(z, r, color=_COLORS[side], lw=0.4)
            ax.plot(z.T, r.T, color=_COLORS[side], lw=0.4)
            ax.plot([], [], color=_COLORS[side], label=f"{side} flank grid")
            ax.set_title(f"{m['name']}, {side} flank: grid in the axial section", fontsize=10)
            ax.set_xlabel("axial position z [mm]")
            ax.set_ylabel("radius [mm]")
            ax.set_aspect("equal", adjustable="datalim")
            ax.legend(fontsize=8, loc="best")
        if profile:
            ax = axes[-1, col]
            if m.get("profile") is None:
                ax.set_visible(False)
                continue
            for xy, side in zip(m["profile"], ("convex", "concave")):
                ax.plot(xy[:, 0], xy[:, 1], color=_COLORS[side], label=side)
            ax.set_title(f"{m['name']}: tooth profile on the sphere R = {m['radius']:.3f} mm", fontsize=10)
            ax.set_xlabel("arc from the tooth centre [mm]")
            ax.set_ylabel("radius from the axis [mm]")
            ax.set_aspect("equal", adjustable="datalim")
            ax.legend(fontsize=8)
    if title:
        fig.suptitle(title)
    fixed_layout(fig, rows, len(members), left=0.75, right=0.3, wspace=0.9, hspace=0.85, suptitle=bool(title))
    return fig
