"""Assembly misalignments of a bevel pair (seed 001 §4.1; signs in docs/conventions.md "Misalignments").

Seed 001 names four misalignments: axial errors of the pinion and of the gear, the shortest distance between the
axes when they cross instead of intersecting (offset), and the error of the shaft angle. All are zero for the
aligned pair.
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass

import numpy as np

from .._core.tca import assembly_axes
from ..errors import DesignError, Problem

__all__ = ["Misalignment"]


@dataclass(frozen=True)
class Misalignment:
    """Misalignments of the assembled pair, in the fixed pair frame of docs/conventions.md.

    Parameters
    ----------
    pinion_axial : float, mm
        Delta A1: the pinion (its apex and every point) is displaced by Delta A1 along +a1, i.e. away from the
        common apex, out of mesh when positive.
    gear_axial : float, mm
        Delta A2: the gear is displaced by Delta A2 along +a2 (away from the apex, out of mesh when positive).
    offset : float, mm
        Delta E: the pinion axis is displaced by Delta E along +y = a1 x a2 / |a1 x a2|; the axes then cross at the
        distance |Delta E|.
    shaft_angle : float, rad
        Delta gamma: the gear axis is turned about +y, so the angle between the axes becomes S + Delta gamma and
        a2 = (sin(S + dg), 0, cos(S + dg)).
    """

    pinion_axial: float = 0.0
    gear_axial: float = 0.0
    offset: float = 0.0
    shaft_angle: float = 0.0

    def __post_init__(self):
        problems = []
        limits = {"pinion_axial": (5.0, "mm"), "gear_axial": (5.0, "mm"), "offset": (5.0, "mm"),
                  "shaft_angle": (0.05, "rad")}
        for name, (lim, unit) in limits.items():
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, numbers.Real) or not np.isfinite(v) or abs(v) > lim:
                problems.append(Problem(name, v, f"|value| <= {lim}", unit,
                                        "misalignments are small assembly errors"))
            else:
                object.__setattr__(self, name, float(v))
        if problems:
            raise DesignError(problems)

    @property
    def is_aligned(self) -> bool:
        return self.pinion_axial == self.gear_axial == self.offset == self.shaft_angle == 0.0

    def axes(self, shaft_angle: float):
        """Fixed-frame axes and apexes ``(a1, o1, a2, o2, B2)`` of the misaligned assembly (see _core.tca)."""
        return assembly_axes(shaft_angle, self.pinion_axial, self.gear_axial, self.offset, self.shaft_angle)

    def pinion_to_fixed(self, phi1, r1):
        """Pinion member-frame points ``r1 (..., 3)`` to the fixed frame at rotation ``phi1`` rad."""
        from .._core.rotations import apply, rot_z

        a1, o1, *_ = self.axes(0.5 * np.pi)
        return o1 + apply(rot_z(phi1), np.asarray(r1, float))

    def gear_to_fixed(self, phi2, r2, shaft_angle: float):
        """Gear member-frame points ``r2 (..., 3)`` to the fixed frame at rotation ``phi2`` rad about a2."""
        from .._core.rotations import apply, rot_axis

        _, _, a2, o2, B2 = self.axes(shaft_angle)
        return o2 + apply(rot_axis(a2, phi2) @ B2, np.asarray(r2, float))
