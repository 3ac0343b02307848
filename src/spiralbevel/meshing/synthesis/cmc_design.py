"""The seed 001 design chain in one call: local synthesis, CMC, multi-point control, TCA (seed 001 §4.3, §5).

``design_seed001_style(gear_cutter, gear_settings, blank, eta=..., semi_major_axis=..., te_magnitude=...)`` synthesizes
the pinion at the mean contact point, builds the combined motion curve by Steps 1-4 (``seed001_cmc``) with the same
magnitude, controls the TE at ``n_control`` pinion rotations spread over the part of the mesh cycle where the contact
lies on the active flanks of both members (``active_range``), and runs TCA of the final pair over three tooth pairs.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from ...conventions import Side
from ...errors import DesignError, GeometryError
from ..motion_curves import seed001_cmc
from ..tca_result import ARCSEC, ContactStatus
from ._multipoint_system import MultiPointSystem
from .local import synthesize_pinion
from .multipoint import _Surface, multipoint_control, multipoint_tca

__all__ = ["CMCDesign", "active_range", "design_seed001_style", "te_summary"]


def active_range(synthesis, step: float | None = None) -> tuple[float, float]:
    """Pinion rotations (x_lo, x_hi), rad from phi10, over which the contact of the synthesized pair stays inside
    both flank domains (above the fillet junctions, below the face cones, between toe and heel), within one mesh cycle.

    The contact is traced outward from M in steps of ``step`` (default pi / (12 z1)) on both sides, by continuation in
    one compiled call (``MultiPointSystem.march``); the domains are then tested at all stations at once, and the last
    station before the first one off a domain (or without contact) on each side is returned.
    """
    sysm = MultiPointSystem(synthesis)
    T = 2 * math.pi / sysm.kin.z1
    h = step if step is not None else T / 24
    k, steps = 0, []
    while k * h < T / 2:
        k += 1
        steps.append(min(k * h, T / 2))
    xs = np.array([steps, [-v for v in steps]])
    z, u, count = sysm.march(xs)
    pin = _Surface(synthesis.pinion_flank, 0.0, synthesis.pinion_params)
    gear = _Surface(synthesis.gear_flank, 0.0, synthesis.mean.gear_params)
    inside = (np.arange(xs.shape[1]) < count[:, None]) & pin.contains(np.stack([u[..., 0], z[..., 1]], -1)) \
        & gear.contains(np.stack([u[..., 1], z[..., 3]], -1))
    n_in = np.argmin(np.c_[inside, np.zeros(2, bool)], axis=1)     # stations before the first one off
    last = np.where(n_in > 0, xs[np.arange(2), np.maximum(n_in - 1, 0)], 0.0)
    if not (last[1] < 0 < last[0]):
        raise GeometryError.single("synthesis", "-", "a contact path on the active flanks on both sides of M", "-",
                                   "the contact leaves a flank within one step of the mean point")
    return float(last[1]), float(last[0])


class CMCDesign(NamedTuple):
    """Result of :func:`design_seed001_style`: unpacks as (synthesis, multipoint, tca)."""

    synthesis: Any
    multipoint: Any
    tca: Any

    def summary(self) -> dict:
        """Report section: settings (deg/mm), CMC, blank-offset law, TCA (arcsec)."""
        mp = self.multipoint
        out = {"synthesis": self.synthesis.summary(), "multipoint": mp.summary(),
               "pinion_settings_final": mp.pinion_settings.to_dict(degrees=True)}
        cmc = mp.cmc
        if hasattr(cmc, "a"):
            out["cmc"] = {"a": list(cmc.a), "b1_deg": math.degrees(cmc.b1), "b2_arcsec": cmc.b2 / ARCSEC,
                          "b3_deg": math.degrees(cmc.b3), "shift_arcsec": cmc.shift / ARCSEC,
                          "units": "a2 1/rad, a3 1/rad^2, a4 1/rad^3 (x and Delta phi2 in rad)"}
        if self.tca is not None:
            out["tca"] = te_summary(self.tca, mp)
        return out


def te_summary(tca, multipoint) -> dict:
    """TE figures of a TCA of the final pair against the predesigned CMC (arcsec, signed as seed 001 §5).

    ``max_transmission_error_arcsec`` is the lowest point of the TE envelope (positions and exact transfer points)
    after shifting its maximum to 0
    (seed 001 Eq. (6), Figure 7: the paper reports -3.1527 arcsec against the predesigned 3 arcsec);
    ``controlled_range_deviation_arcsec`` the largest |TE - (CMC - CMC(0))| of the pair in contact over the controlled
    range.
    """
    te = tca.te
    fin = np.isfinite(te)
    x = tca.phi1 - tca.phi1_mean
    mp = multipoint
    c0 = float(mp.cmc(0.0))
    lo, hi = mp.control_points.min(), mp.control_points.max()
    inr = fin & (x >= lo - 1e-12) & (x <= hi + 1e-12) & (tca.pair == list(tca.pairs).index(0))
    dev = np.abs(te[inr] - (np.asarray(mp.cmc(x[inr])) - c0)) if np.any(inr) else np.array([np.nan])
    T = 2 * math.pi / tca.z1
    design = float(mp.cmc.depth(T)) if hasattr(mp.cmc, "depth") else float("nan")
    return {
        "max_transmission_error_arcsec": float(tca.te_min - tca.te_max) / ARCSEC,
        "predesigned_magnitude_arcsec": design / ARCSEC,
        "peak_to_peak_arcsec": float(tca.peak_to_peak / ARCSEC),
        "controlled_range_deviation_arcsec": float(np.max(dev) / ARCSEC),
        "control_point_errors_rad": mp.control_point_errors.tolist(),
        "transfer_points_deg": np.degrees(np.atleast_1d(tca.transfer_phi1)).tolist(),
        "edge_contact_positions": int(np.sum(tca.status == ContactStatus.EDGE)),
        "no_contact_positions": int(np.sum(tca.status == ContactStatus.NO_CONTACT)),
        "positions": int(len(te)),
        "pinion_rotation_deg": np.degrees(x).tolist(),
        "transmission_error_arcsec": (te / ARCSEC).tolist(),
    }


def design_seed001_style(gear_cutter, gear_settings, blank, *, eta: float, semi_major_axis: float,
                         te_magnitude: float, side=Side.CONCAVE, n_control: int = 11, interpolation: str = "spline",
                         cmc=None, n_positions: int = 61, straight_blades: bool = False, **synthesis_kw) -> CMCDesign:
    """Seed 001 §5 end to end: local synthesis, CMC by Steps 1-4, multi-point control, TCA of three pairs.

    Parameters
    ----------
    gear_cutter, gear_settings, blank
        As :func:`~spiralbevel.meshing.synthesis.synthesize_pinion` (seed 001 Tables 1 and 4).
    eta : float, rad
        Contact-path direction on the gear (seed 001 Table 2: 6 deg).
    semi_major_axis : float, mm
        Contact-ellipse semi-major axis (3.7 mm).
    te_magnitude : float, rad
        Magnitude of the TE: of the parabola of the local synthesis and of the CMC envelope (3 arcsec).
    side : Side
        Pinion side (concave: seed 001).
    n_control : int
        Control points, evenly spread over the part of the cycle [-pi/z1, pi/z1] where the contact stays on the
        active flanks (``active_range``), or over the whole cycle with ``straight_blades``.
    interpolation : {"spline", "linear", "polynomial"}
        Blank-offset law between the nodes (``multipoint_control``); TCA needs "spline" or "polynomial" (with
        "linear" the TCA is skipped and ``tca`` is None).
    cmc : callable, optional
        Predesigned curve (default ``seed001_cmc(te_magnitude, z1)``).
    n_positions : int
        TCA positions over one mesh cycle.
    straight_blades : bool
        Control and TCA on straight-blade flanks (seed 001 Eq. (16), the paper's model), over the whole cycle; see
        ``multipoint_control``.
    **synthesis_kw
        Passed to ``synthesize_pinion`` (``approach``, ``free``, ``depth``, ...).

    Returns
    -------
    CMCDesign
        (synthesis, multipoint, tca); ``.summary()`` for reports.
    """
    if isinstance(n_control, bool) or not isinstance(n_control, int) or n_control < 3:
        raise DesignError.single("n_control", n_control, "integer >= 3", "-")
    synth = synthesize_pinion(gear_cutter, gear_settings, blank, side=side, eta=eta, semi_major_axis=semi_major_axis,
                              te_magnitude=te_magnitude, **synthesis_kw)
    z1 = synth.mean.kinematics.z1
    if cmc is None:
        cmc = seed001_cmc(te_magnitude, z1)
    T = 2 * math.pi / z1
    lo, hi = (-T / 2, T / 2) if straight_blades else active_range(synth)
    x = np.linspace(lo, hi, n_control)
    mp = multipoint_control(synth, cmc, x, interpolation=interpolation, straight_blades=straight_blades)
    tca = None
    if interpolation != "linear":
        tca = multipoint_tca(mp, n_positions=n_positions, straight_blades=straight_blades)
    return CMCDesign(synth, mp, tca)
