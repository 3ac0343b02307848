"""The CMC entries of the hypoid report: a hypoid pair whose pinion is controlled to the predesigned combined motion
curve (``[synthesis] motion_curve = "cmc"``, :func:`~spiralbevel.meshing.synthesis.hypoid_multipoint.design_hypoid_cmc`)
gets ``tca.cmc`` (the TE of the controlled pair over one mesh cycle against the curve, arcsec) and
``tca.control_point_errors_arcsec``, as the spiral bevel report's real-flank figures (``run_facemilled``)."""

from __future__ import annotations

from .units import synthesis_units

__all__ = ["hypoid_cmc_report"]


def hypoid_cmc_report(report, summary, synth, n_positions: int = 61) -> None:
    """Write ``report["tca"]["cmc"]`` and a highlight for the first synthesized side with multi-point control.

    Parameters
    ----------
    report : dict
        The job report (its ``tca`` section exists).
    summary : JobSummary
        ``highlights`` is appended to.
    synth : {side name: HypoidSynthesis or HypoidCMCSynthesis}
    n_positions : int
        TCA positions over one mesh cycle.

    Notes
    -----
    The TCA against the curve is run on the pinion flank of the job (``synth[side].pinion_flank``): where the
    derived edge radius was refitted to the generated root slot after the control
    (:func:`~spiralbevel.gearset.hypoid_fillet.fit_edge_radii`, a smaller radius: the blade, on which every
    control-point contact lies, reaches further down), that flank differs from the controlled one below the old
    fillet junction only, and the TCA is that of the pair the job reports.
    """
    import dataclasses

    from ..meshing.synthesis.hypoid_multipoint import hypoid_multipoint_tca

    from ..meshing.synthesis.cmc_design import te_summary

    cmc = {name: r for name, r in synth.items() if getattr(r, "multipoint", None) is not None}
    if not cmc:
        return
    name, design = next(iter(cmc.items()))
    mp = design.multipoint
    tca = design.tca
    if tca is not None and design.pinion_flank is not mp.pinion_flank:    # edge radius refitted after the control
        mp = dataclasses.replace(mp, pinion_flank=design.pinion_flank)
        tca = hypoid_multipoint_tca(mp, n_positions=n_positions)
    real = synthesis_units(te_summary(tca, mp)) if tca is not None else None
    lo, hi = mp.offset_range
    report["tca"]["cmc"] = {"side": name, "real_flanks": real,
                            "blank_offset_increment_range_mm": [lo, hi]}
    errors = synthesis_units({"control_point_errors_rad": mp.control_point_errors.tolist()})
    report["tca"]["control_point_errors_arcsec"] = errors["control_point_errors_arcsec"]
    text = (f"CMC ({name}, hypoid): control-point errors <= {max(errors['control_point_errors_arcsec']):.2e} arcsec, "
            f"blank offset varied by {1000 * lo:.2f} .. {1000 * hi:.2f} um")
    if real is not None:
        text += (f"; max TE {real['max_transmission_error_arcsec']:.4f} arcsec against the predesigned "
                 f"{real['predesigned_magnitude_arcsec']:.4f}")
    summary.highlights.append(text)
