"""Enumerations, frames and tolerances shared by every layer.

The single written definition of frames, hands, flank names and signs is ``docs/conventions.md``; this module holds
the names used in code. Each rule is pinned by a test in ``tests/test_conventions.py`` or beside the code it governs.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

__all__ = ["Member", "Hand", "Side", "Tolerances", "TOL"]


class Member(str, Enum):
    """Member of a gear set: ``PINION`` (subscript 1) or ``GEAR`` (wheel, subscript 2)."""

    PINION = "pinion"
    GEAR = "gear"

    @property
    def index(self) -> int:  # type: ignore[override]  # deliberately shadows str.index: 1 or 2
        return 1 if self is Member.PINION else 2


class Hand(str, Enum):
    """Hand of spiral (AGMA/ISO): seen from the apex looking at the face, the outer half of a right-hand tooth turns
    clockwise from the axial plane through the mean point.

    In a member frame (axis +z, apex at the origin, body toward +z) a right-hand log-spiral flank has spiral
    parameter beta > 0.
    """

    RIGHT = "RH"
    LEFT = "LH"

    @property
    def sign(self) -> int:
        """+1 for right hand, -1 for left hand."""
        return 1 if self is Hand.RIGHT else -1

    @property
    def opposite(self) -> "Hand":
        return Hand.LEFT if self is Hand.RIGHT else Hand.RIGHT


class Side(str, Enum):
    """Flank of a tooth named by its lengthwise shape: ``CONVEX`` or ``CONCAVE``.

    A spiral bevel pair meshes pinion concave with gear convex (the drive side when the pinion drives, as in seed 001)
    and pinion convex with gear concave (the coast side).
    """

    CONVEX = "convex"
    CONCAVE = "concave"

    @property
    def mate(self) -> "Side":
        """The side of the mating member that meshes with this one."""
        return Side.CONCAVE if self is Side.CONVEX else Side.CONVEX


@dataclass(frozen=True)
class Tolerances:
    """Numerical tolerances used throughout (one shared object, like trimesh's ``tol``).

    Attributes
    ----------
    newton_abs : float, mm
        Absolute residual accepted by batched Newton solves of lengths.
    newton_rel : float
        Relative residual accepted by dimensionless equations (meshing equation n.v / |v|).
    max_iter : int
        Iteration cap of Newton solvers.
    """

    newton_abs: float = 1e-11
    newton_rel: float = 1e-13
    max_iter: int = 50


TOL = Tolerances()
