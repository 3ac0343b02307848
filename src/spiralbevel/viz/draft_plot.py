"""Map of the forging-draft result over the flank's parameter domain (seed 000 Fig. 8, corrected)."""

from __future__ import annotations

import textwrap
from typing import Any

import numpy as np

from .layout import display_subgrid, fixed_layout, legend_among_lines, panel_title

__all__ = ["plot_draft"]


def draft_angle(result):
    """Draft angle of each grid point, rad: asin(-n_out · v_d), the angle by which the flank leans away from the die
    direction (positive: the die can leave; negative: the flank is an undercut for the die)."""
    return np.arcsin(np.clip(-np.asarray(result.normal_dot_die, float), -1.0, 1.0))


def plot_draft(result, ax=None, coords: str = "varphi", limit: float = 0.0, title: str | None = None):
    """Colour map of the draft angle of a :class:`~spiralbevel.manufacturing.draft.DraftResult` over the flank's
    parameter domain, with a colour bar and the required draft angle marked.

    Parameters
    ----------
    result : DraftResult
        From :func:`spiralbevel.manufacturing.draft.draft_map` (or ``relieved_draft_map``).
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; a new figure is made when omitted.
    coords : {"varphi", "psi"}
        Horizontal coordinate: the rolling angle varphi (the domain is a parallelogram, as in seed 000 Fig. 8) or
        psi = (varphi - phi) sin(delta) (a rectangle). The vertical coordinate is phi.
    limit : float, rad
        The required draft angle (>= 0): points below it fail. Marked on the map (black contour) and on the colour
        bar.
    title : str, optional
        Panel title; default: the flank side, the die direction and the failing share of the area, in words.

    Returns
    -------
    matplotlib.figure.Figure

    Notes
    -----
    The draft angle is asin(-n_out · v_d) in degrees (:func:`draft_angle`); the colour scale is centred on the limit:
    green passes, red fails. The black line is the limit's contour on the grid; the dashed line is the analytic
    zero-draft boundary |varphi - phi| = |beta| / sin(delta) where it exists (die direction along ±z,
    docs/theory/logspiral.md, Eq. (S13)).
    """
    import matplotlib.pyplot as plt
    from matplotlib.colors import TwoSlopeNorm

    if coords not in ("varphi", "psi"):
        from ..errors import DesignError

        raise DesignError.single("coords", coords, "'varphi' or 'psi'", "-")
    if ax is None:
        fig, ax = plt.subplots(figsize=(6.4, 4.5))
    else:
        fig = ax.figure
    deg = 180.0 / np.pi
    x = (result.varphi if coords == "varphi" else result.psi) * deg
    y = result.phi * deg
    a = draft_angle(result) * deg
    lim = float(limit) * deg
    span = max(float(np.max(np.abs(a - lim))), 1e-6)
    norm = TwoSlopeNorm(vcenter=lim, vmin=lim - span, vmax=lim + span)
    mesh = ax.pcolormesh(*display_subgrid(x, y, a), shading="gouraud", cmap="RdYlGn", norm=norm)
    cb = fig.colorbar(mesh, ax=ax, label="draft angle [deg]")
    cb.ax.axhline(lim, color="k", lw=1.5)
    handles: list[Any] = []
    if a.min() < lim < a.max():
        ax.contour(x, y, a, levels=[lim], colors="k", linewidths=1.2)
    handles.append(plt.Line2D([], [], color="k", lw=1.2, label=f"required draft {lim:g}°"))
    if result.boundary is not None:
        bx = result.boundary[:, 0] if coords == "varphi" else np.full(2, result.boundary_psi)
        ax.plot(bx * deg, result.boundary[:, 1] * deg, "--", color="navy", lw=1.5)
        handles.append(plt.Line2D([], [], color="navy", ls="--", label="zero draft (analytic)"))
    # domain outline
    for row in (0, -1):
        ax.plot(x[row], y[row], color="k", lw=0.6)
    for col in (0, -1):
        ax.plot(x[:, col], y[:, col], color="k", lw=0.6)
    ax.set_xlabel("rolling angle φ [deg]" if coords == "varphi" else "ψ = (φ − ϕ) sin δ [deg]")
    ax.set_ylabel("spiral parameter ϕ [deg]")
    if title is None:
        title = f"{result.side.value} flank: " + _verdict(result, lim)
    panel_title(ax, "\n".join(textwrap.wrap(title, 58)), fontsize=9)   # at most the panel's width
    legend_among_lines(ax, handles=handles, fontsize=7)
    return fig


def _verdict(result, limit_deg: float) -> str:
    v = tuple(float(c) for c in np.round(result.die_direction, 3))
    share = 100 * result.failing_area_fraction
    if share > 0:
        verdict = f"{share:.1f}% of the area below {limit_deg:g}° draft"
    else:
        verdict = f"at least {limit_deg:g}° draft everywhere" if limit_deg > 0 else "draftable everywhere"
    return f"die along {v}: {verdict}"


def plot_draft_maps(results):
    """Several draft maps side by side: ``results`` is a list of (label, DraftResult) or (label, DraftResult,
    required draft angle in rad)."""
    import matplotlib.pyplot as plt

    n = len(results)
    cols = 2
    rows = (n + 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(12, 4.4 * rows), squeeze=False)
    for ax, item in zip(axes.flat, results):
        label, r = item[0], item[1]
        limit = float(item[2]) if len(item) > 2 else 0.0
        plot_draft(r, ax=ax, limit=limit, title=f"{label}: {_verdict(r, np.degrees(limit))}")
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    fig.suptitle("Forging draft: the angle by which each flank leans away from the die direction "
                 "(green passes, red fails)", fontsize=11)
    fixed_layout(fig, rows, cols, right=0.9, top=0.5, wspace=1.6, hspace=1.0, suptitle=True)
    return fig
