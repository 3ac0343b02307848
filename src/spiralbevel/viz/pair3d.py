"""3-D view of meshing tooth flanks in the pair frame."""

from __future__ import annotations

import numpy as np

from .layout import fixed_layout


def plot_surfaces_3d(surfaces, title="", elev=25, azim=-60, views=None):
    """Draw point grids as opaque, lit surfaces with equal scales on the three axes.

    Parameters
    ----------
    surfaces : list of (label : str, points : (n, m, 3) float mm, color : str)
        A label starting with ``_`` is left out of the legend.
    title : str
    elev, azim : float, deg
        The first view's camera.
    views : list of (title : str, elev : float deg, azim : float deg), optional
        One panel per view; default: the first view and an oblique view of the same scene.

    Returns
    -------
    matplotlib.figure.Figure

    Notes
    -----
    Each face is shaded by a light from the upper left of the camera (matplotlib ``LightSource``), and the grid
    lines are drawn thinly in a darker shade of the face colour, so that the curvature of each flank can be read. The
    box aspect equals the data's extent on each axis: a millimetre has the same length in x, y and z.
    """
    import matplotlib.pyplot as plt
    from matplotlib.colors import LightSource, to_rgb
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    if views is None:
        views = [("", elev, azim), ("oblique view", elev + 20.0, azim - 35.0)]
    fig = plt.figure(figsize=(6.2 * len(views), 6.2))
    allpts = np.concatenate([np.asarray(pts, float).reshape(-1, 3) for _, pts, _ in surfaces])
    lo, hi = allpts.min(0), allpts.max(0)
    span = np.maximum(hi - lo, 1e-3 * float((hi - lo).max()))
    pad = 0.04 * span
    for k, (vtitle, el, az) in enumerate(views):
        ax = fig.add_subplot(1, len(views), k + 1, projection="3d")
        light = LightSource(azdeg=az + 135.0, altdeg=55.0)
        polys, faces, edges = [], [], []
        seen = set()
        for label, pts, color in surfaces:
            q, f, e = _shaded_quads(np.asarray(pts, float), to_rgb(color), light)
            polys.append(q)
            faces.append(f)
            edges.append(e)
            if label and not label.startswith("_") and label not in seen:
                seen.add(label)
                ax.plot([], [], color=color, lw=6, label=label)
        # one collection: matplotlib sorts the faces of a collection by depth, but whole collections only by their
        # mean depth, so separate surfaces would be painted over each other in the wrong order
        coll = Poly3DCollection(np.concatenate(polys), facecolors=np.concatenate(faces),
                                edgecolors=np.concatenate(edges), linewidths=0.15)
        ax.add_collection3d(coll)
        ax.set_xlim(lo[0] - pad[0], hi[0] + pad[0])
        ax.set_ylim(lo[1] - pad[1], hi[1] + pad[1])
        ax.set_zlim(lo[2] - pad[2], hi[2] + pad[2])
        ax.set_box_aspect(tuple(span + 2 * pad))
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
        ax.set_zlabel("z [mm]")
        ax.view_init(elev=el, azim=az)
        for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
            axis.pane.set_alpha(0.0)
        if k == 0:
            ax.legend(loc="upper left", fontsize=8)
        if vtitle:
            ax.set_title(vtitle, fontsize=10)
    if title:
        fig.suptitle(title)
    fig.subplots_adjust(left=0.04, right=0.94, bottom=0.1, top=0.86, wspace=0.15)
    return fig


def _shaded_quads(pts, rgb, light):
    """Quads of a (n, m, 3) grid, (k, 4, 3), with Lambert-shaded face colours (k, 3) lit by ``light`` (two-sided:
    a face lit from behind is shaded as if it faced the light) and darker edge colours (k, 3)."""
    quads = np.stack([pts[:-1, :-1], pts[1:, :-1], pts[1:, 1:], pts[:-1, 1:]], axis=2).reshape(-1, 4, 3)
    n = np.cross(quads[:, 2] - quads[:, 0], quads[:, 3] - quads[:, 1])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    az, alt = np.radians(light.azdeg), np.radians(light.altdeg)
    d = np.array([np.cos(alt) * np.cos(az), np.cos(alt) * np.sin(az), np.sin(alt)])
    lam = np.abs(n @ d)
    shade = (0.35 + 0.65 * lam)[:, None]
    face = np.clip(np.asarray(rgb)[None, :] * shade, 0.0, 1.0)
    return quads, face, 0.6 * face


def plot_transverse_section(profiles, title=""):
    """Tooth profiles of a meshing pair in the transverse (spherical) section, projected on the pitch-point plane.

    Parameters
    ----------
    profiles : list of (label : str, xy : (k, 2) float mm, color : str)
        Profile polylines in the plane tangent to the sphere at the mean pitch point: x across the teeth, y along
        the pinion's addendum direction.
    """
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    seen = set()
    for label, xy, color in profiles:
        xy = np.asarray(xy, float)
        ax.plot(xy[:, 0], xy[:, 1], color=color, lw=1.6, label=None if label in seen else label)
        seen.add(label)
    ax.axhline(0.0, color="0.5", lw=0.6, ls="--")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("across the teeth [mm]")
    ax.set_ylabel("toward the pinion tip [mm]")
    ax.legend(fontsize=8, loc="upper right")
    if title:
        ax.set_title(title)
    fixed_layout(fig, 1, 1, left=0.75, right=0.2)
    return fig
