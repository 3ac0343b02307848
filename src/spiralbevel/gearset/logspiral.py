"""Log-spiral designs in the main job: pair from the blank, flank grids, report sections and output files."""

from __future__ import annotations

import math

import numpy as np

from ..conventions import Hand, Member, Side
from ..design.logspiral_pair import BlankBoundaries  # noqa: F401  (re-exported for callers of this module)

MEMBERS = (Member.PINION, Member.GEAR)
SIDES = (Side.CONVEX, Side.CONCAVE)


def boundaries_from_blank(blank):
    """Per-member :class:`BlankBoundaries` from an ISO 23509 blank (``design.logspiral_blank``)."""
    from ..design.logspiral_blank import logspiral_boundaries

    return logspiral_boundaries(blank)


def design_pair(spec, blank):
    """The :class:`~spiralbevel.design.logspiral_pair.LogSpiralPair` of a design file and its blank."""
    from ..errors import DesignError
    from .problems import restated

    from ..design.logspiral_blank import logspiral_pair_from_blank

    g = spec.gear_set
    if g.depth.taper == "uniform":
        # one problem naming the key, not one per cone of each member (root and face angle equal to the pitch angle)
        raise DesignError.single(
            "gear_set.depth.taper", "uniform", "'standard', 'duplex', 'trl' or 'given' with flank.kind = 'log-spiral'",
            "-", "a uniform (parallel) depth has root and face angles equal to the pitch angle, but the log-spiral "
            "tooth needs a tapered depth (its flank is similar to itself about the pitch apex, so its depth grows with "
            "the cone distance); use gear_set.depth.taper = 'standard' or 'duplex', or flank.kind = 'face-milled'")
    try:
        return logspiral_pair_from_blank(
            blank, g.pinion_teeth, g.gear_teeth, math.radians(g.shaft_angle), math.radians(g.normal_pressure_angle),
            math.radians(g.mean_spiral_angle), Hand(g.pinion_hand))
    except DesignError as err:
        raise restated(err, LOGSPIRAL_PATHS, default="log-spiral pair") from err


#: library parameter -> design-file field (root and face cones come from the ISO blank's depths and taper)
LOGSPIRAL_PATHS = {
    "z1": "gear_set.pinion_teeth", "z2": "gear_set.gear_teeth", "shaft_angle": "gear_set.shaft_angle",
    "normal_pressure_angle": "gear_set.normal_pressure_angle", "spiral_angle": "gear_set.mean_spiral_angle",
    "pinion_hand": "gear_set.pinion_hand", "thickness": "gear_set.depth.thickness_factor (pinion thickness)",
    "boundaries[pinion].": "gear_set.depth -> pinion blank", "boundaries[gear].": "gear_set.depth -> gear blank",
    # the limits of design.logspiral_blank already name design-file keys
    **{k: k for k in ("gear_set.normal_pressure_angle", "gear_set.mean_spiral_angle",
                      "gear_set.depth.thickness_factor")},
}


def flank_grids(pair, n_face: int, n_profile: int):
    """Closed-form geometry on each flank grid, member frames: {(member, side): FlankGeometry}."""
    return {(m, s): pair.flank(m, s).grid(n_face, n_profile) for m in MEMBERS for s in SIDES}


def _deg(x):
    return float(np.degrees(x))


def flank_report(pair, grids):
    """Report section ``logspiral``: pair recipe and, per member and side, the flank data (degrees, mm, 1/mm)."""
    out = {
        "transverse_pressure_angle_deg": _deg(pair.transverse_pressure_angle),
        "plane_spiral_angle_deg": _deg(pair.plane_spiral_angle),
        "members": {},
    }
    for m in MEMBERS:
        md = pair.member(m)
        entry = {
            "hand": md.hand.value,
            "teeth": md.teeth,
            "pitch_angle_deg": _deg(md.pitch_angle),
            "base_cone_angle_deg": _deg(md.base_cone_angle),
            "spiral_parameter_deg": _deg(md.spiral_parameter),
            "psi_pitch_deg": _deg(md.psi_pitch),
            "mean_cone_distance_mm": md.mean_cone_distance,
            "mean_normal_thickness_mm": md.mean_normal_thickness,
            "flanks": {},
        }
        for s in SIDES:
            f = pair.flank(m, s)
            g = grids[(m, s)]
            mean = pair.mean_point(m, s)
            d = f.domain
            entry["flanks"][s.value] = {
                "rho0_mm": f.surface.rho0,
                "rotation_deg": _deg(f.rotation),
                "domain": {"phi_min_deg": _deg(d.phi_min), "phi_max_deg": _deg(d.phi_max),
                           "psi_min_deg": _deg(d.psi_min), "psi_max_deg": _deg(d.psi_max)},
                "mean_point": {
                    "point_mm": mean.point, "normal": mean.normal,
                    "k1_per_mm": float(mean.k1), "k2_per_mm": float(mean.k2),
                },
                "k1_range_per_mm": [float(g.k1.min()), float(g.k1.max())],
                "k2_range_per_mm": [float(g.k2.min()), float(g.k2.max())],
            }
        out["members"][m.value] = entry
    return out


def tooth_grids(pair, grids, member):
    """(convex, concave) point/normal tuples of one tooth of ``member`` in its member frame."""
    return tuple((grids[(member, s)].point, grids[(member, s)].normal) for s in SIDES)
