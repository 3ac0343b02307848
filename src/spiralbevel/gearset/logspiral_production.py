"""Log-spiral designs ready for production in the main job: the mismatched (crowned) pair, its forging relief, the
modified flank grids for CAD and tool paths, and their report sections. Thin: the numbers come from
``meshing.synthesis.logspiral_crowning``, ``meshing.synthesis.logspiral_sensitivity`` and
``manufacturing.forging``."""

from __future__ import annotations

import math

import numpy as np

from ..conventions import Member, Side
from . import logspiral as ls

ARCSEC = math.pi / (180.0 * 3600.0)

#: library parameter -> design-file field
CROWNING_PATHS = {"semi_major_axis": "crowning.semi_major_axis", "path_direction": "crowning.path_direction",
                  "te_level": "crowning.te_level", "approach": "crowning.approach"}


def design_crowning(spec, pair):
    """The :class:`LogSpiralCrowning` of the design file's ``[crowning]`` (None when absent)."""
    from ..errors import DesignError
    from ..meshing.synthesis.logspiral_crowning import design_logspiral_crowning
    from .problems import restated

    c = spec.crowning
    if c is None:
        return None
    try:
        return design_logspiral_crowning(pair, Side(c.side), semi_major_axis=c.semi_major_axis,
                                         path_direction=math.radians(c.path_direction),
                                         te_level=c.te_level * ARCSEC, approach=c.approach)
    except DesignError as err:
        raise restated(err, CROWNING_PATHS, default="crowning") from err


def _crown_of(crowning, member, side):
    if crowning is not None and member is Member.PINION and side is crowning.side:
        return crowning.deviation()
    return None


def design_reliefs(spec, pair, crowning):
    """{(member, side): ReliefDesign} of every flank, relief designed on top of the crowning."""
    from ..manufacturing.forging import design_forging_relief

    mf = spec.manufacturing
    out = {}
    for m in ls.MEMBERS:
        for s in ls.SIDES:
            f = pair.flank(m, s)
            out[(m, s)] = design_forging_relief(f.surface, f.domain, mf.die_direction, math.radians(mf.draft_angle),
                                                base_deviation=_crown_of(crowning, m, s))
    return out


def contact_surface(pair, member, side, crowning=None, reliefs=None):
    """The flank as TCA sees it: exact log-spiral flank, crowned and/or relieved when asked."""
    from ..manufacturing._flank import check_flank
    from ..meshing.contact_surface import NormalDeviation
    from ..meshing.synthesis.logspiral_crowning import SumDeviation, logspiral_contact_surface

    base = logspiral_contact_surface(pair, member, side)
    parts = [_crown_of(crowning, member, side)]
    rd = (reliefs or {}).get((member, side))
    if rd is not None and rd.relief is not None:
        f = pair.flank(member, side)
        parts.append(rd.relief.contact_deviation(check_flank(f.surface, f.domain)))
    parts = [p for p in parts if p is not None]
    return NormalDeviation(base, SumDeviation(*parts)) if parts else base


def modified_tooth_grids(pair, member, n_face, n_profile, crowning=None, reliefs=None):
    """(convex, concave) (points, normals) of one tooth of ``member`` with its modifications, member frame, in the
    grid order of :meth:`DesignedFlank.grid` (toe to heel, root to top)."""
    out = []
    for s in ls.SIDES:
        f = pair.flank(member, s)
        varphi, phi = f.domain.grid(n_face, n_profile)
        if f.surface.spiral_angle < 0:
            varphi, phi = varphi[::-1], phi[::-1]
        if f.domain.psi_max <= 0:
            varphi, phi = varphi[:, ::-1], phi[:, ::-1]
        surf = contact_surface(pair, member, s, crowning, reliefs)
        out.append(surf.evaluate(np.stack([varphi, phi], -1)))
    return tuple(out)


def forging_section(spec, pair, reliefs, crowning, out, summary, plots):
    """Report section ``forging``: the two feature parameters, deviation and draft of every modified flank."""
    from ..manufacturing.forging import RelievedFlank, relieved_draft_map

    mf = spec.manufacturing
    theta = math.radians(mf.draft_angle)
    section = {"die_direction": list(mf.die_direction), "draft_angle_deg": mf.draft_angle,
               "deviation_sign": "along the outward normal, positive = material added", "flanks": {}}
    maps, devs = [], []
    for (m, s), rd in reliefs.items():
        f = pair.flank(m, s)
        crown = _crown_of(crowning, m, s)
        before = relieved_draft_map(RelievedFlank(f.surface, f.domain, None, crown), mf.die_direction, theta)
        after = relieved_draft_map(rd.relieved, mf.die_direction, theta)
        entry = {"failing_area_fraction_before": before.failing_area_fraction,
                 "failing_area_fraction_after": after.failing_area_fraction,
                 "passes": bool(after.passes), "relieved": rd.relief is not None}
        if rd.relief is not None:
            r = rd.relief
            delta = f.surface.base_cone_angle
            entry.update({
                "start_psi_deg": math.degrees(r.start_psi),
                "start_cone_angle_deg": math.degrees(math.acos(math.cos(r.start_psi) * math.cos(delta))),
                "rate": r.rate,
                "max_deviation_um": rd.max_deviation * 1e3,
                "added_volume_mm3": rd.volume,
                "relieved_area_fraction": rd.relieved_fraction,
            })
            g = RelievedFlank(f.surface, f.domain, r)
            varphi, phi = f.domain.grid(31, 15)
            pts, _, _, w = g.evaluate(varphi, phi)
            devs.append((f"{m.value} {s.value}: forging relief", pts, w * 1e3, "um"))
        section["flanks"][f"{m.value}_{s.value}"] = entry
        maps.append((f"{m.value} {s.value} (relieved)", after, theta))
    if plots:
        from . import outputs
        from ..viz.draft_plot import plot_draft_maps

        summary.files.append(outputs.save_figure(plot_draft_maps(maps), out / "draft_map_relieved.png"))
        if devs:
            from ..viz.flank_maps import plot_flank_fields

            fig = plot_flank_fields(devs, title="Forging relief: deviation from the theoretical flank",
                                    cmap="viridis", symmetric=False)
            summary.files.append(outputs.save_figure(fig, out / "forging_deviation.png"))
    return section


