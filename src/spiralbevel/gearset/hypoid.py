"""Face-milled hypoid designs in the job: the four flanks of a hypoid pair (basic settings at each member's mean cone
distance, local synthesis of the pinion in the crossed-axes frame), and the hypoid pair of one side phased for meshing
with the offset kinematics. Used by :class:`~spiralbevel.gearset.GearSet` (``spiralbevel run``, ``machine``) and by
``spiralbevel correct`` and ``sweep`` (``job.correction.flank_setups``, ``job.sweep_hypoid``); the paths that still
assemble spiral bevel flanks only stop on a hypoid (``gearset.blank.require_no_offset``)."""

from __future__ import annotations

import math

import numpy as np

from ..conventions import Member
from ..errors import ConvergenceError, DesignError, GeometryError, NoContactError
from ..meshing.tca_result import ARCSEC
from .facemilled import (DEFAULT_PATH_DIRECTIONS, MEMBERS, PAIR_SIDES, SIDES, FlankSetup, _default_cutter, _FREE,
                         _given_cutter, _given_settings, _in_design_file, effective_synthesis)

__all__ = ["hypoid_easeoff_maps", "hypoid_pair", "setup_hypoid_flanks"]

#: positions of the TCA that checks the bearing of a synthesized hypoid pair over one mesh cycle
_CHECK_POSITIONS = 41
#: design-file keys of the multi-point control's arguments (``[synthesis] motion_curve = "cmc"``)
_CMC_PATHS = {"control_points": "synthesis.control_points", "n_control": "synthesis.control_points",
              "interpolation": "synthesis.offset_interpolation"}

#: default synthesis against a Formate gear: semi-major axis of the contact ellipse as a fraction of the face width,
#: and the pinion settings solved (modified roll 2C in place of the blank offset). The Formate gear's straight profile
#: leaves a large third-order mismatch with a generated pinion: with a 4-6 mm ellipse and the blank offset free the
#: Sample 2 pairs interfere (300-800 arcsec of TE, tests/meshing/test_formate_tca.py); a shorter ellipse
#: (larger relative curvature along the path) keeps the TE parabolic at the design level
#: (tests/gearset/test_formate_example.py)
FORMATE_SEMI_MAJOR_FRACTION = 0.0675
FORMATE_FREE = "modified-roll"


def is_formate(spec) -> bool:
    """True when the design's gear is Formate (``gear_set.gear_generation = "formate"``)."""
    return getattr(spec.gear_set, "gear_generation", "generated") == "formate"


def _formate_gear(spec, blank, view, key, fs, side):
    """Cutter, settings and flank of a Formate gear flank: blade angle and machine spiral angle solved for the design
    mean-point angles (``meshing.formate.solve_formate_settings``); a given cutter or machine is refused."""
    from ..meshing.formate import solve_formate_settings

    for part in ("cutter", "machine"):
        if getattr(fs, part) is not None:
            raise DesignError.single(f"face_milling.{key}.{part}", "given", "not given for a Formate gear", "-",
                                     "the Formate gear's cutter and settings are solved from the blank "
                                     "(gear_set.gear_generation = 'formate')")
    return solve_formate_settings(blank, Member.GEAR, side, _default_cutter(spec, view, Member.GEAR, side))


def _basic(spec, blank):
    from ..design.hypoid_member import member_blank
    from ..generation.basic_settings_solve import solve_basic_settings
    from ..generation.flank import generate_flank

    from ..generation.basic_settings_solve import FlankFit
    from ..machine.default_cutter import design_pressure_angle

    out = {}
    for m in MEMBERS:
        view = member_blank(blank, m)
        for s in SIDES:
            key = f"{m.value}_{s.value}"
            fs = getattr(spec.face_milling, key)
            fit = None
            if m is Member.GEAR and is_formate(spec):
                cutter, settings, flank = _formate_gear(spec, blank, view, key, fs, s)
                mp = flank.mean_point()
                fit = FlankFit(design_pressure_angle(blank, m, s), mp.pressure_angle, abs(float(blank.beta_m2)),
                               mp.spiral_angle, flank.root_deviation(), 0)
                out[(m, s)] = FlankSetup(m, s, cutter, settings, flank, "Formate gear: cutter surface, blade angle "
                                         "and machine spiral angle solved for the design mean-point angles", fit)
                continue
            try:
                cutter = _given_cutter(fs.cutter, s) if fs.cutter is not None else _default_cutter(spec, view, m, s)
                if fs.machine is not None:
                    settings, source = _given_settings(fs.machine), "given"
                    flank = generate_flank(cutter, settings, view, m, s)
                    flank.mean_point()
                else:
                    cutter, settings, flank, fit = solve_basic_settings(
                        view, m, s, cutter, solve_blade_angle=fs.cutter is None, roll=spec.face_milling.roll)
                    source = (f"hypoid basic settings solved for the design pressure and spiral angles at R_m{m.index}"
                              + ("" if fs.cutter is None else " (given cutter: spiral angle only)"))
            except DesignError as err:
                raise _in_design_file(err, key, fs) from err
            out[(m, s)] = FlankSetup(m, s, cutter, settings, flank, source, fit)
    return out


