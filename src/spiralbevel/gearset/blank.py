"""Design file → ISO 23509 blank. Problems are reported with design-file field paths."""

from __future__ import annotations

import math
from typing import Any

from ..conventions import Hand
from ..errors import DesignError, Problem
from ..io.design_schema import DesignFile

# BlankInput field -> design-file path
FIELD_PATHS = {
    "z1": "gear_set.pinion_teeth",
    "z2": "gear_set.gear_teeth",
    "b": "gear_set.face_width",
    "beta_m": "gear_set.mean_spiral_angle",
    "rc0": "gear_set.cutter_radius",
    "hand1": "gear_set.pinion_hand",
    "shaft_angle": "gear_set.shaft_angle",
    "de2": "gear_set.outer_pitch_diameter",
    "met": "gear_set.module",
    "alpha_dD": "gear_set.normal_pressure_angle",
    "alpha_dC": "gear_set.coast_pressure_angle",
    "c_ham": "gear_set.depth.mean_addendum_factor",
    "k_d": "gear_set.depth.depth_factor",
    "k_c": "gear_set.depth.clearance_factor",
    "k_t": "gear_set.depth.thickness_factor",
    "jen": "gear_set.depth.backlash",
    "taper": "gear_set.depth.taper",
    "theta_f1": "gear_set.depth.dedendum_angles[0]",
    "theta_f2": "gear_set.depth.dedendum_angles[1]",
    "theta_a2": "gear_set.depth.gear_addendum_dedendum_angles[0]",
    "a": "gear_set.hypoid_offset",
    "f_alim": "gear_set.limit_pressure_angle_factor",
    "gear_generated": "gear_set.gear_generation",
}


def blank_input_from_design(spec: DesignFile):
    """Build the :class:`~spiralbevel.design.blank_input.BlankInput` of a design file."""
    from ..design.blank_input import BlankInput

    g, d = spec.gear_set, spec.gear_set.depth
    r = math.radians
    kw: dict[str, Any] = dict(
        z1=g.pinion_teeth, z2=g.gear_teeth, b=g.face_width, beta_m=r(g.mean_spiral_angle), rc0=g.cutter_radius,
        hand1=Hand(g.pinion_hand), shaft_angle=r(g.shaft_angle), de2=g.outer_pitch_diameter, met=g.module,
        alpha_dD=r(g.normal_pressure_angle),
        alpha_dC=r(g.coast_pressure_angle if g.coast_pressure_angle is not None else g.normal_pressure_angle),
        c_ham=d.mean_addendum_factor, k_d=d.depth_factor, k_c=d.clearance_factor, k_t=d.thickness_factor,
        jen=d.backlash if d.backlash > 0 else None, taper=d.taper, a=g.hypoid_offset,
        f_alim=g.limit_pressure_angle_factor, gear_generated=g.gear_generation == "generated",
    )
    _check_method(g.blank_method, g.hypoid_offset)
    if g.gear_generation == "formate" and g.hypoid_offset == 0.0:
        raise DesignError.single("gear_set.gear_generation", g.gear_generation, "'generated' with "
                                 "gear_set.hypoid_offset = 0", "-", "a Formate gear is offered on the hypoid chain "
                                 "(ISO 23509 Method 1, hypoid_offset != 0) only")
    if g.gear_generation == "formate" and spec.flank.kind != "face-milled":
        raise DesignError.single("gear_set.gear_generation", g.gear_generation, "'generated' with flank.kind = "
                                 f"{spec.flank.kind!r}", "-", "a Formate gear is face milled: set flank.kind = "
                                 "'face-milled'")
    if d.taper == "given":
        if d.dedendum_angles is not None:
            kw.update(theta_f1=r(d.dedendum_angles[0]), theta_f2=r(d.dedendum_angles[1]))
        else:
            ga = d.gear_addendum_dedendum_angles
            assert ga is not None  # the schema requires one of the two pairs for taper "given"
            kw.update(theta_a2=r(ga[0]), theta_f2=r(ga[1]))
    try:
        return BlankInput(**kw)
    except DesignError as err:
        raise _renamed(err) from err


