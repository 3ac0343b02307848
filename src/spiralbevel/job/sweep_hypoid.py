"""The hypoid pair of a misalignment sweep (``spiralbevel sweep`` on a design with ``gear_set.hypoid_offset`` != 0).

The pair is the one ``spiralbevel run`` analyses: the four flanks of the hypoid branch (basic settings at each
member's mean cone distance, the pinion of the swept side by hypoid local synthesis), phased at the pitch point of
the synthesis, meshing through the offset kinematics
(:class:`~spiralbevel.meshing.hypoid_kinematics.HypoidPairKinematics`). The sweep's misalignments act on top of the
offset as in docs/conventions.md "Misalignments" (Delta E adds to the design offset E)."""

from __future__ import annotations

from ..conventions import Member
from ..errors import DesignError

__all__ = ["hypoid_sweep_pair"]


def hypoid_sweep_pair(spec, blank, side: str):
    """(pinion surface, gear surface, kinematics, gear (R, h) of (axial, radius), extra keywords of ``solve_tca``)
    of one side of a hypoid design, as :func:`spiralbevel.job.sweep._pair` gives them for a spiral bevel pair.

    Parameters
    ----------
    spec : DesignFile
        A face-milled hypoid design.
    blank : BevelBlank
        Its ISO 23509 Method 1 blank.
    side : {"drive", "coast"}

    Raises
    ------
    DesignError
        Naming ``synthesis.sides`` when the side's pinion flank is not synthesized: a hypoid pair meshes through the
        pitch point of its synthesis.
    """
    from ..gearset.facemilled import PAIR_SIDES
    from ..gearset.hypoid import hypoid_pair, setup_hypoid_flanks

    setups, synth = setup_hypoid_flanks(spec, blank, with_synthesis=True)
    if side not in synth:
        raise DesignError.single("synthesis.sides", ", ".join(synth) or "none", f"including '{side}'", "-",
                                 f"the {side} side's pinion flank of a hypoid pair is not synthesized, and a hypoid "
                                 "pair meshes through the pitch point of its synthesis")
    pair = hypoid_pair(synth[side])
    gear = setups[(Member.GEAR, PAIR_SIDES[side][1])].flank
    return pair.pinion, pair.gear, pair.kinematics, gear.outline.Rh, {"start": pair.start}