def _off_flank(res) -> int:
    """TCA positions over one mesh cycle where the synthesized pair's contact is not inside both flanks."""
    from ..meshing.synthesis.hypoid_local import tca_surfaces
    from ..meshing.tca import solve_tca

    try:
        res.pinion_flank.grid(9, 5, curvature=False)
    except GeometryError:
        return _CHECK_POSITIONS
    c1, c2, start = tca_surfaces(res)
    try:
        tca = solve_tca(c1, c2, res.kinematics, n_positions=_CHECK_POSITIONS, start=start)
    except (NoContactError, ConvergenceError):
        return _CHECK_POSITIONS
    return int(np.sum(~np.isfinite(tca.te) | tca.edge_contact))


def _synthesize(spec, blank, setups):
    from ..meshing import synthesis as syn
    from ..meshing.synthesis.hypoid_local import synthesize_hypoid_pinion

    sy = effective_synthesis(spec, blank)
    if sy is None:
        return {}, {}
    default = getattr(sy, "_default", False)
    if default and is_formate(spec):
        sy = sy.model_copy(update=dict(semi_major_axis=FORMATE_SEMI_MAJOR_FRACTION * float(blank.b2),
                                       free=FORMATE_FREE))
    new, results = {}, {}
    for name in sy.sides:
        s1, s2 = PAIR_SIDES[name]
        gear, pin = setups[(Member.GEAR, s2)], setups[(Member.PINION, s1)]
        etas = DEFAULT_PATH_DIRECTIONS if default else (sy.path_direction,)
        best, last = None, None
        for eta in etas:
            try:
                res = synthesize_hypoid_pinion(
                    gear.flank, pin.cutter, pin.settings, blank, side=s1, eta=math.radians(eta),
                    semi_major_axis=sy.semi_major_axis, te_magnitude=sy.te_magnitude * ARCSEC, approach=sy.approach,
                    free=getattr(syn, _FREE[sy.free]))
            except (ConvergenceError, GeometryError) as err:
                if not default:
                    raise
                last = err
                continue
            off = _off_flank(res) if default else 0
            if best is None or off < best[0]:
                best = (off, res, eta)
            if off == 0:
                break
        if best is None:
            # quote the last failure without its own iteration count: this error appends it once
            raise ConvergenceError(f"{name} side: the default local synthesis of the hypoid pinion found no pinion "
                                   f"flank for any path direction (last: {getattr(last, 'message', last)}); give a "
                                   "[synthesis] section with another synthesis.free (\"fixed-blade\" or "
                                   "\"modified-roll\"), a synthesis.path_direction or a synthesis.semi_major_axis "
                                   "(the keys it leaves out keep the defaults: both sides, the search over path "
                                   "directions)",
                                   getattr(last, "iterations", 0), getattr(last, "residual", float("inf")),
                                   getattr(last, "last", None)) from last
        off, res, eta = best
        note = "" if off == 0 else f"; bearing off the flanks at {off} of {_CHECK_POSITIONS} positions"
        if sy.motion_curve == "cmc":    # multi-point control of the blank offset (synthesis/hypoid_multipoint.py)
            from ..meshing.synthesis.hypoid_multipoint import design_hypoid_cmc
            from .problems import restated

            try:
                res = design_hypoid_cmc(res, te_magnitude=sy.te_magnitude * ARCSEC, n_control=sy.control_points,
                                        interpolation=sy.offset_interpolation, n_positions=spec.tca.positions)
            except DesignError as err:
                raise restated(err, _CMC_PATHS, default="synthesis") from err
            note += f"; multi-point control to the CMC, {sy.control_points} points, {sy.offset_interpolation} law"
        new[(Member.PINION, s1)] = FlankSetup(
            Member.PINION, s1, res.pinion_cutter, res.pinion_settings, res.pinion_flank,
            f"hypoid local synthesis ({name} side, path {eta:g} deg, free = {sy.free}{note})")
        results[name] = res
    return new, results


