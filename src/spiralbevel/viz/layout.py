"""Subplot layout from fixed margins in inches: one ``subplots_adjust`` instead of ``tight_layout``'s measuring pass
(which lays out every tick label and title once more before the figure is drawn)."""

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
