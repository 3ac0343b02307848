"""Plot of an ease-off map (:class:`~spiralbevel.meshing.easeoff.EaseOff`) over the projected pinion tooth."""

from __future__ import annotations

import numpy as np

from ..errors import DesignError, MissingDependencyError

__all__ = ["plot_easeoff"]


def plot_easeoff(easeoff, kind: str = "surface", ax=None, title: str = "Ease-off"):
    """Draw an ease-off map in micrometres.

    Parameters
    ----------
    easeoff : EaseOff
    kind : {"surface", "contour"}
        ``"surface"``: 3-D surface over (R, h) (toe to heel, root to top); ``"contour"``: filled contours on the
        projected tooth (axial position vs radius, the usual contact-pattern view).
    ax : matplotlib Axes, optional
        Target axes (3-D axes for ``"surface"``); a new figure otherwise.
    title : str

    Returns
    -------
    matplotlib.figure.Figure

    Notes
    -----
    Positive ease-off = material removed from the pinion relative to the conjugate flank (clearance); the map is 0 at
    the mean point (rigid rotation removed).
    """
    if kind not in ("surface", "contour"):
        raise DesignError.single("kind", kind, "'surface' or 'contour'", "-")
    try:
        import matplotlib.pyplot as plt
    except ImportError as err:  # pragma: no cover - matplotlib is a core dependency
        raise MissingDependencyError("matplotlib", "all", "plotting the ease-off") from err
    um = 1e3 * np.asarray(easeoff.values, float)
    if kind == "surface":
        if ax is None:
            fig = plt.figure(figsize=(6.4, 4.8))
            ax = fig.add_subplot(projection="3d")
        fig = ax.figure
        ax.plot_surface(easeoff.R, easeoff.h, um, cmap="viridis", edgecolor="k", linewidth=0.2)
        ax.set_xlabel("R (toe → heel), mm")
        ax.set_ylabel("h (root → top), mm")
        ax.set_zlabel("ease-off, µm")
    else:
        if ax is None:
            fig, ax = plt.subplots(figsize=(6.4, 4.8))
        fig = ax.figure
        cs = ax.contourf(easeoff.axial, easeoff.radius, um, levels=15, cmap="viridis")
        ax.contour(easeoff.axial, easeoff.radius, um, levels=15, colors="k", linewidths=0.3)
        fig.colorbar(cs, ax=ax, label="ease-off, µm (+ = clearance)")
        z, r = easeoff.axial, easeoff.radius
        outline = np.concatenate([np.stack([z[:, 0], r[:, 0]], -1), np.stack([z[-1], r[-1]], -1),
                                  np.stack([z[::-1, -1], r[::-1, -1]], -1), np.stack([z[0, ::-1], r[0, ::-1]], -1)])
        ax.plot(outline[:, 0], outline[:, 1], "k-", lw=0.8)
        ax.set_xlabel("axial position, mm")
        ax.set_ylabel("radius, mm")
        ax.set_aspect("equal", adjustable="datalim")
    ax.set_title(title)
    return fig
