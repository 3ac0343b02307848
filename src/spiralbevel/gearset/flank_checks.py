"""Checks of a developed face-milled flank: achieved mean-point pressure and spiral angles and root position against
the design, each warning naming the design-file key to change."""

from __future__ import annotations

import math

from ..conventions import Member, Side

#: tolerances of the developed-flank checks: the acceptance of the basic settings (0.05 deg on the mean-point
#: angles, 0.01 mm of the root on the root cone)
CHECK_ANGLE_DEG = 0.05
CHECK_ROOT_MM = 0.01


def flank_checks(fit, member, side) -> list[str]:
    """Warnings on one developed flank from its design-vs-achieved values (``FlankFit``), each naming the key."""
    key = f"face_milling.{Member(member).value}_{Side(side).value}"
    out = []
    da = math.degrees(fit.pressure_angle - fit.pressure_angle_design)
    if abs(da) > CHECK_ANGLE_DEG:
        out.append(f"mean-point pressure angle {math.degrees(fit.pressure_angle):.3f} deg misses the design "
                   f"{math.degrees(fit.pressure_angle_design):.3f} deg by {da:+.3f} deg: change "
                   f"{key}.cutter.blade_angle (or leave {key} out to have it solved)")
    db = math.degrees(fit.spiral_angle - fit.spiral_angle_design)
    if abs(db) > CHECK_ANGLE_DEG:
        out.append(f"mean-point spiral angle {math.degrees(fit.spiral_angle):.3f} deg misses the design "
                   f"{math.degrees(fit.spiral_angle_design):.3f} deg by {db:+.3f} deg: change {key}.machine "
                   f"(or leave {key} out to have it solved)")
    for where, dev in zip(("toe", "mean", "heel"), fit.root_deviation):
        if dev is not None and dev < -CHECK_ROOT_MM:
            out.append(f"root {-dev:.3f} mm below the blank's root cone at the {where}: the cutter cuts below the "
                       f"root cone; change {key}.machine.machine_root_angle / sliding_base (or leave {key} out)")
    return out
