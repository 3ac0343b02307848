"""Plots of a loaded tooth contact analysis (:class:`~spiralbevel.meshing.ltca.result.LTCAResult`).

matplotlib is imported lazily inside the functions.
"""

from __future__ import annotations

import numpy as np

__all__ = ["plot_ltca"]


def plot_ltca(result, member: str = "gear", fig=None):
    """Three panels: unloaded and loaded transmission error (arcsec), load share per pair, and the contact pressure
    over the flank of ``member`` (all positions superposed, projected on the member's axial plane: axial z versus
    radius, mm).

    Parameters
    ----------
    result : LTCAResult
    member : {"gear", "pinion"}
    fig : matplotlib.figure.Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    if fig is None:
        fig = plt.figure(figsize=(12, 4))
    ax1, ax2, ax3 = fig.subplots(1, 3)
    x = np.degrees(result.pinion_angles)
    for j in range(result.te_pairs.shape[1]):
        ax1.plot(x, result.te_pairs[:, j], ":", lw=1, label=f"unloaded {result.pair_names[j]}" if result.pair_names
                 else None)
    ax1.plot(x, result.te_unloaded, "k-", lw=1.5, label="unloaded")
    ax1.plot(x, result.te_loaded, "r-", lw=1.5, label=f"loaded, T = {result.torque / 1000:.4g} N m")
    ax1.set_xlabel("pinion rotation (deg)")
    ax1.set_ylabel("transmission error (arcsec)")
    ax1.legend(fontsize=7)
    ax1.set_title("transmission error, unloaded and loaded", fontsize=9)
    for j in range(result.load_share.shape[1]):
        ax2.plot(x, result.load_share[:, j], label=result.pair_names[j] if result.pair_names else None)
    ax2.set_xlabel("pinion rotation (deg)")
    ax2.set_title("load share of each tooth pair", fontsize=9)
    if result.pair_names:
        ax2.legend(fontsize=7)
    ax2.set_ylabel("load share (-)")
    ax2.set_ylim(-0.05, 1.05)
    pts = np.concatenate(result.points2 if member == "gear" else result.points1)
    p = np.concatenate(result.pressure)
    on = p > 0
    sc = ax3.scatter(pts[on, 2], np.hypot(pts[on, 0], pts[on, 1]), c=p[on], s=6, cmap="viridis")
    fig.colorbar(sc, ax=ax3, label="contact pressure (N/mm^2)")
    ax3.set_xlabel("axial z (mm)")
    ax3.set_ylabel("radius (mm)")
    ax3.set_title(f"{member} flank, peak {result.peak_pressure:.0f} N/mm^2", fontsize=9)
    fig.tight_layout()
    return fig
