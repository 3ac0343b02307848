"""Face-milled flanks from the design file: per member side the cutter and machine settings (given, or solved from the
blank for the design angles) and the generated flank, then the pinion's synthesis; errors named by design-file key."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..conventions import Member, Side
from ..errors import DesignError

MEMBERS = (Member.PINION, Member.GEAR)
SIDES = (Side.CONVEX, Side.CONCAVE)


@dataclass(frozen=True)
class FlankSetup:
    """Cutter, settings and generated flank of one member side; ``source`` says where the settings came from."""

    member: Member
    side: Side
    cutter: object
    settings: object
    flank: object
    source: str
    fit: object = None


def _default_cutter(spec, blank, member, side):
    """The derived cutter of a flank (``machine.default_cutter``) with the design file's overrides."""
    from ..machine.default_cutter import default_cutter

    fm = spec.face_milling
    return default_cutter(blank, member, side, point_width=fm.point_width, edge_radius=fm.edge_radius)


def _given_cutter(cs, side):
    from ..machine.cutter import Blade, HeadCutter

    return HeadCutter(point_radius=cs.point_radius, blade_angle=math.radians(cs.blade_angle),
                      point_width=cs.point_width, edge_radius=cs.edge_radius,
                      blade=Blade.INNER if side is Side.CONVEX else Blade.OUTER,
                      profile_radius=cs.profile_radius if cs.profile_radius is not None else math.inf)


def _given_settings(ms):
    from ..machine.settings import MachineSettings

    return MachineSettings(
        radial_setting=ms.radial_setting, cradle_angle=math.radians(ms.cradle_angle),
        machine_root_angle=math.radians(ms.machine_root_angle), machine_centre_to_back=ms.machine_centre_to_back,
        sliding_base=ms.sliding_base, blank_offset=ms.blank_offset, ratio_of_roll=ms.ratio_of_roll,
        modified_roll=ms.modified_roll, blank_offset_poly=ms.blank_offset_poly)


def setup_flanks(spec, blank, with_synthesis: bool = False):
    """Cutters, settings and generated flanks of all four member sides: {(member, side): FlankSetup}.

    With a ``[synthesis]`` section the pinion flank of each listed side is then replaced by local synthesis from the
    mating gear flank (:func:`synthesize_sides`); ``with_synthesis`` also returns {side name: SynthesisResult}.
    """
    from .blank import require_no_offset
    from .default_synthesis import effective_synthesis, synthesize_sides

    require_no_offset(blank, "face-milled flanks")
    out = _basic_setups(spec, blank)
    basic = dict(out)
    synth = {}
    sy = effective_synthesis(spec, blank)
    if sy is not None:
        new, synth = synthesize_sides(spec, blank, out, sy)
        out.update(new)
    from .slot_check import fit_point_widths

    verified = dict(out)
    fit_point_widths(spec, blank, out, synth)    # derived point widths that the tooth space does not hold
    if sy is not None and getattr(sy, "_default", False) and sy.motion_curve != "cmc":
        from .refit_bearing import keep_verified_bearings

        out, synth = keep_verified_bearings(spec, blank, sy, basic, verified, out, synth)
    return (out, synth) if with_synthesis else out


