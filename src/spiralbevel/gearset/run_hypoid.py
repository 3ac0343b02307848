"""The hypoid branch of the main job (a face-milled design with ``gear_set.hypoid_offset`` != 0): the ISO 23509
Method 1 pair developed by the default (or given) hypoid local synthesis, its machine settings, design against
achieved mean-point angles, the TCA of both sides with the offset kinematics, the loaded TCA of the drive side with
rigid teeth and (``[ltca]``) with FE tooth compliance, the ease-off against the hypoid conjugate, the CMM grids and
(``[output] stl / step``) the whole teeth as STL and STEP. The analyses that do not take the
offset yet are reported as not available (``hypoid.not_available``), not as failures."""

from __future__ import annotations

from . import facemilled as fm
from . import outputs
from ..errors import NoContactError
from .partial import attempt, mark_failed
from .run_facemilled import _tca_checks, tca_and_flank_highlights
from .units import synthesis_units

#: status of an analysis the hypoid branch does not run yet
NOT_AVAILABLE = "not available for hypoid pairs yet"

#: (report section, what it is, why it is left out) of the analyses not run on a hypoid pair
_LEFT_OUT: tuple = ()


def hypoid_steps(spec) -> int:
    """Progress steps of :func:`run_hypoid` (the rigid loaded TCA counted: it runs when the drive TCA does)."""
    o = spec.output
    return 5 + int(o.plots) + int(spec.ltca is not None) + int(o.stl) + int(o.step)


def run_hypoid(gs, out, steps, report, summary):
    """Develop the hypoid pair of the gear set ``gs`` and write its report sections (and TCA plots) into ``out``."""
    spec, blank = gs.design, gs.blank
    with steps.step("hypoid cutters and machine settings (local synthesis)"):
        setups, synth = gs.setups, gs.synthesis
        report["synthesis"] = {name: synthesis_units(r.summary()) for name, r in synth.items()}
    with steps.step("generated flanks: design against achieved"):
        flanks, machines = fm.flank_report(setups, blank, spec)   # the checks name the design-file keys
        report["flanks"] = flanks
        report["machine_settings"] = machines
    with steps.step("tooth contact analysis (offset kinematics)"):
        from .tca import side_tca

        grids = gs.grids()
        report["tca"], results, outlines, pairs = {}, {}, {}, {}
        for name in ("drive", "coast"):
            pair = pairs[name] = gs.pair(name) if name in synth else None
            if pair is None:
                s1, s2 = fm.PAIR_SIDES[name]
                report["tca"][name] = {"pinion_side": s1.value, "gear_side": s2.value,
                                       "error": f"the {name} side's pinion flank was not synthesized "
                                                "(synthesis.sides): a hypoid pair meshes through its synthesis"}
                res, outline = None, None
            else:
                res, report["tca"][name], outline = side_tca(blank, setups, name, n_positions=spec.tca.positions,
                                                             grids=grids, pair=pair)
            mark_failed(summary.partial, report["tca"][name], f"TCA, {name} side")
            _tca_checks(report, name, res, synth, blank.z1, spec)
            results[name] = res
            if outline is not None:
                outlines[name] = outline
        from .hypoid_cmc import hypoid_cmc_report

        hypoid_cmc_report(report, summary, synth, spec.tca.positions)   # [synthesis] motion_curve = "cmc"
    with steps.step("ease-off (hypoid conjugate) and measurement grids"):
        from .hypoid import hypoid_easeoff_maps
        from .inspection import measurement_files

        report["easeoff"], files, _ = hypoid_easeoff_maps(setups, pairs, out, spec.output.plots)
        summary.files += files
        for name in ("drive", "coast"):
            mark_failed(summary.partial, report["easeoff"][name], f"ease-off, {name} side")
        report["measurement"], files = measurement_files(setups, out)
        summary.files += files
    missing = [{"analysis": what, "section": key, "status": NOT_AVAILABLE, "reason": why}
               for key, what, why in _LEFT_OUT]
    if pairs.get("drive") is not None:
        from .tca import SENSITIVITY, misalignment_sensitivity

        sens, failed = attempt(summary.partial, "misalignment sensitivity", misalignment_sensitivity, blank, setups,
                               "drive", n_positions=spec.tca.positions, pair=pairs["drive"])
        report["tca"]["misalignment_sensitivity"] = failed or sens
        if failed is None:
            mark_failed(summary.partial, sens, "misalignment sensitivity, aligned")
            for case in SENSITIVITY:
                if isinstance(sens.get(case[0]), dict):
                    mark_failed(summary.partial, sens[case[0]], f"misalignment sensitivity, {case[0]} case")
    else:
        report["tca"]["misalignment_sensitivity"] = {"side": "drive", "error": report["tca"]["drive"]["error"]}
    report["hypoid"] = {"offset_mm": float(blank.a), "not_available": missing}
    if results.get("drive") is not None:
        with steps.step("loaded TCA, rigid teeth (drive side)"):
            sec, failed = attempt(summary.partial, "loaded TCA with rigid teeth, drive side", rigid_ltca_section,
                                  pairs["drive"], results["drive"], spec)
            report["hypoid"]["rigid_ltca"] = failed or sec
            if failed is None:
                summary.highlights.append(
                    f"loaded TCA drive, rigid teeth: torque {sec['torque_N_m']:.2f} N m (approach 0.00635 mm), "
                    f"loaded TE {sec['loaded_transmission_error_largest_magnitude_arcsec']:.3f} arcsec, max pressure "
                    f"{sec['max_contact_pressure_N_per_mm2']:.0f} N/mm^2")
    if spec.ltca is not None:   # FE loaded TCA of the [ltca] section (gearset/hypoid_ltca.py)
        from .hypoid_ltca import hypoid_ltca_report

        side = spec.ltca.side
        if side in synth:
            hypoid_ltca_report(gs, report, summary, steps, out, spec.output.plots,
                               outlines.get(side, (None, None))[1])
        else:
            report["ltca"] = {"side": side, "error": f"the {side} side's pinion flank was not synthesized "
                                                     "(synthesis.sides): a hypoid pair meshes through its synthesis"}
            mark_failed(summary.partial, report["ltca"], f"loaded TCA, {side} side")
    if spec.output.plots:
        with steps.step("plots"):
            for name, res in results.items():
                if res is not None:
                    fig = res.plot(outline1=outlines[name][0], outline2=outlines[name][1])
                    fig.suptitle(f"TCA, {name} side: {spec.title}")
                    fig.tight_layout(rect=(0, 0, 1, 0.93))
                    summary.files.append(outputs.save_figure(fig, out / f"tca_{name}.png"))
    if spec.output.stl or spec.output.step:   # whole teeth with their generated fillets (gearset/hypoid_cad.py)
        from .hypoid_cad import hypoid_cad

        hypoid_cad(gs, out, steps, report, summary)
    summary.highlights += tca_and_flank_highlights(report, flanks, machines)
    if missing:
        summary.highlights.append(f"hypoid pair (offset {float(blank.a):g} mm): " + "; ".join(
            f"{w['analysis']} {NOT_AVAILABLE}" for w in missing))


