"""Subplot layout from fixed margins in inches: one ``subplots_adjust`` instead of ``tight_layout``'s measuring pass
(which lays out every tick label and title once more before the figure is drawn), and panel titles at a fixed
height."""

from __future__ import annotations


def fixed_layout(fig, rows: int, cols: int, *, left=0.7, right=0.55, bottom=0.55, top=0.35, wspace=1.4,
                 hspace=0.75, suptitle: bool = False) -> None:
    """Place a ``rows x cols`` subplot grid with margins and gaps given in inches.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    rows, cols : int
        Subplot grid.
    left, right, bottom, top : float, in
        Figure margins (room for axis labels and tick labels on the left and bottom, a panel title on top).
    wspace, hspace : float, in
        Gaps between panels (room for a colorbar's labels and the next panel's axis label).
    suptitle : bool
        Add 0.35 in on top for a figure title.
    """
    width, height = fig.get_size_inches()
    top = top + (0.35 if suptitle else 0.0)
    ax_w = (width - left - right - (cols - 1) * wspace) / cols
    ax_h = (height - bottom - top - (rows - 1) * hspace) / rows
    fig.subplots_adjust(left=left / width, right=1.0 - right / width, bottom=bottom / height, top=1.0 - top / height,
                        wspace=wspace / ax_w if cols > 1 else 0.0, hspace=hspace / ax_h if rows > 1 else 0.0)


def legend_among_lines(ax, **kwargs):
    """``ax.legend(loc="best", **kwargs)`` on a panel filled by a colour map (``pcolormesh``).

    matplotlib's "best" placement hit-tests the lines, patches and the *offsets* of collections. To read the offsets
    of a :class:`~matplotlib.collections.QuadMesh` it first builds one ``Path`` per cell (40,000 for the draft maps:
    a quarter of a second per figure) and then finds the single default offset at the figure's corner, outside every
    candidate box. Leaving the meshes out of that hit test gives the same position without the paths.
    """
    from matplotlib.collections import QuadMesh

    legend = ax.legend(loc="best", **kwargs)
    hit_test = getattr(legend, "_auto_legend_data", None)
    if hit_test is None or not hasattr(ax, "_children"):  # another matplotlib: its own "best", only slower
        return legend

    def without_meshes(renderer):
        children = ax._children
        ax._children = [a for a in children if not isinstance(a, QuadMesh)]
        try:
            return hit_test(renderer)
        finally:
            ax._children = children

    legend._auto_legend_data = without_meshes
    return legend


def panel_title(ax, label: str, **kwargs):
    """``ax.set_title(label, **kwargs)`` at the top edge of the panel (``y=1``), not re-placed at each draw.

    By default matplotlib places a title anew on every draw: it measures the tick labels of the x axis (when they may
    sit on top) and the y axis of the panel and its siblings, to lift the title above top-side tick labels or the y
    axis' offset text ("1e-3" above the axis). The panels of this package have neither, so the title stays at the top
    edge, where the measurement would put it; fixing it saves about a fifth of the drawing time of a map figure.
    Not for a panel with a y axis that may carry an offset text (values far from 0 with a small spread).
    """
    return ax.set_title(label, y=1.0, **kwargs)


#: nodes along each direction of a grid drawn with Gouraud shading: 40 cells of a 4-6 inch panel at 100 dpi are about
#: 10 pixels each, where the linear colour interpolation of a smooth field inside a cell stays within a few levels of
#: the finer grid's colours (at most 8 of 255 per channel inside the bundled example's draft maps)
DISPLAY_NODES = 41


def display_subgrid(*arrays, nodes: int = DISPLAY_NODES):
    """The arrays of an (n, m) grid thinned to at most ``nodes`` rows and columns for a Gouraud-shaded map.

    The cost of drawing ``pcolormesh(..., shading="gouraud")`` grows with the number of cells, not with the pixels
    they cover: a 101 x 101 draft map takes 50-60 ms per panel in Agg, its 41 x 41 subgrid a sixth of that. The
    first and last rows and columns are kept (same outline and data limits); compute on the full grid (contours,
    colour limits) and draw the colours from this.

    Parameters
    ----------
    *arrays : (n, m) array_like
        Coordinates and values on the same grid.
    nodes : int
        Most rows and columns kept.

    Returns
    -------
    tuple of (n', m') ndarray
        The same arrays on rows and columns evenly spread over the grid, n' = min(n, nodes), m' = min(m, nodes).
    """
    import numpy as np

    grids = [np.asarray(a) for a in arrays]
    n, m = grids[0].shape[:2]
    rows, cols = (np.unique(np.round(np.linspace(0, k - 1, min(k, nodes))).astype(int)) for k in (n, m))
    return tuple(a[np.ix_(rows, cols)] for a in grids)
