"""The developed pair by default: local synthesis of the pinion flanks against the gear's, with the default bearing
and TE level when a face-milled design has no ``[synthesis]`` section (docs/conventions.md, "Developed pair by
default"): the synthesis of the design (the section's keys over the defaults), and per pinion side the search of
:mod:`~spiralbevel.gearset.default_candidates`, at lower TE levels when no candidate at the design's gives a pinion
flank that covers the face and meshes, with the source line of the flank that was chosen."""

from __future__ import annotations

import math
import warnings

from ..conventions import Member, Side
from ..errors import ConvergenceError, DesignError, DesignWarning
from ..meshing.tca_result import ARCSEC
from .default_candidates import (_ALL_DIRECTIONS, _CHECK_POSITIONS, _FREE, DEFAULT_MAX_SYNTHESES,
                                 DEFAULT_OTHER_SET_SYNTHESES, _candidates)
from .flank_setup import SIDES, FlankSetup

#: defaults of the developed pair when a face-milled design has no ``[synthesis]`` section (docs/conventions.md,
#: "Developed pair by default"): both sides, contact path 0 deg from the gear's profile direction, contact-ellipse
#: semi-major axis 0.15 b (a bearing about a third of the face width long) at an elastic approach of b/5827 (the
#: Gleason 0.00635 mm at seed 001's 37 mm face width, scaled with the size so that geometrically similar designs get
#: similar relative curvatures), parabolic TE of 8 arcsec over half a mesh cycle on each side of the mean contact
DEFAULT_SYNTHESIS = dict(sides=("drive", "coast"), path_direction=0.0, semi_major_axis_fraction=0.15,
                         approach_fraction=0.00635 / 37.0, te_magnitude=8.0)

#: TE levels (fractions of the default's) tried when no candidate at the default level gives a pinion flank that
#: covers the face and meshes, with at most ``DEFAULT_FALLBACK_SYNTHESES`` syntheses each: a parabolic TE of a given
#: angle asks for a relative profile curvature that grows with z1^2 and the ratio (the contact moves slowly across a
#: fine pinion's profile), and on a fine-pitch pinion of a large set the settings that reach it lie far from the
#: blank's (a blank offset of 153 mm at R_m = 551 mm for 8 arcsec on a 34/194 pinion, bench/bench_robustness.py)
DEFAULT_TE_FALLBACK = (0.5, 0.25)
DEFAULT_FALLBACK_SYNTHESES = 6


def _default_spec_class():
    from ..io.design_schema import SynthesisSpec

    class DefaultSynthesis(SynthesisSpec):
        """The default synthesis: may fall back to the other sets of solved settings."""

        _default: bool = True

    return DefaultSynthesis


def effective_synthesis(spec, blank):
    """The synthesis of the design: the developed-pair defaults, each overridden by the key the ``[synthesis]``
    section gives (``model_fields_set``: the keys written in the design file).

    A key the section leaves out keeps the developed-pair default (``DEFAULT_SYNTHESIS``): both sides (those whose
    pinion machine settings the design file gives keep them), semi-major axis 0.15 b, approach b/5827, parabolic TE
    8 arcsec; without ``path_direction`` the default search over path directions (and depths of the mean contact
    point, sets of solved settings, the given ``free`` first, and lower TE levels) runs, with the section's values.
    Returns ``None`` when nothing is synthesized (every pinion side with given machine settings keeps them).
    """
    given = spec.synthesis
    keys = set() if given is None else set(given.model_fields_set)
    fmspec = spec.face_milling
    if "sides" in keys:
        sides = tuple(given.sides)
    else:
        sides = tuple(name for name in DEFAULT_SYNTHESIS["sides"]
                      if getattr(fmspec, f"pinion_{PAIR_SIDES[name][0].value}").machine is None)
    if not sides:
        return None
    d = DEFAULT_SYNTHESIS
    values = dict(sides=sides, path_direction=d["path_direction"],
                  semi_major_axis=d["semi_major_axis_fraction"] * float(blank.b2),
                  approach=d["approach_fraction"] * float(blank.b2), te_magnitude=d["te_magnitude"])
    if given is not None:
        values.update({k: getattr(given, k) for k in keys if k != "sides"})
    cls = _default_spec_class() if "path_direction" not in keys else type(given)
    return cls(**values)


