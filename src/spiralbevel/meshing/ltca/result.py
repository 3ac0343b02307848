"""Result object of loaded tooth contact analysis."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["LTCAResult", "ARCSEC"]

ARCSEC = np.pi / (180.0 * 3600.0)  # rad per arcsecond


@dataclass(frozen=True, repr=False)
class LTCAResult:
    """Loaded tooth contact analysis over a mesh cycle.

    Attributes
    ----------
    pinion_angles : (n_pos,) float, rad
        Pinion rotation phi1 - phi10 of each mesh position.
    torque : float, N mm
        Gear torque.
    te_unloaded, te_loaded : (n_pos,) float, arcsec
        Transmission error (seed 001 Eq. (1) sign: negative = the gear lags) without and with load.
    te_pairs : (n_pos, n_pairs) float, arcsec
        Unloaded transmission error of each tooth pair (NaN where a pair is out of mesh).
    load_share : (n_pos, n_pairs) float, -
        Share of the torque carried by each pair (rows sum to 1).
    pair_force : (n_pos, n_pairs) float, N
        Total normal force of each pair.
    max_pressure : (n_pos,) float, N/mm^2
        Peak contact pressure (force of a cell / cell area).
    points : list of (n_i, 3) float, mm
        Potential contact points of each position (pair frame).
    pair_of_point : list of (n_i,) int
        Pair index (0..n_pairs-1) of each point.
    force : list of (n_i,) float, N
        Normal force at each point.
    pressure : list of (n_i,) float, N/mm^2
        Mean pressure on the cell of each point.
    points1, points2 : list of (n_i, 3) float, mm
        The same points in the pinion and gear member frames, for flank maps: on the reference tooth when produced by
        :meth:`~spiralbevel.meshing.ltca.from_tca.LTCAModel.run` / ``loaded_tca``; in the FE segment frame (the
        pair's tooth ``tooth_*``) when :func:`~spiralbevel.meshing.ltca.ltca.run_ltca` is called directly.
    dtheta : (n_pos,) float, rad
        Gear lag that closes the gaps (loaded); the loaded TE is -dtheta.
    approach_torque : float or None, N mm
        Torque at which the tooth approach at the mean contact point equals ``approach_target`` (seed 001 §4.3.2).
    approach_target : float, mm
    pair_names : tuple of str
    """

    pinion_angles: np.ndarray
    torque: float
    te_unloaded: np.ndarray
    te_loaded: np.ndarray
    te_pairs: np.ndarray
    load_share: np.ndarray
    pair_force: np.ndarray
    max_pressure: np.ndarray
    points: list
    pair_of_point: list
    force: list
    pressure: list
    points1: list
    points2: list
    dtheta: np.ndarray
    approach_torque: float | None = None
    approach_target: float = 0.00635
    pair_names: tuple = field(default_factory=tuple)

    @property
    def peak_pressure(self) -> float:
        """Largest contact pressure over the cycle, N/mm^2."""
        return float(np.max(self.max_pressure))

    @property
    def loaded_te_amplitude(self) -> float:
        """Peak-to-peak loaded transmission error, arcsec."""
        return float(np.ptp(self.te_loaded))

    def __repr__(self) -> str:
        return (f"LTCAResult({len(self.pinion_angles)} positions, gear torque {self.torque / 1000.0:.4g} N m, "
                f"loaded TE peak-to-peak {self.loaded_te_amplitude:.4g} arcsec, peak pressure "
                f"{self.peak_pressure:.4g} N/mm^2)")

    def plot(self, **kwargs):
        """Transmission errors, load sharing and the pressure over the flank (see :mod:`spiralbevel.viz.ltca_plot`)."""
        from ...viz.ltca_plot import plot_ltca

        return plot_ltca(self, **kwargs)
