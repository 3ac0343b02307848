"""Checks of a developed face-milled flank: achieved mean-point pressure and spiral angles and root position against
the design, each warning naming the design-file key to change.

A flank whose settings the local synthesis produced (its ``source`` names the synthesis) has no
``face_milling.<member>_<side>.machine`` to change: its warnings name the ``[synthesis]`` keys, and, when the design
file has no ``[synthesis]`` section, say that the default synthesis produced it (:func:`synthesis_advice`). Of the
sets of solved settings only ``free = "fixed-blade"`` solves the machine centre to back (X_D1), which moves the
cutter's tip plane, and with it the generated root, off the blank's root cone; ``"offset"`` and ``"modified-roll"``
keep X_D1 = 0, where the tip plane generates the root cone (``meshing.synthesis.machine_fit``).
"""

from __future__ import annotations

import math
import re

from ..conventions import Member, Side

#: tolerances of the developed-flank checks: the acceptance of the basic settings (0.05 deg on the mean-point
#: angles, 0.01 mm of the root on the root cone)
CHECK_ANGLE_DEG = 0.05
CHECK_ROOT_MM = 0.01


def synthesized(source: str) -> bool:
    """True when a flank's settings come from the local synthesis (``FlankSetup.source``)."""
    return "synthesis" in source


def synthesis_advice(source: str, spec=None, root: bool = False) -> str:
    """What to change for a synthesized flank: the ``[synthesis]`` keys, or, without that section in ``spec``, that
    the default synthesis produced it and which keys to give. With ``root``, the advice for a root off the root cone:
    the set of solved settings (module docstring) first."""
    found = re.search(r"free = ([\w-]+)", source)
    free = found.group(1) if found else None
    default = spec is not None and spec.synthesis is None
    head = (f"the default synthesis (no [synthesis] section) produced this flank with free = {free or 'offset'}"
            if default else "the local synthesis of the [synthesis] section produced this flank"
            + (f" with free = {free}" if free else ""))
    if root and free == "fixed-blade":
        why = ("; free = fixed-blade solves the machine centre to back, which moves the cutter's tip plane off the "
               "root cone (\"offset\" and \"modified-roll\" keep it on the cone)")
        if default:
            rc = f" (now {spec.gear_set.cutter_radius:g} mm)"
            todo = ("give a [synthesis] section with synthesis.free = \"offset\" or \"modified-roll\" and a "
                    "synthesis.path_direction (the default's is synthesis.<side>.eta_deg in the report; without a path "
                    "direction the search may take the fixed blade again; the keys left out keep the defaults), or "
                    f"change gear_set.cutter_radius{rc}, with which the default search may take another set")
        else:
            todo = "set synthesis.free = \"offset\" or \"modified-roll\""
        return f"{head}{why}; {todo}"
    if default:
        return (f"{head}; give a [synthesis] section (synthesis.path_direction, synthesis.semi_major_axis, "
                "synthesis.free; the keys it leaves out keep the defaults) or change gear_set.cutter_radius")
    return f"{head}; change synthesis.path_direction, synthesis.semi_major_axis or synthesis.free"


def flank_checks(fit, member, side, source: str = "", spec=None) -> list[str]:
    """Warnings on one developed flank from its design-vs-achieved values (``FlankFit``), each naming the key: for a
    flank with given or solved basic settings ``face_milling.<member>_<side>``, for a synthesized one (``source``)
    the ``[synthesis]`` keys (:func:`synthesis_advice`; ``spec``, the design, tells whether the section was given).
    The root below the root cone is one line with its depths at toe, mean and heel."""
    key = f"face_milling.{Member(member).value}_{Side(side).value}"
    syn = synthesized(source)
    out = []
    da = math.degrees(fit.pressure_angle - fit.pressure_angle_design)
    if abs(da) > CHECK_ANGLE_DEG:
        todo = (synthesis_advice(source, spec) if syn
                else f"change {key}.cutter.blade_angle (or leave {key} out to have it solved)")
        out.append(f"mean-point pressure angle {math.degrees(fit.pressure_angle):.3f} deg misses the design "
                   f"{math.degrees(fit.pressure_angle_design):.3f} deg by {da:+.3f} deg: {todo}")
    db = math.degrees(fit.spiral_angle - fit.spiral_angle_design)
    if abs(db) > CHECK_ANGLE_DEG:
        todo = (synthesis_advice(source, spec) if syn
                else f"change {key}.machine (or leave {key} out to have it solved)")
        out.append(f"mean-point spiral angle {math.degrees(fit.spiral_angle):.3f} deg misses the design "
                   f"{math.degrees(fit.spiral_angle_design):.3f} deg by {db:+.3f} deg: {todo}")
    dev = [(where, d) for where, d in zip(("toe", "mean", "heel"), fit.root_deviation) if d is not None]
    if any(d < -CHECK_ROOT_MM for _, d in dev):
        depths = " / ".join(f"{0.0 - d:.3f}" for _, d in dev)
        places = " / ".join(w for w, _ in dev)
        todo = (synthesis_advice(source, spec, root=True) if syn
                else f"change {key}.machine.machine_root_angle / sliding_base (or leave {key} out)")
        out.append(f"root below the blank's root cone by {depths} mm at the {places} (negative: above): the cutter "
                   f"cuts below the root cone; {todo}")
    return out