#: design-file names of the pair sides: (pinion side, gear side)
PAIR_SIDES = {"drive": (Side.CONCAVE, Side.CONVEX), "coast": (Side.CONVEX, Side.CONCAVE)}


def synthesize_sides(spec, blank, setups, sy=None):
    """Local synthesis of the pinion flank of each side listed in ``sy`` (default ``spec.synthesis``).

    Returns ({(PINION, side): FlankSetup}, {side name: SynthesisResult}).
    """
    from ..meshing import synthesis as syn

    from .problems import restated

    try:
        return _synthesize_sides(spec.synthesis if sy is None else sy, blank, setups, syn, _derived_edge_radius(spec),
                                 _slot_floors(spec))
    except DesignError as err:
        raise restated(err, SYNTHESIS_PATHS, default="synthesis") from err


SYNTHESIS_PATHS = {
    "eta": "synthesis.path_direction", "semi_major_axis": "synthesis.semi_major_axis",
    "te_magnitude": "synthesis.te_magnitude", "m21_prime": "synthesis.te_magnitude", "approach": "synthesis.approach",
    "eta/semi_major_axis": "synthesis.path_direction / semi_major_axis / te_magnitude (together)",
}


def _derived_edge_radius(spec) -> dict:
    """{pinion side: True when its cutter's edge radius is derived} (neither ``face_milling.edge_radius`` nor the
    side's cutter given): only a derived edge radius of a synthesized pinion is refitted (gearset/pinion_fillet.py)."""
    fm = spec.face_milling
    return {s: fm.edge_radius is None and getattr(fm, f"pinion_{s.value}").cutter is None for s in SIDES}


def _slot_floors(spec) -> dict:
    """{pinion side: narrowest point width the refit tries, as a fraction of the cutter's}: ``SLOT_FLOOR`` for a
    derived point width, 1 for a given one (``face_milling.point_width`` or the side's cutter; kept as given)."""
    from .slot_open import SLOT_FLOOR

    fm = spec.face_milling
    return {s: SLOT_FLOOR if fm.point_width is None and getattr(fm, f"pinion_{s.value}").cutter is None else 1.0
            for s in SIDES}


