"""Map of the forging-draft result over the flank's parameter domain (seed 000 Fig. 8, corrected)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .layout import fixed_layout

__all__ = ["plot_draft"]


def plot_draft(result, ax=None, coords: str = "varphi"):
    """Draw draftable / failing regions of a :class:`~spiralbevel.manufacturing.draft.DraftResult`.

    Parameters
    ----------
    result : DraftResult
        From :func:`spiralbevel.manufacturing.draft.draft_map`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; a new figure is made when omitted.
    coords : {"varphi", "psi"}
        Horizontal coordinate: the rolling angle varphi (the domain is a parallelogram, as in seed 000 Fig. 8) or
        psi = (varphi - phi) sin(delta) (a rectangle). The vertical coordinate is phi.

    Returns
    -------
    matplotlib.figure.Figure

    Notes
    -----
    Colours: green = draftable (n_out · v_d <= 0), red = fails. The black line is the zero contour of n_out · v_d
    from the grid; the dashed line is the analytic boundary |varphi - phi| = |beta| / sin(delta) where it exists
    (die direction along ±z, docs/theory/logspiral.md, Eq. (S13)). Angles are shown in degrees.
    """
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    if coords not in ("varphi", "psi"):
        from ..errors import DesignError

        raise DesignError.single("coords", coords, "'varphi' or 'psi'", "-")
    if ax is None:
        fig, ax = plt.subplots(figsize=(6.0, 4.5))
    else:
        fig = ax.figure
    deg = 180.0 / np.pi
    x = (result.varphi if coords == "varphi" else result.psi) * deg
    y = result.phi * deg
    fail = (~result.draftable).astype(float)
    ax.pcolormesh(x, y, fail, shading="gouraud", cmap=ListedColormap(["#7fc97f", "#e3504a"]), vmin=0.0, vmax=1.0)
    g = result.normal_dot_die
    handles: list[Any] = [Patch(color="#7fc97f", label="draftable"), Patch(color="#e3504a", label="fails")]
    if g.min() < 0 < g.max():
        ax.contour(x, y, g, levels=[0.0], colors="k", linewidths=1.0)
        handles.append(plt.Line2D([], [], color="k", lw=1.0, label="n_out·v_d = 0 (grid)"))
    if result.boundary is not None:
        bx = result.boundary[:, 0] if coords == "varphi" else np.full(2, result.boundary_psi)
        ax.plot(bx * deg, result.boundary[:, 1] * deg, "--", color="navy", lw=1.5)
        handles.append(plt.Line2D([], [], color="navy", ls="--", label="|φ−ϕ| = |β|/sin δ (analytic)"))
    # domain outline
    for row in (0, -1):
        ax.plot(x[row], y[row], color="k", lw=0.6)
    for col in (0, -1):
        ax.plot(x[:, col], y[:, col], color="k", lw=0.6)
    ax.set_xlabel("rolling angle φ [deg]" if coords == "varphi" else "ψ = (φ − ϕ) sin δ [deg]")
    ax.set_ylabel("spiral parameter ϕ [deg]")
    v = result.die_direction
    ax.set_title(f"Forging draft, {result.side.value} flank, v_d = ({v[0]:.3g}, {v[1]:.3g}, {v[2]:.3g}): "
                 f"{100 * result.failing_area_fraction:.2f}% of area fails", fontsize=9)
    ax.legend(handles=handles, fontsize=8, loc="best")
    return fig


def plot_draft_maps(results):
    """Several draft maps side by side: ``results`` is a list of (label, DraftResult)."""
    import matplotlib.pyplot as plt

    n = len(results)
    cols = 2
    rows = (n + 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(11, 4.2 * rows), squeeze=False)
    for ax, (label, r) in zip(axes.flat, results):
        plot_draft(r, ax=ax)
        d = tuple(float(c) for c in np.round(r.die_direction, 3))
        ax.set_title(f"{label}: n_out . v_d > 0 (no draft) on {100 * r.failing_area_fraction:.1f} % of the area, "
                     f"v_d = {d}", fontsize=8)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    fixed_layout(fig, rows, cols, right=0.2, wspace=0.9, hspace=0.8)
    return fig
