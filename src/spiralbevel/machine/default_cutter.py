"""Default head cutters of a face-milled member, derived from the ISO 23509 blank.

The point width is the width of the tooth space at the root in the mean normal section; the edge radius is the
largest that fits both the point width and the tip clearance of the mating member. The blank's mean normal tooth
thickness enters here and nowhere else (:func:`slot_width_at_root`).
"""

from __future__ import annotations

import math

from spiralbevel.conventions import Member, Side
from spiralbevel.errors import GeometryError
from spiralbevel.machine.cutter import Blade, HeadCutter

__all__ = ["EDGE_RADIUS_FILL", "design_pressure_angle", "slot_width_at_root", "largest_edge_radius",
           "default_cutter"]

#: fraction of the geometric limit taken by a derived edge radius (leaves a small flat at the blade point and a
#: small gap between the fillet and the mating tooth's tip)
EDGE_RADIUS_FILL = 0.95


def is_drive(member, side) -> bool:
    """True for the drive side (pinion concave / gear convex, docs/conventions.md)."""
    member, side = Member(member), Side(side)
    return (member is Member.PINION) == (side is Side.CONCAVE)


def design_pressure_angle(blank, member, side) -> float:
    """Design normal pressure angle (rad) of a flank at the mean point: ISO 23509 alpha_nD on the drive side, alpha_nC
    on
    the coast side (both include f_alpha_lim * alpha_lim)."""
    return float(blank.alpha_nD if is_drive(member, side) else blank.alpha_nC)


def slot_width_at_root(blank, member) -> float:
    """Width of the tooth space at the root in the mean normal section, mm.

    W = (pi m_mn - s_mn) - h_fm (tan alpha_nD + tan alpha_nC): the space width on the pitch line less the run-out of
    both flanks over the mean dedendum at their design pressure angles. The only place where a derived cutter depends on
    the blank's mean normal tooth thickness ``smn1/smn2`` (ISO 23509).
    """
    i = Member(member).index
    space = math.pi * float(blank.mmn) - float(getattr(blank, f"smn{i}"))
    run_out = float(getattr(blank, f"hfm{i}")) * (math.tan(blank.alpha_nD) + math.tan(blank.alpha_nC))
    return space - run_out


def largest_edge_radius(point_width: float, blade_angles, clearance: float) -> float:
    """Largest edge radius (mm) that fits, times :data:`EDGE_RADIUS_FILL`.

    Two limits, for every blade angle alpha of the slot: the fillet takes at most half the point width,
    rho (1 - sin alpha) / cos alpha <= W/2, and its junction with the blade stays within the tip clearance c of the
    mating member, rho (1 - sin alpha) <= c (the mating tooth tip must not reach the fillet).
    """
    lim = math.inf
    for a in blade_angles:
        lim = min(lim, 0.5 * point_width * math.cos(a) / (1.0 - math.sin(a)), clearance / (1.0 - math.sin(a)))
    return EDGE_RADIUS_FILL * lim


def default_cutter(blank, member, side, blade_angle: float | None = None, point_width: float | None = None,
                   edge_radius: float | None = None) -> HeadCutter:
    """Head cutter (one blade) for a flank of a member, derived from the blank.

    Parameters
    ----------
    blank : BevelBlank
    member : Member
    side : Side
    blade_angle : float, rad, optional
        Default: the design pressure angle of the flank (the basic-settings solve corrects it).
    point_width : float, mm, optional
        Default: :func:`slot_width_at_root`.
    edge_radius : float, mm, optional
        Default: :func:`largest_edge_radius` for the design pressure angles of both sides.

    Returns
    -------
    HeadCutter
        Point radius r_c0 + s W/2 (nominal cutter radius r_c0 of the blank).
    """
    member, side = Member(member), Side(side)
    alpha = design_pressure_angle(blank, member, side) if blade_angle is None else float(blade_angle)
    W = slot_width_at_root(blank, member) if point_width is None else float(point_width)
    if not W > 0.2 * blank.mmn:
        raise GeometryError.single(
            "face_milling.point_width", "derived", f"> {0.2 * blank.mmn:.3f}", "mm",
            f"the {member.value} tooth space is too narrow at the root for a derived cutter (slot width {W:.3f} mm): "
            "give face_milling.point_width explicitly, or reduce gear_set.depth (dedendum) or the pressure angle")
    if edge_radius is None:
        edge_radius = largest_edge_radius(W, (blank.alpha_nD, blank.alpha_nC, alpha), float(blank.c))
    blade = Blade.for_side(side)
    return HeadCutter(point_radius=float(blank.rc0) + blade.sign * 0.5 * W, blade_angle=alpha, point_width=W,
                      edge_radius=float(edge_radius), blade=blade)
