"""Plots of a loaded tooth contact analysis (:class:`~spiralbevel.meshing.ltca.result.LTCAResult`).

matplotlib is imported lazily inside the functions.
"""

from __future__ import annotations

import numpy as np

from .layout import fixed_layout

__all__ = ["plot_ltca"]


def plot_ltca(result, member: str = "gear", fig=None, outline=None, title=None):
    """Three panels: unloaded and loaded transmission error (arcsec), load share per pair, and the contact pressure
    over the flank of ``member`` as a filled map (all positions of the mesh cycle together, projected on the member's
    axial plane: axial z versus radius, mm) inside the flank outline.

    Parameters
    ----------
    result : LTCAResult
    member : {"gear", "pinion"}
    fig : matplotlib.figure.Figure, optional
    outline : (n, m, 3) float, mm, optional
        The flank grid of ``member`` in its frame (rows toe -> heel, columns root -> top): its toe, heel, root and top
        lines are drawn and labelled around the pressure map.
    title : str, optional
        Figure title above the three panels.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    own = fig is None
    if own:
        fig = plt.figure(figsize=(12, 4))
    ax1, ax2, ax3 = fig.subplots(1, 3)
    x = np.degrees(result.pinion_angles)
    for j in range(result.te_pairs.shape[1]):
        ax1.plot(x, result.te_pairs[:, j], ":", lw=1, label=f"unloaded {result.pair_names[j]}" if result.pair_names
                 else None)
    ax1.plot(x, result.te_unloaded, "k-", lw=1.5, label="unloaded")
    ax1.plot(x, result.te_loaded, "r-", lw=1.5, label=f"loaded, T = {result.torque / 1000:.4g} N m")
    # the range of the loaded and unloaded TE: pairs that trail far below it (edge contacts followed for the loaded
    # solve, carrying no load) are clipped
    band = np.concatenate([np.asarray(result.te_unloaded, float), np.asarray(result.te_loaded, float)])
    if np.isfinite(band).any():
        lo, hi = np.nanmin(band), np.nanmax(band)
        pad = 0.25 * (hi - lo) + 1.0
        ax1.set_ylim(lo - pad, hi + pad)
    ax1.set_xlabel("pinion rotation φ1 − φ10 (deg)")
    ax1.set_ylabel("transmission error (arcsec)")
    ax1.legend(fontsize=7)
    ax1.set_title("transmission error, unloaded and loaded", fontsize=9)
    for j in range(result.load_share.shape[1]):
        ax2.plot(x, result.load_share[:, j], label=result.pair_names[j] if result.pair_names else None)
    ax2.set_xlabel("pinion rotation φ1 − φ10 (deg)")
    ax2.set_title("load share of each tooth pair", fontsize=9)
    if result.pair_names:
        ax2.legend(fontsize=7)
    ax2.set_ylabel("load share (-)")
    ax2.set_ylim(-0.05, 1.05)
    pts = np.concatenate(result.points2 if member == "gear" else result.points1)
    p = np.concatenate(result.pressure)
    pressure_map(ax3, pts[:, 2], np.hypot(pts[:, 0], pts[:, 1]), p, fig=fig)
    if outline is not None:
        from .tca_plot import _label_outside, _outline_lines, project_axial_radial

        lines = _outline_lines(np.asarray(outline, float))
        for line, _ in lines:
            q = project_axial_radial(line)
            ax3.plot(q[:, 0], q[:, 1], "k-", lw=1.0)
        _label_outside(ax3, lines)
        ax3.set_aspect("equal", adjustable="datalim")
        ax3.margins(0.1)
    ax3.set_xlabel("axial position z (mm)")
    ax3.set_ylabel("radius (mm)")
    ax3.set_title(f"contact pressure on the {member} flank over the mesh cycle,\npeak {result.peak_pressure:.0f} N/mm²",
                  fontsize=9)
    if title:
        fig.suptitle(title)
    if own:  # fixed margins; the pressure map's colour bar sits in the right margin
        fixed_layout(fig, 1, 3, left=0.75, right=0.9, bottom=0.6, top=0.55, wspace=1.05, suptitle=bool(title))
    else:
        fig.tight_layout()
    return fig


def pressure_map(ax, x, y, p, fig=None, levels=12):
    """Filled map of contact pressures known at scattered points (x, y), mm, N/mm^2: linear interpolation on their
    Delaunay triangulation, zero-pressure points included so that the map falls to zero at the contact's edge.

    Triangles much longer than the point spacing (those that bridge a gap between contact lines at the edge of the
    point cloud) are left blank. Returns the ``tricontourf`` artist (its colour bar is added when ``fig`` is given);
    points that span no area (a single contact line) are drawn as dots instead.
    """
    import matplotlib.tri as mtri

    x, y, p = (np.asarray(a, float).ravel() for a in (x, y, p))
    keep = np.isfinite(x) & np.isfinite(y) & np.isfinite(p)
    x, y, p = x[keep], y[keep], np.maximum(p[keep], 0.0)
    try:
        tri = mtri.Triangulation(x, y)
    except (ValueError, RuntimeError):  # fewer than 3 points, or all on one line: no area to fill
        sc = ax.scatter(x, y, c=p, s=6, cmap="viridis")
        if fig is not None:
            fig.colorbar(sc, ax=ax, label="contact pressure (N/mm²)")
        return sc
    t = tri.triangles
    edge = np.max(np.hypot(x[t] - x[np.roll(t, 1, axis=1)], y[t] - y[np.roll(t, 1, axis=1)]), axis=1)
    tri.set_mask(edge > 4.0 * np.median(edge))
    peak = float(p.max()) if p.size and p.max() > 0 else 1.0
    cs = ax.tricontourf(tri, p, levels=np.linspace(0.0, peak, levels + 1), cmap="viridis")
    if fig is not None:
        fig.colorbar(cs, ax=ax, label="contact pressure (N/mm²)")
    return cs