def _basic_setups(spec, blank):
    from ..generation.flank import generate_flank
    from ..generation.basic_settings_solve import solve_basic_settings

    out = {}
    for m in MEMBERS:
        for s in SIDES:
            key = f"{m.value}_{s.value}"
            fs = getattr(spec.face_milling, key)
            fit = None
            try:
                cutter = _given_cutter(fs.cutter, s) if fs.cutter is not None else _default_cutter(spec, blank, m, s)
                if fs.machine is not None:
                    settings, source = _given_settings(fs.machine), "given"
                    flank = generate_flank(cutter, settings, blank, m, s)
                    flank.mean_point()  # generation is lazy: check here that the settings generate this flank at all
                else:
                    cutter, settings, flank, fit = solve_basic_settings(
                        blank, m, s, cutter, solve_blade_angle=fs.cutter is None, roll=spec.face_milling.roll)
                    source = ("basic settings solved for the design pressure and spiral angles, root on the root "
                              "cone" + ("" if fs.cutter is None else " (given cutter: spiral angle only)"))
            except DesignError as err:
                if fs.machine is not None and "equation of meshing has no solution" in str(err):
                    raise _misplaced_cutter(err, key, fs, blank, m, s, cutter, spec) from err
                raise _in_design_file(err, key, fs) from err
            out[(m, s)] = FlankSetup(m, s, cutter, settings, flank, source, fit)
    return out


#: given settings against the basic settings from the blank: an angle this far off (deg), or a length this far off
#: as a fraction of the mean cone distance, is named as the likely reason why the cutter misses the blank
_CULPRIT_ANGLE_DEG, _CULPRIT_LENGTH = 10.0, 0.25


def _misplaced_cutter(err, key, fs, blank, m, s, cutter, spec):
    """The cutter of given settings misses the blank: name the setting farthest from the blank's basic settings
    (machine root angle against the root angle, radial setting, sliding base, machine centre to back, blank offset),
    or all of them when none stands out."""
    from ..errors import GeometryError
    from ..machine.settings import MachineSettings

    ms = fs.machine
    reason = "the cutter does not reach the blank (the equation of meshing has no solution)"
    try:
        basic = MachineSettings.from_blank(blank, m, s, cutter, roll=spec.face_milling.roll)
    except DesignError:
        basic = None
    worst, score = None, 1.0
    if basic is not None:
        candidates = [("machine_root_angle", ms.machine_root_angle, math.degrees(basic.machine_root_angle), "deg",
                       _CULPRIT_ANGLE_DEG)]
        for name in ("radial_setting", "sliding_base", "machine_centre_to_back", "blank_offset"):
            candidates.append((name, getattr(ms, name), getattr(basic, name), "mm", _CULPRIT_LENGTH * blank.Rm))
        for name, given, ref, unit, scale in candidates:
            if abs(given - ref) / scale > score:
                worst, score = (name, given, ref, unit, scale), abs(given - ref) / scale
    if worst is None:
        names = "radial_setting, cradle_angle, machine_root_angle, sliding_base, machine_centre_to_back, blank_offset"
        return GeometryError.single(f"face_milling.{key}.machine ({names})", "(section)",
                                    "settings that place the cutter at the blank", "", reason)
    name, given, ref, unit, scale = worst
    return GeometryError.single(f"face_milling.{key}.machine.{name}", round(given, 6),
                                f"|value - {ref:.4f}| <= {scale:.4g}", unit,
                                f"{ref:.4f} {unit} is the basic setting from the blank; {reason}")


def _in_design_file(err, key, fs):
    """The same error with field names as design-file paths (face_milling.<member>_<side>.cutter/machine....); a
    derived cutter or setting is named as such."""
    from ..errors import Problem

    def path(field):
        head, _, rest = field.partition(".")
        if head == "settings":
            return f"face_milling.{key}.machine.{rest}" + (
                "" if fs.machine is not None else " (derived from the blank)")
        if head == "cutter":
            return f"face_milling.{key}.cutter.{rest}" + ("" if fs.cutter is not None else " (derived cutter)")
        if field in ("point_radius", "blade_angle", "point_width", "edge_radius", "profile_radius"):
            return f"face_milling.{key}.cutter.{field}" + ("" if fs.cutter is not None else " (derived cutter)")
        if field.startswith("locate"):
            return f"face_milling.{key} (cutter and machine settings)"
        return f"face_milling.{key}: {field}" if field else f"face_milling.{key}"

    return type(err)([Problem(path(p.field), p.value, p.allowed, p.unit, p.reason) for p in err.problems])
