"""Formate (non-generated) flanks as TCA contact surfaces (the ``ContactSurface`` protocol of ``contact_surface.py``).

:class:`FormateSurface` turns a :class:`~spiralbevel.meshing.formate.FormateFlank` (the cutter surface placed on the
universal generator with the cradle locked) into what ``solve_tca`` reads: points and outward normals at the
parameters (u, theta) (blade parameter mm, cutter angle rad), the flank boundaries (toe, heel, top, fillet junction)
as signed margins, and the reference parameters at the flank's mean point. Derivatives are central differences of
``evaluate`` (``fd_step``): the cutter surface is a surface of revolution, smooth in both parameters.
"""

from __future__ import annotations

import numpy as np

from .._core.rotations import rot_z
from .generated_surface import EDGE_TOL

__all__ = ["FormateSurface"]


class FormateSurface:
    """A :class:`~spiralbevel.meshing.formate.FormateFlank` seen by TCA, parameters (u mm, theta rad).

    Parameters
    ----------
    flank : FormateFlank
    rotation : float, rad
        Turn about +z applied to points and normals (member frame), as ``GeneratedSurface``.
    """

    #: central-difference steps (mm, rad): the truncation error (~h^2 x third derivative) stays below 1e-10 mm
    fd_step = (1e-5, 1e-7)
    boundary_names = ("toe", "heel", "top", "fillet")

    def __init__(self, flank, rotation: float = 0.0):
        self.flank = flank
        self.rotation = float(rotation)
        self._R = rot_z(self.rotation)
        mp = flank.mean_point()
        self.reference_params = np.array([mp.u, mp.theta])
        self.mean_point = mp
        self._u_j = flank.cutter.fillet_range[1]

    @staticmethod
    def chart_params(grid):
        """The surface parameters (u, theta) of the points of a ``FlankPoints`` grid of the flank."""
        return grid.u, grid.theta

    def evaluate(self, params):
        """Points (..., 3) mm and outward unit normals (..., 3) in the member frame at ``params (..., 2) = (u,
        theta)``."""
        params = np.asarray(params, float)
        fp = self.flank.evaluate(params[..., 0], params[..., 1])
        return fp.points @ self._R.T, fp.normals @ self._R.T

    def boundary_margins(self, params):
        """Signed margins (..., 4) to ``boundary_names`` (>= 0 on the flank): R - R_i and R_e - R (mm, toe and heel),
        h_face(R) - h (mm, top edge) and u - u_j (mm, junction of the blade with the cutter's edge radius)."""
        params = np.asarray(params, float)
        r, _ = self.evaluate(params)
        ol = self.flank.outline
        with np.errstate(invalid="ignore"):
            R, h = ol.Rh(r[..., 2], np.hypot(r[..., 0], r[..., 1]))
            return np.stack([R - ol.Ri, ol.Re - R, ol.h_face(R) - h, params[..., 0] - self._u_j], -1)

    def contains(self, params):
        """True where (u, theta) lies on the flank (within ``EDGE_TOL`` of a boundary, as ``GeneratedSurface``)."""
        g = self.boundary_margins(params)
        with np.errstate(invalid="ignore"):
            return np.all(g >= -EDGE_TOL, axis=-1)
