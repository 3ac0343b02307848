"""Plot of an ease-off map (:class:`~spiralbevel.meshing.easeoff.EaseOff`) over the projected pinion tooth."""

from __future__ import annotations

import textwrap

import numpy as np

from ..errors import DesignError, MissingDependencyError

__all__ = ["plot_easeoff"]

#: the sign of the map, stated on every ease-off plot
SIGN = "+ = clearance (material removed from the pinion)"


def plot_easeoff(easeoff, kind: str = "surface", ax=None, title: str = "Ease-off"):
    """Draw an ease-off map in micrometres, with a colour bar that states the sign.

    Parameters
    ----------
    easeoff : EaseOff
    kind : {"surface", "contour", "both"}
        ``"surface"``: 3-D surface over (R, h) (toe to heel, root to top); ``"contour"``: filled contours on the
        projected tooth (axial position vs radius, the usual contact-pattern view); ``"both"``: the two side by side
        (a new figure; ``ax`` is not used).
    ax : matplotlib Axes, optional
        Target axes (3-D axes for ``"surface"``); a new figure otherwise.
    title : str
        Figure title (wrapped to fit the figure).

    Returns
    -------
    matplotlib.figure.Figure

    Notes
    -----
    Positive ease-off = material removed from the pinion relative to the conjugate flank (clearance); the map is 0 at
    the mean point (rigid rotation removed).
    """
    if kind not in ("surface", "contour", "both"):
        raise DesignError.single("kind", kind, "'surface', 'contour' or 'both'", "-")
    try:
        import matplotlib.pyplot as plt
    except ImportError as err:  # pragma: no cover - matplotlib is a core dependency
        raise MissingDependencyError("matplotlib", "all", "plotting the ease-off") from err
    um = 1e3 * np.asarray(easeoff.values, float)
    if kind == "both":
        fig = plt.figure(figsize=(12.0, 5.2))
        ax3 = fig.add_axes((0.0, 0.06, 0.5, 0.78), projection="3d")
        ax2 = fig.add_axes((0.57, 0.12, 0.3, 0.7))
        _surface(fig, ax3, easeoff, um, colorbar=False)
        _contour(fig, ax2, easeoff, um)
        fig.suptitle("\n".join(textwrap.wrap(title, 110)), fontsize=10)
        return fig
    if ax is None:
        if kind == "surface":
            fig = plt.figure(figsize=(7.2, 5.4))
            ax = fig.add_axes((0.0, 0.04, 0.78, 0.8), projection="3d")
        else:
            fig, ax = plt.subplots(figsize=(6.4, 4.8))
            fig.subplots_adjust(top=0.85)
    fig = ax.figure
    (_surface if kind == "surface" else _contour)(fig, ax, easeoff, um)
    ax.set_title("\n".join(textwrap.wrap(title, 60)), fontsize=9)
    return fig


def _surface(fig, ax, easeoff, um, colorbar=True):
    surf = ax.plot_surface(easeoff.R, easeoff.h, um, cmap="viridis", edgecolor="k", linewidth=0.2,
                           vmin=float(np.nanmin(um)), vmax=float(np.nanmax(um)))  # the contour panel's colours
    ax.set_xlabel("R (toe → heel), mm")
    ax.set_ylabel("h (root → top), mm")
    ax.set_zlabel("ease-off, µm")
    if colorbar:
        fig.colorbar(surf, ax=ax, shrink=0.7, pad=0.1, label=f"ease-off, µm\n{SIGN}")


def _contour(fig, ax, easeoff, um):
    cs = ax.contourf(easeoff.axial, easeoff.radius, um, levels=15, cmap="viridis")
    ax.contour(easeoff.axial, easeoff.radius, um, levels=15, colors="k", linewidths=0.3)
    fig.colorbar(cs, ax=ax, label=f"ease-off, µm\n{SIGN}")
    z, r = easeoff.axial, easeoff.radius
    outline = np.concatenate([np.stack([z[:, 0], r[:, 0]], -1), np.stack([z[-1], r[-1]], -1),
                              np.stack([z[::-1, -1], r[::-1, -1]], -1), np.stack([z[0, ::-1], r[0, ::-1]], -1)])
    ax.plot(outline[:, 0], outline[:, 1], "k-", lw=0.8)
    ax.set_xlabel("axial position, mm")
    ax.set_ylabel("radius, mm")
    ax.set_aspect("equal", adjustable="datalim")