def _synthesize_sides(sy, blank, setups, syn, refit=None, floors=None):
    new, results, raised = {}, {}, {}
    refit = refit or {}
    for k_side, name in enumerate(sy.sides):
        s1, s2 = PAIR_SIDES[name]
        # the slot rule of the default synthesis (gearset/slot_open.py) on the side whose other pinion side is final
        # (synthesized before it, or not synthesized at all)
        s_o = Side.CONCAVE if s1 is Side.CONVEX else Side.CONVEX
        later = {PAIR_SIDES[n][0] for n in sy.sides[k_side + 1:]}
        slot_other = (None if floors is None or s_o in later or (Member.PINION, s_o) not in setups
                      else new.get((Member.PINION, s_o), setups[(Member.PINION, s_o)]))
        gear = setups[(Member.GEAR, s2)]
        if sy.motion_curve == "cmc":
            from ..meshing.synthesis.cmc_design import design_seed001_style

            design = design_seed001_style(
                gear.cutter, gear.settings, blank, side=s1, eta=math.radians(sy.path_direction),
                semi_major_axis=sy.semi_major_axis, te_magnitude=sy.te_magnitude * ARCSEC,
                n_control=sy.control_points, interpolation=sy.offset_interpolation, approach=sy.approach,
                free=getattr(syn, _FREE[sy.free]))
            mp = design.multipoint
            new[(Member.PINION, s1)] = FlankSetup(
                Member.PINION, s1, design.synthesis.pinion_cutter, mp.pinion_settings, mp.pinion_flank,
                f"local synthesis + multi-point control ({name} side)")
            results[name] = design
            continue
        pin = setups[(Member.PINION, s1)]
        default = getattr(sy, "_default", False)
        # the default synthesis lowers the parabolic TE level when the candidates at the default level reach the
        # synthesized geometry but none gives a pinion flank that covers the face and meshes (DEFAULT_TE_FALLBACK)
        levels = (sy.te_magnitude,) + (tuple(sy.te_magnitude * f for f in DEFAULT_TE_FALLBACK) if default else ())
        for k_level, te in enumerate(levels):
            best, tried, last = _candidates(sy, blank, gear, pin, s1, te, syn, default,
                                            DEFAULT_MAX_SYNTHESES if k_level == 0 else DEFAULT_FALLBACK_SYNTHESES,
                                            refit.get(s1, False),
                                            DEFAULT_OTHER_SET_SYNTHESES if k_level == 0 else DEFAULT_FALLBACK_SYNTHESES,
                                            (slot_other, floors), raised)
            # a lower level only when this one reached the geometry but no flank covered the face and meshed
            if best is None or not default or best[0] < _CHECK_POSITIONS:
                break
        levels = levels[:k_level + 1]
        if best is None:   # every default candidate failed: say so, with the last reason
            raise ConvergenceError(f"{name} side: the default local synthesis of the pinion found no pinion flank for "
                                   f"any path direction ({', '.join(f'{e:g}' for e in _ALL_DIRECTIONS)} deg; "
                                   f"{tried} syntheses; last: {last}); give a [synthesis] section "
                                   "(synthesis.path_direction, synthesis.semi_major_axis, synthesis.te_magnitude)",
                                   getattr(last, "iterations", 0), getattr(last, "residual", float("inf")),
                                   getattr(last, "last", None)) from last
        if default and best[0] >= _CHECK_POSITIONS:   # no candidate's pinion flank covers the face and meshes
            st = best[1].pinion_settings
            raise ConvergenceError(f"{name} side: the default local synthesis of the pinion gave no pinion flank that "
                                   f"covers the face and meshes with the gear (path directions "
                                   f"{', '.join(f'{e:g}' for e in _ALL_DIRECTIONS)} deg, parabolic TE "
                                   f"{', '.join(f'{t:g}' for t in levels)} arcsec; the settings that reach the "
                                   f"synthesized geometry lie far from the blank's: blank offset "
                                   f"{st.blank_offset:.1f} mm, machine centre to back "
                                   f"{st.machine_centre_to_back:.1f} mm at R_m = {float(blank.Rm):.1f} mm); give a "
                                   f"[synthesis] section with synthesis.te_magnitude below {levels[-1]:g} arcsec "
                                   "(with synthesis.path_direction, synthesis.semi_major_axis), or change "
                                   "gear_set.cutter_radius or gear_set.mean_spiral_angle", tried, float("inf"), None)
        _, res, free = best
        source = f"local synthesis ({name} side, free = {free})"
        if k_level:   # a reduced TE level is not the design's: say so (the TCA's TE check compares with the level used)
            source += f"; parabolic TE level reduced to {levels[-1]:g} arcsec (design {sy.te_magnitude:g} arcsec)"
            warnings.warn(f"{name} side: the default synthesis found no pinion flank that covers the face and meshes "
                          f"at the design TE level {sy.te_magnitude:g} arcsec and developed the pair at "
                          f"{levels[-1]:g} arcsec (synthesis.{name}.te_magnitude_arcsec); give a [synthesis] section "
                          "(synthesis.te_magnitude, synthesis.path_direction, synthesis.semi_major_axis) or change "
                          "gear_set.cutter_radius or gear_set.mean_spiral_angle", DesignWarning, stacklevel=2)
        if res.pinion_cutter.point_width < pin.cutter.point_width - 1e-9:   # gearset/pinion_fillet.lower_root
            source += (f"; root lowered onto the root cone: blade extended to a point width of "
                       f"{res.pinion_cutter.point_width:.3f} mm, sliding base moved, blade surface unchanged")
        up = id(res) in raised and raised[id(res)][0] is res
        if up:   # gearset/pinion_fillet.raise_root
            source += (f"; root raised {raised[id(res)][1]:.3f} mm onto the root cone: blade shortened, sliding base "
                       f"moved, blade surface unchanged")
        if up and res.pinion_cutter.edge_radius < pin.cutter.edge_radius:
            source += (f"; edge radius {res.pinion_cutter.edge_radius:.3f} mm reduced to keep the raised fillet below "
                       f"the gear's tip contact (derived {pin.cutter.edge_radius:.3f} mm)")
        elif res.pinion_cutter.edge_radius < pin.cutter.edge_radius:
            source += (f"; edge radius {res.pinion_cutter.edge_radius:.3f} mm refitted to keep the generated fillet "
                       f"below the gear's top (derived {pin.cutter.edge_radius:.3f} mm)")
        new[(Member.PINION, s1)] = FlankSetup(Member.PINION, s1, res.pinion_cutter, res.pinion_settings,
                                              res.pinion_flank, source)
        results[name] = res
    return new, results
