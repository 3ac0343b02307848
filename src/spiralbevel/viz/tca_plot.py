"""Plots of a :class:`~spiralbevel.meshing.tca_result.TCAResult`: transmission errors, contact paths on the projected
teeth (axial position vs radius) and instantaneous contact ellipses. matplotlib is imported lazily."""

from __future__ import annotations

import numpy as np

from ..errors import MissingDependencyError
from .layout import fixed_layout

__all__ = ["plot_tca", "project_axial_radial"]

ARCSEC = np.pi / (180.0 * 3600.0)


def _plt():
    try:
        import matplotlib.pyplot as plt
    except ImportError as err:  # pragma: no cover - matplotlib is a core dependency
        raise MissingDependencyError("matplotlib", "all", "plotting a TCA result") from err
    return plt


def project_axial_radial(points):
    """(axial z, radius sqrt(x^2 + y^2)) of member-frame points (..., 3) mm -> (..., 2) mm."""
    p = np.asarray(points, float)
    return np.stack([p[..., 2], np.hypot(p[..., 0], p[..., 1])], -1)


def _outline_lines(outline):
    """Boundary polylines and labels from a (n, m, 3) grid (rows toe -> heel, columns root -> top) or a list."""
    if outline is None:
        return []
    if isinstance(outline, np.ndarray) and outline.ndim == 3:
        g = outline
        return [(g[0, :], "toe"), (g[-1, :], "heel"), (g[:, 0], "root"), (g[:, -1], "top")]
    return [(np.asarray(line, float), f"boundary {i}") for i, line in enumerate(outline)]


def _label_outside(ax, lines):
    """Label each boundary line at its middle, pushed outward from the outline's centre (toe, heel, root and top
    labels then sit outside the flank, clear of the contact path and ellipses drawn inside it)."""
    qs = [project_axial_radial(line) for line, _ in lines]
    centre = np.concatenate(qs).mean(0)
    for q, (_, label) in zip(qs, lines):
        m = q[len(q) // 2]
        d = m - centre
        d = d / (np.hypot(*d) or 1.0)
        ax.annotate(label, m, xytext=(14 * d[0], 14 * d[1]), textcoords="offset points", fontsize=7, color="0.3",
                    ha="center", va="center", annotation_clip=False)


def _tooth_panel(ax, title, outline, path, ellipses, status_ok, edge=None):
    lines = _outline_lines(outline)
    for line, _ in lines:
        q = project_axial_radial(line)
        ax.plot(q[:, 0], q[:, 1], "k-", lw=1.0)
    if lines:
        _label_outside(ax, lines)
    q = project_axial_radial(path)
    ax.plot(q[status_ok, 0], q[status_ok, 1], "o-", ms=2.5, lw=1.0, color="C3", label="contact path")
    edge = np.zeros(len(q), bool) if edge is None else edge
    if edge.any():
        ax.plot(q[edge, 0], q[edge, 1], "x", ms=4, color="C3", label="edge contact")
    for e in ellipses:
        qe = project_axial_radial(e)
        ax.plot(qe[:, 0], qe[:, 1], "-", lw=0.7, color="C0")
    if ellipses:
        ax.plot([], [], "-", lw=0.7, color="C0", label="contact ellipses")
    ax.set_title(title)
    ax.set_xlabel("axial position z (mm)")
    ax.set_ylabel("radius (mm)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.12)
    ax.legend(fontsize=7, loc="best")


def plot_tca(result, outline1=None, outline2=None, axes=None, ellipse_every=4, n_ellipse=49, title=None):
    """Three panels: TE (arcsec) of every pair and the envelope; contact path and ellipses on the pinion and on the
    gear, drawn on the projected tooth (axial position vs radius).

    Parameters
    ----------
    result : TCAResult
    outline1, outline2 : (n, m, 3) float or list of (k, 3) float, mm, optional
        Flank outlines in the member frames: a grid whose rows run toe -> heel and columns root -> top (the four
        boundary lines are drawn and labelled), or boundary polylines.
    axes : sequence of 3 matplotlib Axes, optional
    ellipse_every : int
        Draw the contact ellipse at every ``ellipse_every``-th position (finite ellipses only).
    title : str, optional
        Figure title above the three panels.

    Returns
    -------
    matplotlib.figure.Figure
        The pinion rotation is shown in degrees from the mean position (as in the loaded TCA plot), TE in arcsec.
    """
    plt = _plt()
    own = axes is None
    if own:
        fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    else:
        fig = axes[0].figure
    ax_te, ax1, ax2 = axes
    x = np.degrees(result.phi1 - result.phi1_mean)
    for j, k in enumerate(result.pairs):
        ax_te.plot(x, result.te_pairs[:, j] / ARCSEC, "--", lw=0.8, label=f"pair {k}")
    # the envelope through the exact transfer points (its kinks between positions)
    tt = np.degrees(np.asarray(result.transfer_phi1, float) - result.phi1_mean)
    te_t = np.asarray(getattr(result, "transfer_te", np.full(tt.shape, np.nan)), float)
    xe = np.r_[x, tt[np.isfinite(te_t)]]
    ye = np.r_[result.te, te_t[np.isfinite(te_t)]]
    o = np.argsort(xe, kind="stable")
    ax_te.plot(xe[o], ye[o] / ARCSEC, "k-", lw=2.0, label="in contact")
    edge = np.asarray(result.status) == 2  # ContactStatus.EDGE
    if edge.any():
        names = sorted({f"{m} {e}" for _, _, m, e in getattr(result, "edges", ())})
        ax_te.plot(x[edge], result.te[edge] / ARCSEC, "s", ms=3.5, mfc="none", color="C3",
                   label="edge contact" + (f" ({', '.join(names)})" if names else ""))
    for t in tt:
        ax_te.axvline(t, color="0.6", lw=0.6)
    ax_te.set_xlabel("pinion rotation φ1 − φ10 (deg)")
    ax_te.set_ylabel("transmission error (arcsec)")
    ax_te.set_title("transmission error")
    ax_te.legend(fontsize=7)
    ok = result.pair >= 0
    status_ok = ok & (result.status <= 1)
    sel = np.maximum(result.pair, 0)
    idx = np.arange(len(result.phi1))
    p1 = result.point1[idx, sel]
    p2 = result.point2[idx, sel]
    t = np.linspace(0, 2 * np.pi, n_ellipse)[:, None]
    ell1, ell2 = [], []
    for i in idx[::max(1, int(ellipse_every))]:
        a, b = result.semi_axes[i]
        if not (status_ok[i] and np.isfinite(a) and np.isfinite(b)):
            continue
        for p, d, out in ((p1, result.ellipse_dirs1, ell1), (p2, result.ellipse_dirs2, ell2)):
            out.append(p[i] + a * np.cos(t) * d[i, 0] + b * np.sin(t) * d[i, 1])
    edge_at = ok & (np.asarray(result.status) == 2)
    _tooth_panel(ax1, "pinion flank", outline1, p1, ell1, status_ok, edge_at)
    _tooth_panel(ax2, "gear flank", outline2, p2, ell2, status_ok, edge_at)
    if title:
        fig.suptitle(title)
    if own:  # fixed margins: room for the tick labels and the toe/heel/root/top labels outside the flanks
        fixed_layout(fig, 1, 3, left=0.75, right=0.3, bottom=0.6, top=0.4, wspace=1.0, suptitle=bool(title))
    return fig
