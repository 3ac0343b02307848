"""Result object of tooth contact analysis (compute -> result object -> ``.plot()``)."""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import IntEnum

import numpy as np

__all__ = ["ContactStatus", "TCAResult", "ARCSEC"]

ARCSEC = np.pi / (180.0 * 3600.0)
"""One arcsecond in rad."""


class ContactStatus(IntEnum):
    """Status of a tooth pair at a position (``status_pairs``) or of the position itself (``status``).

    OK : point contact inside both flank domains.
    LINE : line contact (exact conjugate surfaces; the contact system is singular along the line).
    EDGE : for a pair, the solution of the analytically extended surfaces lies outside a flank domain (it is not a
        contact of the real flanks and never selected); for a position, such a pair would touch before the best
        contact of the real flanks: the real contact there is an edge contact of the boundary crossed (``edges``),
        which is not solved, so the position reports no TE, point or ellipse (NaN) rather than an extrapolated one.
    NO_CONTACT : no solution found (Newton diverged, or the normals are not opposite).
    """

    OK = 0
    LINE = 1
    EDGE = 2
    NO_CONTACT = 3


@dataclass(frozen=True, eq=False, repr=False)
class TCAResult:
    """Tooth contact analysis over one mesh cycle and several tooth pairs.

    Per-position arrays have n = number of pinion positions; per-pair arrays have shape (n, P) for the P tooth pairs
    in ``pairs``. Points and normals are in the member frames of the *reference* teeth (flank coordinates; tooth k
    is the reference flank turned by 2 pi k / z about its axis), or in the fixed pair frame where named ``_fixed``.

    Attributes
    ----------
    phi1 : (n,) float, rad
        Pinion rotations.
    phi1_mean, phi2_mean : float, rad
        phi10 and phi20 of seed 001 Eq. (1): the rotations at the mean contact point of pair 0.
    drive_sign : int
        +1 if the pinion flank drives the gear when phi1 increases (the pinion point moves along its outward
        normal), else -1.
    pairs : (P,) int
        Tooth-pair indices k.
    te_pairs : (n, P) float, rad
        Transmission error of each pair, drive_sign * [-(phi2 - phi20) - (z1/z2)(phi1 - phi10)] (positive: gear
        ahead of the nominal motion in its driven direction); NaN where ``status_pairs`` is NO_CONTACT.
    phi2_pairs : (n, P) float, rad
        Gear rotations about a2 at contact.
    status_pairs : (n, P) int
        :class:`ContactStatus` per pair.
    params1, params2 : (n, P, 2) float
        Surface parameters of pinion and gear.
    point1, normal1, point2, normal2 : (n, P, 3) float, mm and -
        Contact points and outward normals in member frames.
    point_fixed, normal_fixed : (n, P, 3) float
        Contact point and the pinion's outward normal in the fixed frame.
    residual : (n, P) float, mm
        Final max|F|.
    pair : (n,) int
        Index into ``pairs`` of the pair in contact: the largest TE among contacts inside both real flanks (it leads
        the gear), -1 if none.
    status : (n,) int
        :class:`ContactStatus` of the position.
    semi_axes : (n, 2) float, mm
        Semi-major and semi-minor axes of the instantaneous contact ellipse (inf on line contact; NaN where no
        contact).
    ellipse_dirs1, ellipse_dirs2 : (n, 2, 3) float
        Unit directions of the major and minor axes in the pinion and gear member frames.
    relative_curvatures : (n, 2) float, 1/mm
        Principal relative curvatures lam_1 <= lam_2 (see ``spiralbevel.meshing.ellipse``).
    approach : float, mm
        Elastic approach used for the ellipses.
    transfer_phi1 : (t,) float, rad
        Pinion rotations where the pair in contact changes: the exact crossing of the two pairs' TE curves
        (:mod:`spiralbevel.meshing.tca_transfer`; the middle of the interval where the curves do not cross).
    transfer_te : (t,) float, rad
        TE at those crossings (the envelope's kinks; NaN where the curves do not cross).
    z1, z2 : int
    shaft_angle : float, rad
    iterations : int
        Newton iterations of the final batched solve.
    edges : tuple of (int, int, str, str)
        Per EDGE position: (position index, tooth pair k, member "pinion"/"gear" whose boundary is crossed, edge name
        such as "top", "toe", "heel", "root", "fillet").
    """

    phi1: np.ndarray
    phi1_mean: float
    phi2_mean: float
    drive_sign: int
    pairs: np.ndarray
    te_pairs: np.ndarray
    phi2_pairs: np.ndarray
    status_pairs: np.ndarray
    params1: np.ndarray
    params2: np.ndarray
    point1: np.ndarray
    normal1: np.ndarray
    point2: np.ndarray
    normal2: np.ndarray
    point_fixed: np.ndarray
    normal_fixed: np.ndarray
    residual: np.ndarray
    pair: np.ndarray
    status: np.ndarray
    semi_axes: np.ndarray
    ellipse_dirs1: np.ndarray
    ellipse_dirs2: np.ndarray
    relative_curvatures: np.ndarray
    approach: float
    transfer_phi1: np.ndarray
    z1: int
    z2: int
    shaft_angle: float
    iterations: int
    edges: tuple = ()
    transfer_te: np.ndarray = field(default_factory=lambda: np.zeros(0))

    # ------------------------------------------------------------------ selected contact
    def _pick(self, arr):
        arr = np.asarray(arr)
        out = np.full((arr.shape[0],) + arr.shape[2:], np.nan)
        ok = self.pair >= 0
        out[ok] = arr[np.nonzero(ok)[0], self.pair[ok]]
        return out

    @property
    def te(self) -> np.ndarray:
        """(n,) float, rad: TE of the pair in contact (the upper envelope of ``te_pairs``)."""
        return self._pick(self.te_pairs)

    @property
    def te_arcsec(self) -> np.ndarray:
        """(n,) float, arcsec."""
        return self.te / ARCSEC

    @property
    def te_pairs_arcsec(self) -> np.ndarray:
        """(n, P) float, arcsec."""
        return self.te_pairs / ARCSEC

    @property
    def phi2(self) -> np.ndarray:
        """(n,) float, rad: gear rotation of the pair in contact."""
        return self._pick(self.phi2_pairs)

    @property
    def contact_point1(self) -> np.ndarray:
        """(n, 3) float, mm: contact point on the pinion flank (member frame)."""
        return self._pick(self.point1)

    @property
    def contact_point2(self) -> np.ndarray:
        """(n, 3) float, mm: contact point on the gear flank (member frame)."""
        return self._pick(self.point2)

    @property
    def line_contact(self) -> np.ndarray:
        """(n,) bool."""
        return self.status == ContactStatus.LINE

    @property
    def edge_contact(self) -> np.ndarray:
        """(n,) bool."""
        return self.status == ContactStatus.EDGE

    @property
    def envelope_te(self) -> np.ndarray:
        """(m,) float, rad: the TE of the contact envelope at the positions with contact and at the exact transfer
        points (the kinks between positions): the values its extremes are taken over."""
        te = np.concatenate([self.te, np.asarray(self.transfer_te, float)])
        return te[np.isfinite(te)]

    @property
    def te_max(self) -> float:
        """Largest TE of the contact envelope (positions and transfer points), rad."""
        te = self.envelope_te
        return float(te.max()) if te.size else float("nan")

    @property
    def te_min(self) -> float:
        """Smallest TE of the contact envelope (positions and transfer points, where the envelope has its kinks),
        rad."""
        te = self.envelope_te
        return float(te.min()) if te.size else float("nan")

    @property
    def peak_to_peak(self) -> float:
        """Peak-to-peak TE of the contact envelope over positions with contact and the transfer points, rad."""
        return self.te_max - self.te_min

    @property
    def peak_to_peak_arcsec(self) -> float:
        """:attr:`peak_to_peak` in arcsec (the unit of :meth:`summary` and of the reports)."""
        return self.peak_to_peak / ARCSEC

    def summary(self) -> str:
        n = len(self.phi1)
        counts = {s.name: int(np.sum(self.status == s)) for s in ContactStatus}
        return (f"TCA {self.z1}/{self.z2}: {n} positions, pairs {[int(k) for k in self.pairs]}, status {counts}, "
                f"TE peak-to-peak {self.peak_to_peak / ARCSEC:.4f} arcsec, transfers at "
                f"{np.round(self.transfer_phi1, 6).tolist()} rad")

    def __repr__(self) -> str:
        return f"TCAResult({self.summary()})"

    def plot(self, outline1=None, outline2=None, ax=None, **kw):
        """TE curves, contact paths on the projected flanks and contact ellipses; see
        :func:`spiralbevel.viz.tca_plot.plot_tca`."""
        from ..viz.tca_plot import plot_tca

        return plot_tca(self, outline1=outline1, outline2=outline2, axes=ax, **kw)
