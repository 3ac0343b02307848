"""Face-milling head cutter: straight (or circular-arc) blade with a circular edge radius (seed 001 Eqs. (7)-(10)).

docs/theory/generation.md, Eqs. (G1)-(G3) gives the decoded equations. Frame S_h: cutter axis z_h, blade tips in the
plane z_h = 0, cutter body
toward -z_h. s = +1 for the OUTER blade, which cuts the CONCAVE flank; s = -1 for the INNER blade, which cuts the
CONVEX flank.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum

import numpy as np

from spiralbevel._core import generation as _g
from spiralbevel.conventions import Side
from spiralbevel.errors import DesignError, GeometryError

__all__ = ["Blade", "HeadCutter"]


class Blade(str, Enum):
    """Blade of a face-milling cutter. ``INNER`` cuts the convex flank, ``OUTER`` the concave flank."""

    INNER = "inner"
    OUTER = "outer"

    @property
    def sign(self) -> int:
        """s of seed 001 Eqs. (7)-(10): +1 outer, -1 inner (docs/theory/generation.md, Eqs. (G1)-(G3))."""
        return 1 if self is Blade.OUTER else -1

    @property
    def side(self) -> Side:
        """The flank this blade generates."""
        return Side.CONCAVE if self is Blade.OUTER else Side.CONVEX

    @classmethod
    def for_side(cls, side: Side) -> "Blade":
        return cls.OUTER if Side(side) is Side.CONCAVE else cls.INNER


@dataclass(frozen=True)
class HeadCutter:
    """One blade of a face-milling head cutter.

    Parameters
    ----------
    point_radius : float, mm
        R_h, radius of the (virtual sharp) blade point in the tip plane.
    blade_angle : float, rad
        alpha_h, angle of the straight blade to the cutter axis (the *modified* blade angle of seed 001).
    point_width : float, mm
        W, width of the blade point (slot width at the tip); the nominal cutter radius is R_h - s W/2.
    edge_radius : float, mm
        rho_h, edge (fillet) radius, > 0.
    blade : Blade
        ``Blade.INNER`` (convex flank) or ``Blade.OUTER`` (concave flank).
    profile_radius : float, mm, optional
        Radius of a circular-arc blade profile (profile crowning: the generated tooth profile is more convex);
        ``inf`` for a straight blade.
    profile_ref : float, mm
        Blade parameter u (distance along the nominal straight blade from the tip plane) where the arc is tangent to
        the nominal straight blade. Only used with a finite ``profile_radius``.
    """

    point_radius: float
    blade_angle: float
    point_width: float
    edge_radius: float
    blade: Blade = Blade.INNER
    profile_radius: float = math.inf
    profile_ref: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "blade", Blade(self.blade))
        problems = []
        chk = [("point_radius", self.point_radius, 0.0, math.inf, "mm", "> 0"),
               ("blade_angle", self.blade_angle, 0.0, 0.5 * math.pi, "rad", "0 < value < pi/2"),
               ("point_width", self.point_width, 0.0, math.inf, "mm", "> 0"),
               ("edge_radius", self.edge_radius, 0.0, math.inf, "mm", "> 0")]
        for name, val, lo, hi, unit, allowed in chk:
            if not (isinstance(val, (int, float)) and math.isfinite(val) and lo < val < hi):
                problems.append(DesignError.single(f"cutter.{name}", val, allowed, unit).problems[0])
        if not (self.profile_radius > 0):
            problems.append(DesignError.single("cutter.profile_radius", self.profile_radius, "> 0 (inf: straight)",
                                               "mm").problems[0])
        if problems:
            raise DesignError(problems)
        reach = self.edge_radius * (1 - math.sin(self.blade_angle)) / math.cos(self.blade_angle)
        if reach > 0.5 * self.point_width:
            raise GeometryError.single(
                "cutter.edge_radius", self.edge_radius,
                f"<= {0.5 * self.point_width * math.cos(self.blade_angle) / (1 - math.sin(self.blade_angle)):.4g}",
                "mm", "the edge radius takes more than half the point width")
        if self.point_radius - self.blade.sign * reach <= 0:
            raise GeometryError.single("cutter.point_radius", self.point_radius, "larger than the fillet", "mm")
        if math.isfinite(self.profile_radius):
            cp = self._params()
            if not (0.0 < cp["chi_j"] < 0.5 * math.pi) or cp["u_min"] > cp["u_j"]:
                raise GeometryError.single("cutter.profile_radius", self.profile_radius,
                                           "large enough for the edge radius to join the arc", "mm")

    # ------------------------------------------------------------------------------------------------------------
    @property
    def sign(self) -> int:
        """s = +1 outer blade, -1 inner blade."""
        return self.blade.sign

    @property
    def side(self) -> Side:
        return self.blade.side

    @property
    def nominal_radius(self) -> float:
        """Cutter (mean) radius R_c = R_h - s W/2, mm (seed 001 Table 4: 113.155 + 2.29/2 = 114.3)."""
        return self.point_radius - self.sign * 0.5 * self.point_width

    def _params(self) -> dict:
        return _g.cutter_params(self.sign, self.blade_angle, self.point_radius, self.edge_radius,
                                self.profile_radius, self.profile_ref)

    @property
    def fillet_range(self) -> tuple[float, float]:
        """(u_min, u_j): blade parameter at the tip of the edge radius and at its junction with the blade, mm."""
        cp = self._params()
        return cp["u_min"], cp["u_j"]

    def points(self, u, theta):
        """Cutter surface points in S_h, shape (..., 3), mm; u along the blade (fillet for u < u_j), theta rad."""
        rho, z, _, _ = _g.profile(np.asarray(u, float), self._params())
        rho, z, th = np.broadcast_arrays(rho, z, np.asarray(theta, float))
        return np.stack([rho * np.cos(th), rho * np.sin(th), z], -1)

    def normals(self, u, theta):
        """Unit normals n_h of Eqs. (9)-(10) (= r_u x r_theta / |.|), shape (..., 3)."""
        _, _, chi, _ = _g.profile(np.asarray(u, float), self._params())
        chi, th = np.broadcast_arrays(chi, np.asarray(theta, float))
        return np.stack([np.sin(chi) * np.cos(th), np.sin(chi) * np.sin(th), self.sign * np.cos(chi)], -1)

    def principal_curvatures(self, u, theta):
        """Principal curvatures and directions of the cutter surface in S_h.

        Returns
        -------
        k_meridian, k_circ : (...) float, 1/mm
            Curvatures along the blade meridian and along the circle, w.r.t. n_in = s n_h (pointing into the cut
            member's material), with kappa(v) = v.W v, W = -dn_in/dr: this is the member's convex = positive
            convention. Straight blade: 0 and -s cos(alpha)/rho; fillet: -1/rho_h and -s sin(lambda)/rho.
        e_meridian, e_circ : (..., 3)
            Unit directions with e_meridian x e_circ = n_in.
        """
        cp = self._params()
        rho, _, chi, dchi = _g.profile(np.asarray(u, float), cp)
        rho, chi, dchi, th = np.broadcast_arrays(rho, chi, dchi, np.asarray(theta, float))
        e = np.stack([np.cos(th), np.sin(th), np.zeros_like(th)], -1)
        k = np.array([0.0, 0.0, 1.0])
        s = self.sign
        t = (s * np.cos(chi))[..., None] * e - np.sin(chi)[..., None] * k
        n_in = (s * np.sin(chi))[..., None] * e + np.cos(chi)[..., None] * k
        return -dchi, -s * np.sin(chi) / rho, t, np.cross(n_in, t)
