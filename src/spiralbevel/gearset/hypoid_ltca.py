"""Loaded TCA with FE tooth compliance of a hypoid pair (the design's ``[ltca]`` section): the FE tooth segments of
both members are built from their flank grids in their own member frames, and the offset kinematics of the
synthesized pair place them (:func:`~spiralbevel.gearset.ltca.run_ltca` with the hypoid
:class:`~spiralbevel.meshing.pair.MeshingPair`). The contact forces act along the common normal; their moments are
taken about each member's own axis (the wheel torque balances them in the load-sharing solve, the pinion torque is
their moment about the offset pinion axis)."""

from __future__ import annotations

from .partial import attempt, mark_failed

__all__ = ["hypoid_fe_ltca", "hypoid_ltca_report"]


def hypoid_fe_ltca(gs, lt):
    """Loaded TCA of the ``lt.side`` pair of the hypoid gear set ``gs`` with the options ``lt``
    (:class:`~spiralbevel.io.design_schema.LTCASpec`). Returns (LTCAResult or None, report section; N m, arcsec,
    N/mm^2)."""
    from .ltca import run_ltca

    res, section = run_ltca(gs.blank, gs.setups, lt, pair=gs.pair(lt.side))
    section["model"] = ("FE tooth segments of both members placed by the offset kinematics (crossed axes, hypoid "
                        "offset), half-space contact flattening")
    return res, section


def hypoid_ltca_report(gs, report, summary, steps, out=None, plots=False, outline=None):
    """Run :func:`hypoid_fe_ltca` for the design's ``[ltca]`` section into ``report["ltca"]`` (a failure becomes a
    partial result), add its highlight and, with ``plots``, ``ltca.png`` in ``out``. Returns the LTCAResult or None."""
    spec = gs.design
    side = spec.ltca.side
    with steps.step("loaded TCA (FE compliance, offset kinematics)"):
        out_lt, failed = attempt(summary.partial, f"loaded TCA, {side} side", hypoid_fe_ltca, gs, spec.ltca)
        res, report["ltca"] = out_lt if failed is None else (None, failed)
        lt = report["ltca"]
        mark_failed(summary.partial, lt, f"loaded TCA, {side} side")
        if lt.get("status") == "failed":
            summary.highlights.append(f"LTCA {side}: failed ({lt['reason']})")
        elif "torque_N_m" in lt:
            summary.highlights.append(
                f"LTCA {side} (FE, hypoid): torque {lt['torque_N_m']:.2f} N m (approach 0.00635 mm at "
                f"{lt['torque_for_approach_N_m']:.2f} N m), loaded TE "
                f"{lt['loaded_transmission_error_largest_magnitude_arcsec']:.3f} arcsec, max pressure "
                f"{lt['max_contact_pressure_N_per_mm2']:.0f} N/mm^2")
    if plots and res is not None and out is not None:
        from .outputs import save_figure

        fig = res.plot(outline=outline)
        fig.suptitle(f"Loaded TCA, {side} side: {spec.title}")
        fig.tight_layout(rect=(0, 0, 1, 0.93))
        summary.files.append(save_figure(fig, out / "ltca.png"))
    return res