def rigid_ltca_section(pair, tca, spec) -> dict:
    """Loaded TCA of one side of a hypoid pair with rigid teeth (contact flattening only, no FE compliance), in the
    crossed-axes assembly of ``pair`` (:class:`~spiralbevel.meshing.pair.MeshingPair`) over the positions of its
    unloaded ``tca``. The gear torque is the design's ``[ltca] torque`` when it is a number (N m), else the torque at
    which the approach at the mean contact point is 0.00635 mm. Returns the report entry (N m, arcsec, N/mm^2)."""
    import numpy as np

    from ..meshing.ltca import ltca_model

    model = ltca_model(pair.pinion, pair.gear, pair.kinematics, tca, rigid=True, grid=_RIGID_GRID)
    probe = model.run(_PROBE_TORQUE_NMM)
    if probe.approach_torque is None:
        raise NoContactError("hypoid rigid loaded TCA: the pair does not touch at the mean contact position, so no "
                             "torque gives the 0.00635 mm approach")
    T_app = float(probe.approach_torque)
    given = spec.ltca.torque if spec.ltca is not None and not isinstance(spec.ltca.torque, str) else None
    torque = 1000.0 * float(given) if given is not None else T_app
    res = model.run(torque, approach_target=None)
    te = np.asarray(res.te_loaded, float)
    return {
        "model": "rigid teeth: contact flattening only, no FE tooth compliance",
        "side": "drive", "positions": int(te.size),
        "torque_N_m": torque / 1000.0, "torque_for_approach_N_m": T_app / 1000.0,
        "torque_source": "[ltca] torque" if given is not None else "approach 0.00635 mm at the mean contact",
        "loaded_transmission_error_largest_magnitude_arcsec": float(np.max(np.abs(te))),
        "loaded_te_peak_to_peak_arcsec": float(np.ptp(te)),
        "unloaded_transmission_error_largest_magnitude_arcsec": float(np.nanmax(np.abs(tca.te_arcsec))),
        "max_contact_pressure_N_per_mm2": float(res.peak_pressure),
        "pinion_rotation_deg": np.degrees(res.pinion_angles), "loaded_transmission_error_arcsec": te,
    }


#: potential contact points per pair (major x minor axis) of the rigid loaded TCA
_RIGID_GRID = (15, 5)
#: gear torque (N mm) of the probe run that finds the torque of the approach target
_PROBE_TORQUE_NMM = 1e5
