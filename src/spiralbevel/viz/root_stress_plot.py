"""Maximum principal stress of the FE tooth model on the two flanks of a tooth (root fillet highlighted)."""

from __future__ import annotations

import numpy as np

__all__ = ["plot_root_stress"]


def _developed(grid):
    """Flank grid (n_face, n_rows, 3) -> (face arc length along each row, height arc length along each column), mm."""
    ds_face = np.linalg.norm(np.diff(grid, axis=0), axis=-1)
    ds_prof = np.linalg.norm(np.diff(grid, axis=1), axis=-1)
    X = np.concatenate([np.zeros((1, grid.shape[1])), np.cumsum(ds_face, axis=0)], axis=0)
    Y = np.concatenate([np.zeros((grid.shape[0], 1)), np.cumsum(ds_prof, axis=1)], axis=1)
    return X, Y


def plot_root_stress(stresses: dict, title: str | None = None, sigma_F0: dict | None = None):
    """Envelope of the maximum principal stress over the load cases on both flanks of the loaded tooth.

    Parameters
    ----------
    stresses : dict
        ``{"pinion": MemberRootStress, "gear": MemberRootStress}`` (:func:`~spiralbevel.rating.fe_root_stress.
        fe_root_stress`).
    title : str, optional
    sigma_F0 : dict, optional
        ``member -> sigma_F0`` (N/mm^2) of Method B1 at the same torque, quoted in the panel titles.

    Returns
    -------
    matplotlib.figure.Figure
        One row per member, one panel per flank: developed flank (face-width arc length from the toe, height arc
        length from the root line), colour = maximum principal stress in N/mm^2; the fillet rows below the dashed
        line, the maximum along the fillet marked.
    """
    import matplotlib.pyplot as plt

    members = [m for m in ("pinion", "gear") if m in stresses]
    fig, axes = plt.subplots(len(members), 2, figsize=(11, 3.6 * len(members)), squeeze=False)
    for r, member in enumerate(members):
        st = stresses[member]
        vmax = max(float(np.max(st.sigma1[sd])) for sd in ("convex", "concave"))
        vmin = min(float(np.min(st.sigma1[sd])) for sd in ("convex", "concave"))
        lim = max(abs(vmin), abs(vmax))
        for c, sd in enumerate(("concave", "convex")):
            ax = axes[r, c]
            X, Y = _developed(st.grids[sd])
            pc = ax.pcolormesh(X, Y, st.sigma1[sd], shading="gouraud", cmap="coolwarm", vmin=-lim, vmax=lim)
            jf = st.n_fillet - 1
            ax.plot(X[:, jf], Y[:, jf], "k--", lw=1.0, label="fillet / blade junction")
            ax.fill_between(X[:, 0], Y[:, 0], Y[:, jf], facecolor="none", hatch="//", edgecolor="0.35", lw=0.0,
                            label="root fillet")
            if sd == st.side_max:
                i, j = st.index_max
                ax.plot(X[i, j], Y[i, j], "k*", ms=12, label=f"max along the fillet {st.sigma1_max:.1f} N/mm^2")
            ax.set_xlabel("face width from the toe (mm)")
            ax.set_ylabel("height from the root line (mm)")
            load = "loaded" if sd == st.loaded_side else "unloaded"
            ref = f", sigma_F0 = {sigma_F0[member]:.1f}" if sigma_F0 and member in sigma_F0 else ""
            ax.set_title(f"{member}, {sd} flank ({load}){ref}", fontsize=10)
            ax.legend(loc="upper right", fontsize=8)
            fig.colorbar(pc, ax=ax, label="max principal stress (N/mm^2)")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig
