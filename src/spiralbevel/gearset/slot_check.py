"""Does each face-milling cutter fit the tooth space it cuts? The opposite blade of every flank's cutter against the
finished opposite flank.

A flank's cutter is one blade of a head cutter with point width W (:class:`~spiralbevel.machine.cutter.HeadCutter`):
the blades of the other kind sit W away in the tip plane, at point radius R_h - s W (s = +1 outer, -1 inner blade).
While the flank is generated they sweep the same tooth space near its other flank, with the same machine settings.
The two flanks of a tooth space are generated separately when their settings differ (every derived or synthesized
side here), so nothing ties that opposite blade to the opposite flank: if it reaches past it, cutting the first flank
removes material of the finished second one (the tooth comes out thinner than designed, its fillet undercut).

The check generates that opposite blade's surface (blade angle and edge radius of the opposite flank's own cutter, the
edge radius no larger than the point width holds) with the settings of the cut flank and measures, at
``SLOT_STATIONS`` face stations from toe to heel and on ``SLOT_FILLET_ROWS`` rows from its generated root (the tip
line) to its fillet/blade junction (more rows where that fillet climbs steeply; built from the tip line, not from the
pitch cone, which that surface need not reach: :mod:`~spiralbevel.gearset.slot_blade`), how far it lies inside the
material of the opposite flank, which is placed as in
the assembled tooth (:func:`~spiralbevel.gearset.facemilled.tooth_rotation`, the neighbouring tooth's flank that
bounds the same space). The measure is the distance along the opposite flank's normal, positive into its tooth: the
arc, on the circle about the member axis through the point, from the opposite flank to the point, times the azimuthal
component |n . e_phi| of that flank's unit normal there (first order in the distance; the arc alone, the measure of
the CAD root-slot width :func:`~spiralbevel.geometry.solid.root_slot_width`, is ill-conditioned on the fillet's
bottom, where the flank runs nearly along the circle). Both surfaces are compared at equal cone distance R and equal
height h, the opposite flank's azimuth and normal interpolated along its generated profile (fillet and blade rows).
Where the opposite blade runs below the opposite flank's generated root (the cut flank's settings put the cutter's
tip plane deeper than that root), the measure is taken from the opposite flank's side: in each section R = const, the
distance of that flank's root edge and fillet points from the opposite blade's profile (its fillet, continued on its
blade up to the flank's fillet junction), positive where such a point lies in the region the blade cuts, times the
share of the flank's normal in the section. Below the root, at heights no point of the flank has, the blade's points
alone say nothing: the flank's material over them (its root edge and fillet) is what the blade removes.

The generated flank itself does not depend on W (the kernel sees only the cutting blade), so a derived point width
that intrudes is refitted without changing any flank: the largest W at which the opposite blade intrudes nowhere by
more than ``SLOT_FIT_MM``, the edge radius reduced only if the narrower point cannot
hold it (then the fillet of the flank is generated again). A point width from the design file is kept and the check
names its key.

Files: :mod:`~spiralbevel.gearset.slot_blade` (the opposite blade and its fillet),
:mod:`~spiralbevel.gearset.slot_intrusion` (the intrusion field and its largest value),
:mod:`~spiralbevel.gearset.slot_refit` (the point-width refit); this one: the four flanks' checks, their messages and
the report section.
"""

from __future__ import annotations

from ..conventions import Member, Side
from ..errors import DesignError, GeometryError
from .slot_blade import SLOT_FILLET_ROWS, SLOT_STATIONS, _other, opposite_blade, opposite_blade_grid
from .slot_intrusion import SLOT_FIT_MM, SLOT_TOL_MM, SlotFit, intrusion_field, slot_fit
from .slot_refit import _largest_fitting_width, fit_point_widths

#: depth (mm) of the cut flank's root below the root cone from which a cutter that fits at no point width is said to
#: fail for that reason (the root-cone acceptance of the design is 0.01 mm)
_ROOT_TOL_MM = 0.01

__all__ = ["SlotFit", "opposite_blade", "opposite_blade_grid", "intrusion_field", "slot_fit", "slot_checks",
           "slot_messages", "slot_report", "fit_point_widths", "SLOT_STATIONS", "SLOT_FILLET_ROWS", "SLOT_TOL_MM",
           "SLOT_FIT_MM"]


def slot_checks(blank, setups) -> dict:
    """{(member, side): SlotFit, or the GeometryError that kept it from being computed} over the four flanks."""
    from .facemilled import MEMBERS, SIDES

    out: dict[tuple[Member, Side], SlotFit | Exception] = {}
    for m in MEMBERS:
        for s in SIDES:
            if (m, s) not in setups or (m, _other(s)) not in setups:
                continue
            try:
                out[(m, s)] = slot_fit(blank, setups, m, s)
            except (GeometryError, DesignError) as err:
                out[(m, s)] = err
    return out


def cutter_key(spec, member, side, name: str) -> str:
    """Design-file key of cutter quantity ``name`` (``point_width``, ``edge_radius``) of flank (member, side): the
    flank's own ``face_milling.<member>_<side>.cutter.<name>`` where the design file gives that cutter, else the
    shared ``face_milling.<name>``."""
    key = f"face_milling.{member.value}_{side.value}"
    if getattr(spec.face_milling, f"{member.value}_{side.value}").cutter is not None:
        return f"{key}.cutter.{name}"
    return f"face_milling.{name}"


def slot_messages(spec, blank, setups, checks) -> dict:
    """{(member, side): [warning]} for the flanks whose cutter does not fit, each naming the design-file key and the
    largest point width that fits."""
    out = {}
    for (m, s), res in checks.items():
        key = cutter_key(spec, m, s, "point_width")
        if isinstance(res, Exception):
            out[(m, s)] = [_not_checked(blank, m, s, res)]
            continue
        if res.fits:
            continue
        where = f"{res.face_position:.2f} of the face width from the toe, {res.height:.3f} mm above the root cone"
        try:
            w = _largest_fitting_width(blank, setups, m, s, res.point_width)
        except (GeometryError, DesignError):
            w = None
        synthesized = [x.value for x in (s, _other(s)) if "synthesis" in setups[(m, x)].source]
        keys = ("synthesis.path_direction / synthesis.semi_major_axis (the [synthesis] section) of the synthesized "
                f"{' and '.join(synthesized)} side" if synthesized else
                f"face_milling.{m.value}_{s.value}.machine or face_milling.{m.value}_{_other(s).value}.machine")
        if w is not None:
            todo = f"reduce {key} to {w:.3f} mm or less"
        elif res.tip_height < -_ROOT_TOL_MM:
            todo = (f"no point width fits: the {s.value} side's settings put the cutter's tip plane, its root and "
                    f"the opposite blade's tip {-res.tip_height:.3f} mm below the root cone, where the opposite blade "
                    f"undercuts the {_other(s).value} flank's fillet; change {keys}")
        elif isinstance(twin := checks.get((m, _other(s))), SlotFit) and twin.tip_height < -_ROOT_TOL_MM:
            todo = (f"no point width fits: the {_other(s).value} side's settings put its root "
                    f"{-twin.tip_height:.3f} mm below the root cone, and its flank with it into this space; "
                    f"change {keys}")
        else:
            todo = (f"no point width fits: the two flanks' settings leave no tooth space there (the flanks cross); "
                    f"change {keys}, or the tooth thickness")
        out[(m, s)] = [f"the cutter does not fit the tooth space: its opposite blade (point width "
                       f"{res.point_width:.3f} mm) cuts {res.intrusion:.3f} mm into the {_other(s).value} flank "
                       f"({where}); {todo}"]
    return out


#: spiral angle (deg) at the toe or heel below which a failed slot check names the fold of the generated surface
#: there as the likely cause (the cutter's tip line turns back near a zero spiral angle)
_FOLD_SPIRAL_DEG = 3.0


def _not_checked(blank, member, side, err) -> str:
    """The warning for a flank whose slot check could not be computed: what failed, in the user's terms, and what to
    change (the internal locator messages name a grid and a blade parameter, which the user cannot act on)."""
    import math

    prob = getattr(err, "problems", [None])[0]
    field, value = (getattr(prob, "field", ""), getattr(prob, "value", "")) if prob is not None else ("", "")
    other = _other(side).value
    if field == "grid(fillet)":
        what = (f"the fillet that the opposite blade of the {side.value} side's cutter generates could not be followed "
                f"from its junction to the root at {str(value).split(' points')[0]} face stations")
    elif field.startswith("slot check"):
        what = f"the opposite blade's cut could not be followed ({err.problems[0].reason or value})"
    else:
        what = f"the opposite blade's cut could not be computed ({str(err).splitlines()[0]})"
    i = Member(member).index
    ends = {"toe": float(getattr(blank, f"beta_i{i}")), "heel": float(getattr(blank, f"beta_e{i}"))}
    near = [f"{k} {math.degrees(v):+.1f} deg" for k, v in ends.items() if abs(math.degrees(v)) < _FOLD_SPIRAL_DEG]
    if near:
        todo = (f"the spiral angle is near zero at the {' and '.join(near)}, where the generated surface folds: "
                "raise gear_set.cutter_radius or gear_set.mean_spiral_angle, or lower gear_set.face_width")
    else:
        todo = (f"whether the cutter cuts into the finished {other} flank is unknown: check the tooth space of the "
                "STEP/STL solid, or change the cutter (face_milling.point_width, face_milling.edge_radius)")
    return f"cutter fit in the slot not checked: {what}; {todo}"


def slot_report(spec, blank, setups, flanks) -> None:
    """Add each flank's ``slot`` section and its slot warnings to ``flanks`` (the report's ``flanks`` section, from
    ``facemilled.flank_report``), and issue them as ``DesignWarning``."""
    import warnings

    from ..errors import DesignWarning

    checks = slot_checks(blank, setups)
    msgs = slot_messages(spec, blank, setups, checks)
    for (m, s), res in checks.items():
        d = flanks.setdefault(m.value, {}).setdefault(s.value, {})
        if not isinstance(res, Exception):
            d["slot"] = res.to_dict()
        for text in msgs.get((m, s), ()):
            d.setdefault("checks", []).append(text)
            warnings.warn(f"{m.value} {s.value}: {text}", DesignWarning, stacklevel=2)
