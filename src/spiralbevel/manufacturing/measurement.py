"""Nominal measurement grids for a coordinate measuring machine (CMM) and simulated flank measurements.

A :class:`MeasurementGrid` holds nominal points and outward unit normals of one flank in its member frame on an
``n_face x n_profile`` grid (9 x 5 by default, the usual AGMA 2009 / Gleason practice), evenly spaced

* lengthwise in the pitch-generatrix coordinate R (distance from the apex along the pitch generatrix of the point's
  axial section), inset from the toe R_i and the heel R_e by ``face_margin`` times the face width, and
* in height h above the pitch line (measured perpendicular to the pitch generatrix in the axial section), inset from
  the lower limit of the active flank (the fillet/blade junction line of a generated flank, the root cone of a
  log-spiral flank) and from the face cone by ``profile_margin`` times the active depth at that R.

R = rho sin(delta) + z cos(delta), h = rho cos(delta) - z sin(delta) (docs/conventions.md "Flank grid"), with rho the
radius and z the axial position. Points are located exactly on the flank (``ToothFlank.locate``; closed form for a
log-spiral flank). Rows run from toe (row 1) to heel, columns from the lower limit (column 1) to the top; labels read
``F<row>P<column>`` ("face" and "profile" position), e.g. ``F5P3`` is the centre of a 9 x 5 grid.

Measured deviations are normal deviations along the nominal outward normal, mm, **positive = material added** (the
actual flank lies outside the nominal one, into the tooth space); :func:`measure_deviation` simulates such a
measurement on any flank.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..conventions import Member, Side
from ..errors import DesignError
from ..meshing.flank_access import flank_access, logspiral_parameters, normal_line_distance, tooth_grid

__all__ = ["MeasurementGrid", "measurement_grid", "measurement_grid_logspiral", "measure_deviation"]


@dataclass(frozen=True, repr=False)
class MeasurementGrid:
    """Nominal CMM grid of one flank (member frame).

    Attributes
    ----------
    member : Member
    side : Side
    points : (n_face, n_profile, 3) float, mm
        Nominal points.
    normals : (n_face, n_profile, 3) float
        Outward unit normals (out of the tooth material).
    R, h : (n_face, n_profile) float, mm
        Pitch-generatrix coordinate and height above the pitch line.
    axial, radius : (n_face, n_profile) float, mm
        Axial position z and distance from the member axis.
    row, column : (n_face, n_profile) int
        1-based indices, row 1 at the toe, column 1 at the lower limit of the active flank.
    labels : (n_face, n_profile) str
        ``F<row>P<column>``.
    u, v : (n_face, n_profile) float
        Surface parameters of the points ((u mm, psi_c rad) for a generated flank, (varphi, phi) rad for log-spiral).
    pitch_angle : float, rad
        delta used for R and h.
    """

    member: Member
    side: Side
    points: np.ndarray
    normals: np.ndarray
    R: np.ndarray
    h: np.ndarray
    axial: np.ndarray
    radius: np.ndarray
    row: np.ndarray
    column: np.ndarray
    labels: np.ndarray
    u: np.ndarray
    v: np.ndarray
    pitch_angle: float

    @property
    def shape(self) -> tuple:
        """(n_face, n_profile)."""
        return self.R.shape

    @property
    def size(self) -> int:
        """Number of points."""
        return int(self.R.size)

    def __repr__(self) -> str:
        return (f"MeasurementGrid({Member(self.member).value} {Side(self.side).value}, {self.shape[0]} x "
                f"{self.shape[1]} points)")

    def index_of(self, label: str) -> tuple:
        """(i, j) zero-based array index of a point label such as ``"F5P3"``."""
        hit = np.argwhere(self.labels == str(label).strip().upper())
        if hit.size == 0:
            raise DesignError.single("label", label, f"F1P1 .. F{self.shape[0]}P{self.shape[1]}", "-")
        return tuple(int(k) for k in hit[0])


def _labels(n_face, n_profile):
    row, col = np.meshgrid(np.arange(1, n_face + 1), np.arange(1, n_profile + 1), indexing="ij")
    labels = np.array([[f"F{i}P{j}" for j in range(1, n_profile + 1)] for i in range(1, n_face + 1)])
    return row, col, labels


def measurement_grid(flank, n_face: int = 9, n_profile: int = 5, face_margin: float = 0.1,
                     profile_margin: float = 0.1) -> MeasurementGrid:
    """Nominal measurement grid of a generated face-milled flank.

    Parameters
    ----------
    flank : ToothFlank
        From ``spiralbevel.generation.generate_flank``.
    n_face, n_profile : int
        Points lengthwise (toe -> heel) and in profile (lower limit -> top), >= 2 each.
    face_margin : float, -
        Inset from toe and heel as a fraction of the face width R_e - R_i, 0 <= value < 0.5.
    profile_margin : float, -
        Inset from the fillet/blade junction line and from the face cone as a fraction of the active depth at each R,
        0 <= value < 0.5.

    Returns
    -------
    MeasurementGrid

    Notes
    -----
    The lower limit is the generated fillet/blade junction line (u = u_j, seed 001 Eq. (8)), found on 41
    ``ToothFlank.grid`` stations and interpolated in R by a cubic spline (only the placement of the grid depends
    on it); the points themselves are located exactly (``ToothFlank.locate``, residual < 1e-10 mm).
    """
    if not (hasattr(flank, "outline") and hasattr(flank, "generator")):
        raise DesignError.single("flank", type(flank).__name__, "a ToothFlank (use measurement_grid_logspiral for a "
                                 "DesignedFlank)", "-")
    tg = tooth_grid(flank, n_face, n_profile, face_margin, profile_margin)
    fp = flank.locate(tg["axial"], tg["radius"], curvature=False)
    row, col, labels = _labels(n_face, n_profile)
    return MeasurementGrid(flank.member, flank.side, fp.points, fp.normals, tg["R"], tg["h"], tg["axial"],
                           tg["radius"], row, col, labels, fp.u, fp.psi_c, tg["pitch_angle"])


def measurement_grid_logspiral(flank, n_face: int = 9, n_profile: int = 5, face_margin: float = 0.1,
                               profile_margin: float = 0.1, pitch_angle: float | None = None) -> MeasurementGrid:
    """Nominal measurement grid of a log-spiral ``DesignedFlank`` (closed form).

    Parameters
    ----------
    flank : DesignedFlank
        From ``design_logspiral_pair`` (``pair.flank(member, side)``).
    n_face, n_profile, face_margin, profile_margin
        As :func:`measurement_grid`.
    pitch_angle : float, rad, optional
        delta of the (R, h) coordinates; default the mean of the root and face cone angles of the flank domain
        (pass ``pair.member(member).pitch_angle`` for the design's pitch cone).

    Notes
    -----
    The log-spiral blank is bounded by toe/heel spheres and root/face cones through the apex (``BlankBoundaries``),
    so here the grid is even in cone distance rho = |r| (the face coordinate) and in cone half-angle nu (the height
    coordinate), inset by the margins; the points are found in closed form (see ``logspiral_parameters``). The
    reported R = rho cos(nu - delta), h = rho sin(nu - delta) are the same coordinates as for a generated flank.
    """
    if not (hasattr(flank, "domain") and hasattr(flank, "surface") and hasattr(flank, "side")):
        raise DesignError.single("flank", type(flank).__name__, "a log-spiral DesignedFlank", "-")
    tg = tooth_grid(flank, n_face, n_profile, face_margin, profile_margin, pitch_angle)
    rho, nu = np.hypot(tg["axial"], tg["radius"]), np.arctan2(tg["radius"], tg["axial"])
    varphi, phi = logspiral_parameters(flank, rho, nu)
    g = flank.evaluate(varphi, phi)
    row, col, labels = _labels(n_face, n_profile)
    return MeasurementGrid(Member(flank.member), Side(flank.side), np.array(g.point), np.array(g.normal), tg["R"],
                           tg["h"], tg["axial"], tg["radius"], row, col, labels, varphi, phi, tg["pitch_angle"])


def measure_deviation(flank, grid: MeasurementGrid, iterations: int = 4, bounds=None) -> np.ndarray:
    """Simulated CMM measurement: normal deviation of an actual flank from the nominal grid.

    Parameters
    ----------
    flank : ToothFlank, DesignedFlank or callable surface
        The actual (for example re-generated with changed settings) flank, same member frame.
    grid : MeasurementGrid
        Nominal points and normals.
    iterations : int
        Iterations of the normal-line/flank intersection (see ``normal_line_distance``).
    bounds : ((u_min, u_max), (v_min, v_max)), optional
        Parameter box, required when ``flank`` is a callable.

    Returns
    -------
    (n_face, n_profile) float, mm
        Distance from each nominal point along its outward normal to the actual flank; positive = material added.
    """
    return normal_line_distance(flank_access(flank, bounds), grid.points, grid.normals, iterations)
