"""Maps of scalar fields over tooth flanks drawn on the projected tooth (axial position vs radius)."""

from __future__ import annotations

import numpy as np

from .layout import fixed_layout, panel_title


def projected(points):
    """Axial position z and radius from the axis of member-frame points (..., 3), mm."""
    points = np.asarray(points, float)
    return points[..., 2], np.hypot(points[..., 0], points[..., 1])


def ordered_curvatures(k1, k2):
    """(kappa_max, kappa_min) = (max(k1, k2), min(k1, k2)) pointwise, 1/mm: the principal curvatures ordered by value,
    continuous over a flank (unlike curvatures labelled by the nearer of two reference directions)."""
    k1, k2 = np.asarray(k1, float), np.asarray(k2, float)
    return np.maximum(k1, k2), np.minimum(k1, k2)


def plot_flank_fields(panels, title="", cmap="coolwarm", symmetric=True):
    """Draw one or more scalar fields on projected flanks.

    Parameters
    ----------
    panels : list of (label : str, points : (n, m, 3) float mm, values : (n, m) float, unit : str)
        One subplot each.
    title : str
        Figure title.
    symmetric : bool
        Colour scale symmetric about 0 (for signed curvatures).

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    n = len(panels)
    cols = min(n, 4)
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.6 * rows), squeeze=False)
    for ax, (label, pts, vals, unit) in zip(axes.flat, panels):
        z, r = projected(pts)
        vals = np.asarray(vals, float)
        vmax = np.nanmax(np.abs(vals)) if symmetric else None
        kw = dict(vmin=-vmax, vmax=vmax) if symmetric and vmax > 0 else {}
        mesh = ax.pcolormesh(z, r, vals, shading="gouraud", cmap=cmap, **kw)
        _outline(ax, z, r)
        panel_title(ax, label, fontsize=9)
        ax.set_xlabel("axial position z [mm]")
        ax.set_ylabel("radius [mm]")
        ax.set_aspect("equal", adjustable="datalim")
        fig.colorbar(mesh, ax=ax, label=unit, shrink=0.85)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    if title:
        fig.suptitle(title)
    fixed_layout(fig, rows, cols, right=1.0, suptitle=bool(title))
    return fig


def _outline(ax, z, r):
    """Toe, heel, root and top lines of a projected flank grid."""
    for zz, rr in ((z[0], r[0]), (z[-1], r[-1]), (z[:, 0], r[:, 0]), (z[:, -1], r[:, -1])):
        ax.plot(zz, rr, color="k", lw=0.8)


def plot_domain_fields(panels, title="", ncols=4):
    """Scalar fields over flank parameter domains.

    Parameters
    ----------
    panels : list of (label : str, x : (n, m) float, y : (n, m) float, values : (n, m) float, xlabel, ylabel, unit)
    """
    import matplotlib.pyplot as plt

    n = len(panels)
    rows = int(np.ceil(n / ncols))
    fig, axes = plt.subplots(rows, ncols, figsize=(4.25 * ncols, 3.75 * rows), squeeze=False)
    for ax, (label, x, y, vals, xlabel, ylabel, unit) in zip(axes.flat, panels):
        mesh = ax.pcolormesh(x, y, vals, shading="gouraud", cmap="viridis")
        panel_title(ax, label, fontsize=9)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        fig.colorbar(mesh, ax=ax, label=unit, shrink=0.85)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    if title:
        fig.suptitle(title)
    fixed_layout(fig, rows, ncols, right=1.0, suptitle=bool(title))
    return fig
