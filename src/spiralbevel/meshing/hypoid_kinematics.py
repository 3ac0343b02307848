"""Kinematics of a hypoid pair: crossed axes at the offset E, pitch apexes off the crossing point (docs/conventions.md
"Hypoid pair frame"; docs/theory/gearing.md).

The fixed frame of the intersecting-axes pair (``BevelPairKinematics``) is kept: gear axis a2 = (sin S, 0, cos S)
through the origin, pinion axis a1 = (0, 0, 1), both pointing into the bodies. The pinion axis is moved by the offset
E along +y = a1 x a2 / |a1 x a2| (the direction of the misalignment offset), so the crossing points are (0, E, 0) on
the pinion axis and the origin on the gear axis. The member frames sit at the pitch apexes,
o1 = (0, E, 0) + t1 a1 and o2 = t2 a2 (t1 = -t_z1, t2 = -t_z2 of ISO 23509: the pitch apex "beyond the crossing
point" lies on the far side of the body). With E = t1 = t2 = 0 every quantity is that of ``BevelPairKinematics``.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from .._core.rotations import apply
from .._core.tca import assembly_axes
from ..conventions import Hand
from ..errors import DesignError, Problem
from .kinematics import BevelPairKinematics
from .misalignment import Misalignment

__all__ = ["HypoidPairKinematics", "pair_offset"]


def pair_offset(a: float, gear_hand) -> float:
    """Offset E of the pair frame (mm, along +y) for the ISO 23509 hypoid offset ``a`` and the wheel's hand.

    ISO 23509 B.3: a > 0 when the pinion offset follows the hand of spiral of the wheel. Seen on the wheel's face with
    the pinion to the right, that puts the pinion below the wheel centre for a right-hand wheel; in the pair frame
    (view along +a2, right = +z for S = 90 deg) "below" is -y: E = -a for a right-hand wheel, +a for a left-hand
    wheel (pinned by the pitch-point test in tests/meshing/test_hypoid_kinematics.py: with this sign the relative
    velocity at the pitch point runs along a tooth trace of the wheel's hand with beta_m1 - beta_m2 = zeta_mp > 0).
    """
    return -Hand(gear_hand).sign * float(a)


@dataclass(frozen=True)
class HypoidPairKinematics(BevelPairKinematics):
    """Constant-ratio kinematics of a pair with crossed axes (hypoid) or intersecting axes (E = 0).

    Parameters
    ----------
    shaft_angle : float, rad
        S, 0 < S < pi.
    z1, z2 : int
    offset : float, mm
        E, the pinion axis passes through (0, E, 0) (pair frame, see :func:`pair_offset` for the ISO sign).
    pinion_apex : float, mm
        t1, the pinion pitch apex (member-frame origin) sits at (0, E, 0) + t1 a1.
    gear_apex : float, mm
        t2, the gear pitch apex sits at t2 a2.

    Notes
    -----
    w(1) = w1 a1, w(2) = -w2 a2 (w2/w1 = z1/z2) about axes through (0, E, 0) and the origin; the relative velocity is
    v(12) = w(1) x (r - c1) - w(2) x (r - c2) = w(12) x r + b, b = -w(1) x c1 + w(2) x c2 (Litvin and Fuentes,
    Gear Geometry and Applied Theory, 2nd ed., §2.4 and ch. 20 (hypoid drives)). The axis of the instantaneous
    screw motion passes through w(12) x b / |w(12)|^2 along w(12) with the pitch w(12).b / |w(12)|^2.
    """

    offset: float = 0.0
    pinion_apex: float = 0.0
    gear_apex: float = 0.0

    def __post_init__(self):
        super().__post_init__()
        problems = []
        for name in ("offset", "pinion_apex", "gear_apex"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(v):
                problems.append(Problem(name, v, "finite", "mm"))
            else:
                object.__setattr__(self, name, float(v))
        if problems:
            raise DesignError(problems)

    @classmethod
    def from_blank(cls, blank) -> "HypoidPairKinematics":
        """The assembled pair of an ISO 23509 blank (Method 0 or Method 1): E from ``a`` and the wheel's hand,
        apexes from t_z1, t_z2 (zero for a spiral bevel blank)."""
        a = float(getattr(blank, "a", 0.0) or 0.0)
        t1 = -float(getattr(blank, "tz1", 0.0)) if a else 0.0
        t2 = -float(getattr(blank, "tz2", 0.0)) if a else 0.0
        return cls(float(blank.Sigma), int(blank.z1), int(blank.z2), offset=pair_offset(a, blank.hand2),
                   pinion_apex=t1, gear_apex=t2)

    # ----------------------------------------------------------------------------------------- geometry
    @property
    def is_hypoid(self) -> bool:
        return self.offset != 0.0

    def _intersecting_only(self, what):
        if self.offset != 0.0:
            raise DesignError.single("offset", self.offset, "0 for " + what, "mm",
                                     f"{what} exists for intersecting axes only; on a hypoid pair use "
                                     "relative_velocity / screw_axis")

    @property
    def pitch_angle_pinion(self) -> float:
        """Intersecting axes only: tan g1 = sin S / (z2/z1 + cos S) (a hypoid's pitch angles are the blank's)."""
        self._intersecting_only("the pitch angle from the ratio")
        return super().pitch_angle_pinion

    @property
    def pitch_angle_gear(self) -> float:
        self._intersecting_only("the pitch angle from the ratio")
        return super().pitch_angle_gear

    @property
    def pitch_line(self) -> np.ndarray:
        self._intersecting_only("the pitch line")
        return super().pitch_line

    def meshing_willis_form(self, r, n):
        self._intersecting_only("the Willis form")
        return super().meshing_willis_form(r, n)

    def meshing_function(self, r1, n1, phi1):
        self._intersecting_only("the meshing function in closed form")
        return super().meshing_function(r1, n1, phi1)

    @property
    def pinion_centre(self) -> np.ndarray:
        """c1 = (0, E, 0), the crossing point on the pinion axis, (3,) mm."""
        return np.array([0.0, self.offset, 0.0])

    @property
    def pinion_origin(self) -> np.ndarray:
        """o1 = c1 + t1 a1, the pinion pitch apex (member-frame origin), (3,) mm."""
        return self.pinion_centre + self.pinion_apex * self.pinion_axis

    @property
    def gear_origin(self) -> np.ndarray:
        """o2 = t2 a2, the gear pitch apex (member-frame origin), (3,) mm."""
        return self.gear_apex * self.gear_axis

    def axes(self, misalignment: Misalignment | None = None):
        """Axes and apexes ``(a1, o1, a2, o2, B2)`` of the assembly with misalignments on top (``_core.tca``).

        The misalignments act as in docs/conventions.md "Misalignments": Delta A1 along a1, Delta A2 along a2, Delta E
        added to E, the shaft-angle error turning the gear axis about +y through the crossing point.
        """
        m = misalignment if misalignment is not None else Misalignment()
        return assembly_axes(self.shaft_angle, m.pinion_axial + self.pinion_apex, m.gear_axial + self.gear_apex,
                             m.offset + self.offset, m.shaft_angle)

    # ----------------------------------------------------------------------------------------- motion
    def relative_velocity(self, r, omega1=1.0):
        """v(12) = w(1) x (r - c1) - w(2) x (r - c2) at fixed-frame points ``r (..., 3)`` mm, mm/s."""
        r = np.asarray(r, float)
        w1, w2 = self.angular_velocity_pinion(omega1), self.angular_velocity_gear(omega1)
        return np.cross(w1, r - self.pinion_centre) - np.cross(w2, r)

    def screw_axis(self, omega1=1.0):
        """Instantaneous screw axis of the relative motion: (point (3,) mm, unit direction (3,), pitch mm/rad).

        For intersecting axes the point is the apex, the direction the pitch line and the pitch 0.
        """
        w12 = self.relative_angular_velocity(omega1)
        b = self.relative_velocity(np.zeros(3), omega1)
        ww = float(w12 @ w12)
        return np.cross(w12, b) / ww, w12 / math.sqrt(ww), float(w12 @ b) / ww

    def to_fixed_pinion(self, r1, phi1):
        """Pinion member coordinates -> fixed frame, ``(..., 3)`` mm (o1 + R_z(phi1) r1)."""
        return self.pinion_origin + apply(self.pinion_to_fixed(phi1), np.asarray(r1, float))

    def to_fixed_gear(self, r2, phi2):
        """Gear member coordinates -> fixed frame, ``(..., 3)`` mm (o2 + R(a2, phi2) R_y(S) r2)."""
        return self.gear_origin + apply(self.gear_to_fixed(phi2), np.asarray(r2, float))

    def to_gear(self, r1, phi1):
        """Pinion member coordinates -> gear member coordinates at the meshing position phi1, ``(..., 3)`` mm."""
        phi2 = self.gear_angle(phi1)
        rf = self.to_fixed_pinion(r1, phi1)
        return apply(np.swapaxes(self.gear_to_fixed(phi2), -1, -2), rf - self.gear_origin)