def setup_hypoid_flanks(spec, blank, with_synthesis: bool = False):
    """Cutters, settings and generated flanks of the four flanks of a face-milled hypoid design.

    The basic settings of each member are solved at its own mean cone distance for the design mean-point angles; the
    pinion side of each synthesized pair side is then replaced by the hypoid local synthesis at the pitch point
    (the design file's ``[synthesis]``, or the developed-pair defaults with the path direction chosen to keep the
    bearing inside the flanks); a derived edge radius that the generated root slot does not hold is then refitted
    (:func:`~spiralbevel.gearset.hypoid_fillet.fit_edge_radii`). Returns ``{(member, side): FlankSetup}`` (and
    ``{side name: HypoidSynthesis}`` with ``with_synthesis``).
    """
    from .hypoid_fillet import fit_edge_radii

    out = _basic(spec, blank)
    new, synth = _synthesize(spec, blank, out)
    out.update(new)
    fit_edge_radii(spec, blank, out, synth)   # the derived edge radius that the generated root slot holds
    return (out, synth) if with_synthesis else out


def hypoid_pair(synthesis):
    """The synthesized hypoid pair of one side phased for meshing: a
    :class:`~spiralbevel.meshing.pair.MeshingPair` whose kinematics are the offset
    :class:`~spiralbevel.meshing.hypoid_kinematics.HypoidPairKinematics` and whose flanks meet at the pitch point M of
    the synthesis at zero roll (``synthesis``: a :class:`~spiralbevel.meshing.synthesis.hypoid_local.HypoidSynthesis`).
    """
    from ..meshing.pair import MeshingPair
    from ..meshing.synthesis.hypoid_local import tca_surfaces

    c1, c2, start = tca_surfaces(synthesis)
    return MeshingPair(c1, c2, synthesis.kinematics, start)


def hypoid_easeoff_maps(setups, pairs, out=None, plots: bool = False):
    """Ease-off of the drive and coast pinion flanks of a hypoid pair against the flanks exactly conjugate to the
    wheel flanks in the crossed-axes pair (:func:`~spiralbevel.meshing.hypoid_conjugate.hypoid_easeoff`), as the
    ``easeoff`` report section of the spiral bevel job (``gearset.inspection.easeoff_maps``).

    Parameters
    ----------
    setups : {(Member, Side): FlankSetup}
    pairs : {side name: MeshingPair or None}
        The phased hypoid pairs (:func:`hypoid_pair`); a side without a pair gets an ``error`` entry.
    out : Path, optional
        Directory of the plots (with ``plots``).

    Returns
    -------
    (dict, list of str, dict)
        Report section (mm; positive = clearance, material removed from the pinion), plot files written, and
        {side name: EaseOff or None}.
    """
    from ..meshing.hypoid_conjugate import hypoid_easeoff

    section: dict = {"sign": "positive = clearance (material removed from the pinion)"}
    files: list = []
    maps: dict = {}
    for name, (s1, s2) in PAIR_SIDES.items():
        maps[name] = None
        pair = pairs.get(name)
        if pair is None:
            section[name] = {"error": f"the {name} side's pinion flank was not synthesized (synthesis.sides)"}
            continue
        try:
            eo = hypoid_easeoff(setups[(Member.PINION, s1)].flank, pair.gear, pair.kinematics)
        except (GeometryError, ConvergenceError, NoContactError) as err:
            section[name] = {"error": str(err)}
            continue
        maps[name] = eo
        v = eo.values[np.isfinite(eo.values)]
        section[name] = {"min_mm": float(v.min()), "max_mm": float(v.max()),
                         "rms_mm": float(np.sqrt(np.mean(v**2))), "grid": list(eo.values.shape)}
        if plots and out is not None:
            from .outputs import save_figure

            fig = eo.plot(kind="both", title=f"Ease-off of the pinion {s1.value} flank against the hypoid conjugate "
                                             f"of the gear {s2.value} flank ({name} side), µm; + = clearance")
            files.append(save_figure(fig, out / f"easeoff_{name}.png"))
    return section, files, maps