def mismatch_section(spec, pair, crowning, reliefs, out, summary, plots):
    """Report section ``mismatch``: targets, crowning, TCA of the modified pair and misalignment sensitivity."""
    from ..meshing.kinematics import BevelPairKinematics
    from ..meshing.misalignment import Misalignment
    from ..meshing.synthesis.logspiral_sensitivity import misalignment_sensitivity
    from ..meshing.tca import solve_tca
    from ..meshing.tca_result import ContactStatus

    c = spec.crowning
    s1 = crowning.side
    s2 = s1.mate
    kin = BevelPairKinematics(pair.shaft_angle, pair.pinion.teeth, pair.gear.teeth)
    c1 = contact_surface(pair, Member.PINION, s1, crowning, reliefs)
    c0 = contact_surface(pair, Member.PINION, s1)
    c2 = contact_surface(pair, Member.GEAR, s2, None, reliefs)
    p1 = pair.mean_point(Member.PINION, s1).point
    phi1m = -math.atan2(p1[1], p1[0])
    start = np.r_[c1.reference_params, c2.reference_params, -kin.ratio * phi1m]
    res = solve_tca(c1, c2, kin, phi1_mean=phi1m, n_positions=21, start=start)
    mid = len(res.phi1) // 2
    te_level = -float(np.nanmin(res.te))
    a_mean = float(np.max(res.semi_axes[mid]))
    inside = bool(np.all(res.status == ContactStatus.OK))
    section = {
        "modification": "pinion crowning (profile, lengthwise and diagonal): three coefficients for three targets; "
                        "the gear stays the exact conjugate flank",
        "pinion_side": s1.value, "gear_side": s2.value,
        "targets": {"semi_major_axis_mm": c.semi_major_axis, "path_direction_deg": c.path_direction,
                    "te_level_arcsec": c.te_level, "approach_mm": c.approach},
        "crowning_mm_per_rad2": {"c00": float(crowning.coeffs[0]), "c01": float(crowning.coeffs[1]),
                                 "c11": float(crowning.coeffs[2])},
        "tca": {"te_level_arcsec": te_level / ARCSEC, "te_level_error": te_level / (c.te_level * ARCSEC) - 1.0,
                "semi_major_axis_mm": a_mean, "semi_major_axis_error": a_mean / c.semi_major_axis - 1.0,
                "point_contact_inside_flanks": inside,
                "status_counts": {st.name: int(np.sum(res.status == st)) for st in ContactStatus},
                "te_arcsec": [float(x) for x in res.te_arcsec]},
    }
    mz = c.misalignment
    mis = {"pinion_axial": Misalignment(pinion_axial=mz.pinion_axial),
           "gear_axial": Misalignment(gear_axial=mz.gear_axial), "offset": Misalignment(offset=mz.offset),
           "shaft_angle": Misalignment(shaft_angle=math.radians(mz.shaft_angle))}
    study = misalignment_sensitivity(c0, c1, c2, kin, phi1_mean=phi1m, phi2_mean=res.phi2_mean,
                                     drive_sign=res.drive_sign, misalignments=mis)
    # the first touch of all flank points must reproduce the surface TCA: otherwise another point (a forging relief,
    # an edge) touches before the designed contact point
    gap = float(np.nanmax(study.aligned_mismatched_te - res.te))
    section["tca"]["first_touch_excess_arcsec"] = gap / ARCSEC
    section["tca"]["interference_free"] = bool(gap < 0.2 * ARCSEC)  # first-touch grid method: <0.1" measured
    sens = {}
    for r in study.rows:
        entry = {("size_deg" if r.name == "shaft_angle" else "size_mm"):
                 r.value if r.name != "shaft_angle" else math.degrees(r.value),
                 "line_contact_te_growth_arcsec": r.line_growth / ARCSEC,
                 "mismatched_te_growth_arcsec": r.mismatched_growth / ARCSEC,
                 "line_contact_te_ptp_arcsec": r.line_ptp / ARCSEC,
                 "mismatched_te_ptp_arcsec": r.mismatched_ptp / ARCSEC}
        try:  # surface TCA of the mismatched pair under the same misalignment (cross-check of the first-touch TE)
            rm = solve_tca(c1, c2, kin, phi1_mean=phi1m, n_positions=21, start=start, misalignment=mis[r.name])
            entry["mismatched_tca_te_ptp_arcsec"] = rm.peak_to_peak / ARCSEC
            entry["mismatched_tca_inside_flanks"] = bool(np.all(rm.status == ContactStatus.OK))
        except Exception as err:  # noqa: BLE001 - reported, not fatal
            entry["mismatched_tca_error"] = str(err)
        sens[r.name] = entry
    section["misalignment_sensitivity"] = {
        "method": "TE from the first touch of sampled flank points, edge contacts included (both pairs); growth = "
                  "peak-to-peak TE with the misalignment minus the aligned peak-to-peak", "rows": sens}
    if plots:
        from . import outputs

        summary.files.append(outputs.save_figure(res.plot(), out / "tca_mismatched.png"))
    return res, section