def blank_from_design(spec: DesignFile):
    """Compute the ISO 23509 blank (:class:`~spiralbevel.design.blank_result.BevelBlank`) of a design file."""
    from ..design.blank import compute_blank

    inp = blank_input_from_design(spec)
    try:
        return compute_blank(inp)
    except DesignError as err:
        raise _renamed(err) from err


def _check_method(method, a: float) -> None:
    """The ISO 23509 method a design file asks for must fit its offset (Method 0: a = 0; Method 1: a != 0)."""
    if method is None or (method == 0 and a == 0.0) or (method == 1 and a != 0.0):
        return
    if method in (2, 3):
        allowed, reason = "0 or 1", "ISO 23509 Methods 2 (Oerlikon) and 3 (Klingelnberg) are not implemented"
    elif method == 0:
        allowed, reason = "1 for a hypoid offset", f"Method 0 has no offset (gear_set.hypoid_offset = {a:g} mm)"
    else:
        allowed, reason = "0 without offset", "Method 1 needs a hypoid offset (gear_set.hypoid_offset = 0)"
    raise DesignError.single("gear_set.blank_method", method, allowed, "-", reason)


#: why a log-spiral design takes no hypoid offset, and what to change (``require_no_offset``)
LOGSPIRAL_NO_OFFSET = ("a log-spiral pair has intersecting axes; set gear_set.hypoid_offset = 0, or flank.kind = "
                       "'face-milled' for a hypoid pair (developed by 'spiralbevel run')")


def require_no_offset(blank, command: str, hint: str | None = None) -> None:
    """Stop a command that builds flanks when the blank is a hypoid (ISO 23509 Method 1 dimension sheet only).

    Parameters
    ----------
    blank : BevelBlank
        Computed blank.
    command : str
        The command's name for the message (e.g. ``"spiralbevel run"``).
    hint : str, optional
        What to change instead (default: the commands that do develop a hypoid pair); :data:`LOGSPIRAL_NO_OFFSET`
        for a log-spiral design.

    Raises
    ------
    DesignError
        Naming ``gear_set.hypoid_offset`` when a != 0: the command does not take the offset yet.
    """
    if blank.a != 0.0:
        # the allowed value is the bare number, so that the unit follows it ("allowed 0 mm (...)")
        raise DesignError.single(
            "gear_set.hypoid_offset", blank.a, "0", "mm", f"{command} builds spiral bevel flanks only; " + (
                hint or "the hypoid dimension sheet (ISO 23509 Method 1) is computed: see 'spiralbevel blank'; "
                "'spiralbevel run' and 'spiralbevel machine' develop the hypoid pair, this command does not take the "
                "offset yet"))


def _renamed(err: DesignError) -> DesignError:
    problems = [Problem(_path(p.field), p.value, p.allowed, p.unit,
                        "" if p.reason.startswith("given in radians") else p.reason) for p in err.problems]
    return type(err)(problems)


def _path(field: str) -> str:
    """Design-file path of a blank input, or the ISO symbol of a computed quantity with its meaning."""
    if field in FIELD_PATHS:
        return FIELD_PATHS[field]
    try:
        from ..design.blank_meta import QUANTITIES
    except ImportError:  # pragma: no cover
        return field
    base = field.rstrip("12")
    for sym, desc, *_ in QUANTITIES:
        if sym == base:
            return f"{field} (computed {desc}, from gear_set)"
    return field


def blank_section(blank) -> dict:
    """The ``blank`` section of report.json: the ISO 23509 dimension sheet keyed by ISO symbol with the unit as a
    suffix (``delta1_deg``, ``Re1_mm``; dimensionless symbols bare), the descriptions under the same names, the
    method and the warnings."""
    from ..io.dimension_sheet import dimension_sheet_json
    from .units import suffixed

    sheet = dimension_sheet_json(blank)
    units = sheet["units"]
    out = {"method": sheet["method"]}
    for group in ("pair", "pinion", "gear"):
        out[group] = suffixed(sheet[group], units)
    names = {k: ("-" if u == "rad" else u) for k, u in units.items()}   # descriptions: the names only
    out["descriptions"] = suffixed(sheet["descriptions"], names)
    out["warnings"] = sheet["warnings"]
    return out
