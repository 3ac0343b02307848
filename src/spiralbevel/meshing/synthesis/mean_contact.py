"""The mean contact point of a bevel pair: the gear's reference point placed in the pair frame.

The gear's mean point (seed 003 reference point, docs/theory/generation.md, Eqs. (G10)-(G11) (#mean-point): cone
distance R_m, ``depth`` below the pitch
line; ``ToothFlank.mean_point``) is turned about the gear axis until the common normal passes through the pitch line
(Willis, docs/theory/gearing.md, Eq. (M4): det[r, n, p] = 0). For depth 0 the point then lies on the pitch line itself,
where the pitch
cones of both members touch. The pinion must pass through this point with the opposite outward normal; because the
pinion's own rotation phi10 is free, only quantities invariant under rotation about the pinion axis are prescribed:
axial position, radius and the cylindrical components of the normal (docs/conventions.md, gear-pair frame).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ...conventions import Member
from ...errors import DesignError, GeometryError
from ..kinematics import BevelPairKinematics
from ..pair import pair_kinematics
from ._relations import curvature_tensor

__all__ = ["MeanContact", "mean_contact", "path_reference"]


@dataclass(frozen=True)
class MeanContact:
    """Mean contact point M of a pair at the gear rotation phi20, in the fixed pair frame unless named ``_gear``.

    Attributes
    ----------
    point : (3,) float, mm
        M in the fixed frame.
    normal : (3,) float
        Pinion outward unit normal at M (the gear's outward normal is its opposite).
    phi2 : float, rad
        Gear rotation phi20 about a2 that brings the gear reference point to M.
    gear_point, gear_normal : (3,) float
        M and the gear's outward normal in the gear member frame.
    gear_k : (2,) float, 1/mm
        Gear principal curvatures (profile-like first, convex = positive w.r.t. the gear's outward normal).
    gear_dirs : (2, 3) float
        Matching unit principal directions in the fixed frame.
    gear_tensor : (3, 3) float, 1/mm
        Gear curvature tensor in the fixed frame.
    gear_params : (2,) float
        (u, psi_c) of M on the generated gear flank.
    drive_sign : int
        +1 if the pinion point moves along the pinion's outward normal when phi1 increases (the pinion drives), else -1.
    kinematics : BevelPairKinematics
    """

    point: np.ndarray
    normal: np.ndarray
    phi2: float
    gear_point: np.ndarray
    gear_normal: np.ndarray
    gear_k: np.ndarray
    gear_dirs: np.ndarray
    gear_tensor: np.ndarray
    gear_params: np.ndarray
    drive_sign: int
    kinematics: BevelPairKinematics

    @property
    def pinion_axial(self) -> float:
        """Axial position of M along the pinion axis, mm."""
        return float(self.point[2])

    @property
    def pinion_radius(self) -> float:
        """Distance of M from the pinion axis, mm."""
        return float(np.hypot(self.point[0], self.point[1]))

    def gear_to_fixed(self) -> np.ndarray:
        """Rotation (3, 3) gear member frame -> fixed frame at phi20."""
        return self.kinematics.gear_to_fixed(self.phi2)


def path_reference(point, normal, axis, delta):
    """Profile and lengthwise unit tangents of a flank at a point, for the contact-path angle eta.

    t_p is the tangent of the spherical section through the point (perpendicular to the position vector), oriented
    from root to top (increasing height above the cone of angle ``delta``); t_l = n x t_p or its opposite, oriented
    toward the heel (t_l . r > 0). A path direction eta is cos(eta) t_p + sin(eta) t_l: positive eta leans the path
    toward the heel as it climbs the profile.

    Parameters
    ----------
    point, normal, axis : (3,) float
        Point (mm), outward normal and member axis, all in one frame with the apex at the origin.
    delta : float, rad
        Pitch angle of the member.
    """
    r, n, k = (np.asarray(x, float) for x in (point, normal, axis))
    t_p = np.cross(n, r)
    t_p /= np.linalg.norm(t_p)
    ax = r @ k
    rho = r - ax * k
    up = np.cos(delta) * rho / np.linalg.norm(rho) - np.sin(delta) * k   # gradient of the height above the cone
    if t_p @ up < 0:
        t_p = -t_p
    t_l = np.cross(n, t_p)
    if t_l @ r < 0:
        t_l = -t_l
    return t_p, t_l


def mean_contact(gear_flank, blank, depth: float = 0.0) -> MeanContact:
    """Mean contact point of the pair from a generated gear flank (seed 001 §4.3, Litvin's local synthesis, step 0).

    Parameters
    ----------
    gear_flank : ToothFlank
        A generated gear flank (``generate_flank(..., Member.GEAR, side)``).
    blank : ISO 23509 blank (``z1, z2, Sigma``).
    depth : float, mm
        Depth of the reference point below the gear's pitch line at the mean cone distance (0: mean pitch point).

    Returns
    -------
    MeanContact
    """
    if gear_flank.member is not Member.GEAR:
        raise DesignError.single("gear_flank.member", gear_flank.member.value, "gear", "-")
    if not np.isfinite(depth):
        raise DesignError.single("depth", depth, "finite", "mm")
    kin = pair_kinematics(blank)
    mp = gear_flank.mean_point(depth)
    r2, n2 = np.asarray(mp.point, float), np.asarray(mp.normal, float)
    p = kin.pitch_line

    def willis(phi2):
        R = kin.gear_to_fixed(phi2)
        return float(np.cross(R @ r2, R @ n2) @ p) / np.linalg.norm(r2)

    # start: the gear rotation that puts the point in the plane of the axes, on the pitch-line side
    phi0 = np.pi - np.arctan2(r2[1], r2[0])
    grid = phi0 + np.linspace(-0.6, 0.6, 241)
    Rg = kin.gear_to_fixed(grid)                                   # (241, 3, 3), one vectorized scan
    f = np.cross(Rg @ r2, Rg @ n2) @ p
    roots = [brentq(willis, grid[i], grid[i + 1], xtol=1e-15, rtol=1e-15)
             for i in np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) <= 0)[0]]
    if not roots:
        raise GeometryError.single("gear_flank", repr(gear_flank),
                                   "a flank whose mean-point normal meets the pitch line", "-",
                                   "no gear rotation satisfies the equation of meshing at the mean point")
    phi2 = float(min(roots, key=lambda g: abs(np.angle(np.exp(1j * (g - phi0))))))
    phi2 = float(np.angle(np.exp(1j * phi2)))
    R = kin.gear_to_fixed(phi2)
    P, N2 = R @ r2, R @ n2
    dirs = np.stack([R @ mp.e1, R @ mp.e2])
    k = np.array([mp.k1, mp.k2])
    n1 = -N2
    drive = 1 if n1 @ np.cross(kin.pinion_axis, P) > 0 else -1
    return MeanContact(point=P, normal=n1, phi2=phi2, gear_point=r2, gear_normal=n2, gear_k=k, gear_dirs=dirs,
                       gear_tensor=curvature_tensor(k, dirs), gear_params=np.array([mp.u, mp.psi_c]),
                       drive_sign=drive, kinematics=kin)

