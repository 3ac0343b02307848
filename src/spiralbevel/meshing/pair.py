"""A pinion and a gear flank assembled for meshing: the one place where a face-milled pair is put together.

Both flanks are phased so that their mean points meet on the pitch line at zero roll
(:func:`~spiralbevel.meshing.generated_surface.phased_for_pair`), the kinematics come from the blank's shaft angle
and tooth numbers, and the start of the contact solve is the two mean points at phi1 = 0. TCA, loaded TCA, ease-off,
the default-synthesis check and the user-facing :class:`~spiralbevel.gearset.GearSet` all start from here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .generated_surface import GeneratedSurface, phased_for_pair
from .kinematics import BevelPairKinematics

__all__ = ["MeshingPair", "meshing_pair", "pair_kinematics"]


def pair_kinematics(blank) -> BevelPairKinematics:
    """Kinematics of the pair of a blank (shaft angle ``blank.Sigma``, rad; tooth numbers ``z1``, ``z2``)."""
    return BevelPairKinematics(float(blank.Sigma), int(blank.z1), int(blank.z2))


@dataclass(frozen=True)
class MeshingPair:
    """A pinion and a gear contact surface phased for meshing, with the kinematics and the solver start.

    Attributes
    ----------
    pinion, gear : GeneratedSurface
        The flanks turned about their member axes so that the mean points meet at phi1 = phi2 = 0.
    kinematics : BevelPairKinematics
    start : (5,) float
        (pinion mean-point parameters, gear mean-point parameters, phi2 = 0): the start of the contact solve.
    """

    pinion: GeneratedSurface
    gear: GeneratedSurface
    kinematics: BevelPairKinematics
    start: np.ndarray

    def to_pair_frame(self, points, member: str = "pinion") -> np.ndarray:
        """Points of the unphased flank (member frame, (..., 3) float, mm) turned as the phased flank of ``member``
        (``"pinion"`` or ``"gear"``): the frame in which the TCA reports contact points."""
        s = self.pinion if member == "pinion" else self.gear
        return np.asarray(points, float) @ s._R.T


def meshing_pair(pinion_flank, gear_flank, blank) -> MeshingPair:
    """Assemble a pinion and a gear flank (:class:`~spiralbevel.generation.flank.ToothFlank`) of ``blank``.

    Parameters
    ----------
    pinion_flank, gear_flank : ToothFlank
        Generated flanks in their member frames.
    blank : BevelBlank
        The pair's blank (shaft angle and tooth numbers).

    Returns
    -------
    MeshingPair
    """
    c1, c2 = phased_for_pair(pinion_flank, gear_flank)
    start = np.r_[c1.reference_params, c2.reference_params, 0.0]
    return MeshingPair(c1, c2, pair_kinematics(blank), start)
