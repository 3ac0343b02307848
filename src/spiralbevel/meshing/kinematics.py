"""Kinematics of a bevel pair with intersecting axes (seed 002, corrected in docs/theory/gearing.md, Eqs. (M1)-(M2);
docs/conventions.md).

Fixed frame with the common apex O. Pinion axis a1 = (0, 0, 1), gear axis a2 = (sin S, 0, cos S), both pointing from
O into the bodies (S = shaft angle). The pinion turns by phi1 about a1, the gear by phi2 = -(z1/z2) phi1 about a2, so
the pitch cones (half-angles g1, g2, g1 + g2 = S) roll on each other along the pitch line p = (sin g1, 0, cos g1).
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass

import numpy as np

from .._core import meshing as _m
from .._core.rotations import apply
from ..errors import DesignError, Problem

__all__ = ["BevelPairKinematics"]


@dataclass(frozen=True)
class BevelPairKinematics:
    """Constant-ratio kinematics of a bevel pair with intersecting axes and any shaft angle.

    Parameters
    ----------
    shaft_angle : float, rad
        S, angle between the pinion and gear axes, 0 < S < pi.
    z1, z2 : int
        Tooth numbers of the pinion and the gear (>= 1).

    Notes
    -----
    Seed 002 Eqs. (7)-(9), (13)-(16) with the corrections of docs/theory/gearing.md, Eqs. (M1)-(M6):
    w(1) = w1 a1, w(2) = -w2 a2 with w2/w1 = z1/z2, w(12) = w(1) - w(2) = (w1 cos g1 + w2 cos g2) p and
    v(12) = w(12) x r. Member frames (docs/conventions.md): a pinion point r1 sits at R(a1, phi1) r1 in the fixed
    frame, a gear point r2 at R(a2, phi2) R_y(S) r2.
    """

    shaft_angle: float
    z1: int
    z2: int

    def __post_init__(self):
        problems = []
        s = self.shaft_angle
        if isinstance(s, bool) or not isinstance(s, numbers.Real) or not np.isfinite(s) or not 0.0 < s < np.pi:
            problems.append(Problem("shaft_angle", s, "0 < value < pi", "rad"))
        for name in ("z1", "z2"):
            z = getattr(self, name)
            if isinstance(z, bool) or not isinstance(z, numbers.Integral) or z < 1:
                problems.append(Problem(name, z, "integer >= 1", "-"))
        if problems:
            raise DesignError(problems)
        object.__setattr__(self, "shaft_angle", float(s))
        object.__setattr__(self, "z1", int(self.z1))
        object.__setattr__(self, "z2", int(self.z2))

    # ----------------------------------------------------------------------------------------- geometry
    @property
    def ratio(self) -> float:
        """z1/z2 = w2/w1 (-)."""
        return self.z1 / self.z2

    @property
    def pinion_axis(self) -> np.ndarray:
        """a1 = (0, 0, 1), (3,) float, fixed frame."""
        return np.array([0.0, 0.0, 1.0])

    @property
    def gear_axis(self) -> np.ndarray:
        """a2 = (sin S, 0, cos S), (3,) float, fixed frame."""
        return _m.gear_axis(self.shaft_angle)

    @property
    def pitch_angle_pinion(self) -> float:
        """g1, rad: tan g1 = sin S / (z2/z1 + cos S)."""
        return float(_m.pitch_angles(self.shaft_angle, self.z1, self.z2)[0])

    @property
    def pitch_angle_gear(self) -> float:
        """g2 = S - g1, rad."""
        return float(_m.pitch_angles(self.shaft_angle, self.z1, self.z2)[1])

    @property
    def pitch_line(self) -> np.ndarray:
        """p = (sin g1, 0, cos g1), (3,) float, fixed frame: the instantaneous axis of relative rotation."""
        return _m.pitch_line(self.pitch_angle_pinion)

    # ----------------------------------------------------------------------------------------- motion
    def gear_angle(self, phi1):
        """phi2 = -(z1/z2) phi1, rad (same shape as ``phi1``)."""
        return -self.ratio * np.asarray(phi1, float)

    def pinion_to_fixed(self, phi1):
        """R(a1, phi1): pinion member frame -> fixed frame, shape ``phi1.shape + (3, 3)``."""
        return _m.pinion_to_fixed(np.asarray(phi1, float))

    def gear_to_fixed(self, phi2):
        """R(a2, phi2) R_y(S): gear member frame -> fixed frame, shape ``phi2.shape + (3, 3)``."""
        return _m.gear_to_fixed(np.asarray(phi2, float), self.shaft_angle)

    def pinion_to_gear(self, phi1):
        """Pinion member frame -> gear member frame with the pinion at phi1 and the gear at gear_angle(phi1).

        M = R_y(-S) R(a2, (z1/z2) phi1) R(a1, phi1) = gear_to_fixed(phi2)^T pinion_to_fixed(phi1),
        shape ``phi1.shape + (3, 3)`` (docs/theory/gearing.md, Eq. (M6), "conjugate surface").
        """
        return _m.pinion_to_gear(np.asarray(phi1, float), self.shaft_angle, self.ratio)

    def angular_velocity_pinion(self, omega1=1.0):
        """w(1) = w1 a1, (3,) float, rad/s (fixed frame)."""
        return omega1 * self.pinion_axis

    def angular_velocity_gear(self, omega1=1.0):
        """w(2) = -w2 a2 with w2 = (z1/z2) w1, (3,) float, rad/s (fixed frame)."""
        return -self.ratio * omega1 * self.gear_axis

    def relative_angular_velocity(self, omega1=1.0):
        """w(12) = w(1) - w(2) = (w1 cos g1 + w2 cos g2) p, (3,) float, rad/s."""
        return self.angular_velocity_pinion(omega1) - self.angular_velocity_gear(omega1)

    def relative_velocity(self, r, omega1=1.0):
        """v(12) = w(12) x r at fixed-frame points ``r (..., 3)`` mm, mm/s (intersecting axes: no translation)."""
        return np.cross(self.relative_angular_velocity(omega1), np.asarray(r, float))

    # ----------------------------------------------------------------------------------------- meshing equation
    def meshing_velocity_form(self, r, n, omega1=1.0):
        """n . v(12) at fixed-frame points and normals, mm/s (seed 002 Eq. (15), docs/theory/gearing.md, Eqs.
        (M2)-(M4))."""
        return np.einsum("...i,...i->...", np.asarray(n, float), self.relative_velocity(r, omega1))

    def meshing_willis_form(self, r, n):
        """det[r, n, p] = (r x n) . p at fixed-frame points and normals, mm (docs/theory/gearing.md, Eq. (M4)).

        n . v(12) = (w1 cos g1 + w2 cos g2) det[r, n, p]: the common normal meets the pitch line.
        """
        return _m.willis(np.asarray(r, float), np.asarray(n, float), self.pitch_line)

    def meshing_function(self, r1, n1, phi1):
        """f(r1, n1, phi1) = (r1 x n1) . R(a1, -phi1) p, mm: the Willis form in pinion member coordinates.

        Parameters
        ----------
        r1, n1 : (..., 3) float, mm and -
            Pinion points and unit normals in the pinion member frame.
        phi1 : (...) float, rad
            Pinion rotation.
        """
        return _m.meshing_function(np.asarray(r1, float), np.asarray(n1, float), phi1, self.pitch_angle_pinion)

    def to_fixed_pinion(self, r1, phi1):
        """Pinion member coordinates -> fixed frame, ``(..., 3)``."""
        return apply(self.pinion_to_fixed(phi1), np.asarray(r1, float))

    def to_gear(self, r1, phi1):
        """Pinion member coordinates -> gear member coordinates at the meshing position phi1, ``(..., 3)``.

        Elementwise form of :meth:`pinion_to_gear`, M = R_z((z1/z2) phi1) R_y(-S) R_z(phi1) (the same map to
        round-off, without building a 3 x 3 matrix per point).
        """
        return _m.pinion_to_fixed_and_gear((np.asarray(r1, float),), phi1, self.shaft_angle, self.ratio)[1][0]
