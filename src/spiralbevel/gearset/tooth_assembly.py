"""One whole tooth from a member's two generated flanks: the concave flank turned about the axis so that the pair
bounds a tooth of the mean normal thickness."""

from __future__ import annotations

import math

import numpy as np

from .._core.rotations import rot_z
from ..conventions import Side
from ..errors import GeometryError

def _azimuth(p):
    return float(np.arctan2(p[1], p[0]))


def tooth_rotation(blank, setups, member):
    """Rotation (rad, about +z) of the concave flank that makes one tooth of the mean normal thickness smn.

    The convex and concave mean pitch points lie at the same axial position and radius; the tooth's transverse
    angular thickness there is (smn / cos(beta_m)) / r_m. The tooth material lies on the side opposite to the
    convex flank's outward normal.
    """
    i = member.index
    mc = setups[(member, Side.CONVEX)].flank.mean_point()
    mk = setups[(member, Side.CONCAVE)].flank.mean_point()
    r_m = math.hypot(mc.point[0], mc.point[1])
    angle = getattr(blank, f"smn{i}") / math.cos(getattr(blank, f"beta_m{i}")) / r_m
    e_az = np.array([-mc.point[1], mc.point[0], 0.0]) / r_m
    side = 1.0 if mc.normal @ e_az > 0 else -1.0     # material toward -side
    target = _azimuth(mc.point) - side * angle
    rot = math.remainder(target - _azimuth(mk.point), 2 * math.pi)
    nk = rot_z(rot) @ mk.normal
    if np.sign(nk @ e_az) == side:
        raise GeometryError.single(f"{member.value}.flanks", "inconsistent",
                                   "convex and concave outward normals facing away from one tooth", "-",
                                   "the generated flanks cannot bound one tooth: check hands and blades")
    return rot


def rotate_grid(points, normals, angle):
    """Rotate (..., 3) points and normals about +z by ``angle`` rad."""
    R = rot_z(float(angle))
    return points @ R.T, normals @ R.T
