"""Uniform access to a tooth flank: evaluate, locate at an (axial position, radius), normal-line distances.

A :class:`FlankAccess` wraps a generated face-milled ``ToothFlank``, a log-spiral ``DesignedFlank`` or any parametric
surface given as a callable ``surface(u, v) -> (points, normals)`` (member frame, mm, outward unit normals). It is the
common ground of the measurement grid (``spiralbevel.manufacturing.measurement``) and the ease-off
(``spiralbevel.meshing.easeoff``): both measure one flank against another along a normal line.

Locating a point means finding the flank point on the circle of given axial position z and radius about the member
axis (the "projected tooth" coordinates of docs/conventions.md). ``ToothFlank`` has its own batched Newton
(``ToothFlank.locate``); a ``DesignedFlank`` is located in closed form (the log-spiral flank meets the cone of
half-angle nu along psi = +-acos(cos nu / cos delta), docs/theory/logspiral.md, Eqs. (S10)-(S11) (#cones), and the
sphere of radius rho at
phi = ln(rho/rho0) tan(beta)/sin(delta)); a callable surface by a batched Newton solve on (u, v).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.spatial import cKDTree

from .._core.newton import solve_batched
from ..errors import DesignError, GeometryError
from ..geometry.curves import psi_of_cone_angle

__all__ = ["FlankAccess", "flank_access", "normal_line_distance", "logspiral_parameters", "tooth_grid"]


def _split(out):
    if isinstance(out, (tuple, list)):
        return np.asarray(out[0], float), np.asarray(out[1], float)
    return np.asarray(out.point, float), np.asarray(out.normal, float)


@dataclass(frozen=True)
class FlankAccess:
    """One flank seen through three operations (member frame, mm).

    Attributes
    ----------
    surface : callable
        ``surface(u, v) -> (points (..., 3) mm, normals (..., 3))`` with outward unit normals.
    samples : ((k,) float, (k,) float)
        Parameter samples covering the flank (start values of Newton solves).
    locate_fn : callable or None
        ``locate_fn(axial, radius) -> (points, normals, u, v)``; ``None``: batched Newton on ``surface``.
    """

    surface: Callable
    samples: tuple
    locate_fn: Callable | None = None

    def evaluate(self, u, v):
        """Points (..., 3) mm and outward unit normals (..., 3) at broadcast parameters ``u, v``."""
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        return _split(self.surface(u, v))

    def locate(self, axial, radius, tol: float = 1e-10):
        """Flank point on the circle (axial, radius) about the member axis.

        Parameters
        ----------
        axial, radius : array_like, mm
            Broadcast together.
        tol : float, mm
            Newton tolerance on |z - axial| and |rho - radius| (callable surfaces only).

        Returns
        -------
        points, normals : (..., 3) float
        u, v : (...) float
            Surface parameters of the located points.

        Raises
        ------
        GeometryError
            A circle does not meet the flank (Newton fails).
        """
        axial, radius = np.broadcast_arrays(np.asarray(axial, float), np.asarray(radius, float))
        if self.locate_fn is not None:
            return self.locate_fn(axial, radius)
        u0, v0 = (np.asarray(a, float).ravel() for a in self.samples)
        p0, _ = self.evaluate(u0, v0)
        tree = cKDTree(np.stack([p0[:, 2], np.hypot(p0[:, 0], p0[:, 1])], -1))
        _, idx = tree.query(np.stack([axial.ravel(), radius.ravel()], -1))
        x0 = np.stack([u0[idx], v0[idx]], -1).reshape(axial.shape + (2,))
        span = np.array([np.ptp(u0), np.ptp(v0)]) + 1e-12

        def fun(x):
            p, _ = self.evaluate(x[..., 0], x[..., 1])
            return np.stack([p[..., 2] - axial, np.hypot(p[..., 0], p[..., 1]) - radius], -1)

        res = solve_batched(fun, x0, tol=tol, max_iter=60, max_step=0.25 * span)
        if not np.all(res.converged):
            bad = ~res.converged
            raise GeometryError.single("locate(axial, radius)", f"{int(bad.sum())} of {bad.size} points",
                                       "circles that meet the flank", "mm",
                                       f"Newton did not converge (largest residual {np.nanmax(res.residual):.3g} mm)")
        p, n = self.evaluate(res.x[..., 0], res.x[..., 1])
        return p, n, res.x[..., 0], res.x[..., 1]


def _toothflank_access(flank) -> FlankAccess:
    def surface(u, v):
        fp = flank.evaluate(u, v, curvature=False)
        return fp.points, fp.normals

    def locate(axial, radius):
        fp = flank.locate(axial, radius, curvature=False)
        return fp.points, fp.normals, fp.u, fp.psi_c

    g = flank.grid(9, 5, curvature=False)
    return FlankAccess(surface, (g.u.ravel(), g.psi_c.ravel()), locate)


def logspiral_parameters(flank, rho, nu):
    """(varphi, phi) of the log-spiral flank point on the sphere |r| = rho and the coaxial cone of half-angle nu.

    Parameters
    ----------
    flank : DesignedFlank
    rho : array_like, mm
    nu : array_like, rad
        Cone half-angle, delta <= nu < pi/2 (delta: base-cone angle).

    Notes
    -----
    phi = ln(rho/rho0) tan(beta)/sin(delta) (seed 000 Eq. (9)); |psi| = acos(cos nu / cos delta)
    (docs/theory/logspiral.md, Eqs. (S10)-(S11) (#cones)) with
    the sign of the flank's branch; varphi = phi + psi / sin(delta). The rotation of the flank about +z does not
    change rho or nu.
    """
    s = flank.surface
    phi = s.phi_of_rho(rho)
    psi = s.psi_sign(flank.side) * psi_of_cone_angle(nu, s.base_cone_angle)
    return s.varphi_of(psi, phi), phi


def _designed_access(flank) -> FlankAccess:
    def surface(u, v):
        g = flank.evaluate(u, v)
        return g.point, g.normal

    def locate(axial, radius):
        rho, nu = np.hypot(axial, radius), np.arctan2(radius, axial)
        if np.any(nu < flank.surface.base_cone_angle):
            raise GeometryError.single("locate(axial, radius)", "-", "points outside the base cone", "rad",
                                       "the log-spiral flank does not reach inside its base cone")
        varphi, phi = logspiral_parameters(flank, rho, nu)
        p, n = surface(varphi, phi)
        return p, n, varphi, phi

    varphi, phi = flank.domain.grid(9, 5)
    return FlankAccess(surface, (varphi.ravel(), phi.ravel()), locate)


def flank_access(flank, bounds=None, samples=(15, 11)) -> FlankAccess:
    """A :class:`FlankAccess` for a ``ToothFlank``, a ``DesignedFlank``, a ``FlankAccess`` or a callable surface.

    Parameters
    ----------
    flank : ToothFlank, DesignedFlank, FlankAccess or callable
        A callable is ``surface(u, v) -> (points, normals)`` in the member frame.
    bounds : ((u_min, u_max), (v_min, v_max)), parameter units
        Required for a callable: parameter box sampled for Newton start values (the flank's active region).
    samples : (int, int)
        Sample counts of ``bounds``.
    """
    if isinstance(flank, FlankAccess):
        return flank
    if hasattr(flank, "locate") and hasattr(flank, "generator"):
        return _toothflank_access(flank)
    if hasattr(flank, "domain") and hasattr(flank, "surface") and hasattr(flank, "side"):
        return _designed_access(flank)
    if callable(flank):
        try:
            (u0, u1), (v0, v1) = bounds
        except (TypeError, ValueError) as err:
            raise DesignError.single("bounds", bounds, "((u_min, u_max), (v_min, v_max)) for a callable surface",
                                     "parameter units") from err
        U, V = np.meshgrid(np.linspace(u0, u1, samples[0]), np.linspace(v0, v1, samples[1]), indexing="ij")
        return FlankAccess(flank, (U.ravel(), V.ravel()))
    raise DesignError.single("flank", type(flank).__name__,
                             "a ToothFlank, a DesignedFlank, a FlankAccess or a callable surface(u, v)", "-")


def normal_line_distance(access: FlankAccess, points, normals, iterations: int = 4):
    """Signed distance t from ``points`` along the lines ``points + t normals`` to the flank of ``access``.

    Parameters
    ----------
    access : FlankAccess
        The (actual) flank.
    points, normals : (..., 3) float, mm and -
        Nominal points and unit normals (member frame).
    iterations : int
        Fixed-point iterations: locate the flank on the circle through the current estimate p + t n, intersect the
        normal line with the tangent plane there. Converges quadratically (Newton on the line-surface
        intersection); 3-4 iterations reach 1e-12 mm for deviations below 0.1 mm.

    Returns
    -------
    t : (...) float, mm
        Positive when the flank lies on the side the normal points to (outward normal: material added).
    """
    points, normals = np.asarray(points, float), np.asarray(normals, float)
    t = np.zeros(points.shape[:-1])
    for _ in range(int(iterations)):
        q = points + t[..., None] * normals
        pa, na, _, _ = access.locate(q[..., 2], np.hypot(q[..., 0], q[..., 1]))
        t = np.einsum("...i,...i->...", pa - points, na) / np.einsum("...i,...i->...", normals, na)
    return t


def _check_grid_args(n_face, n_profile, face_margin, profile_margin):
    for name, n in (("n_face", n_face), ("n_profile", n_profile)):
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
            raise DesignError.single(name, n, "integer >= 2", "-")
    for name, m in (("face_margin", face_margin), ("profile_margin", profile_margin)):
        if isinstance(m, bool) or not (isinstance(m, (int, float)) and np.isfinite(m) and 0.0 <= m < 0.5):
            raise DesignError.single(name, m, "0 <= value < 0.5", "- (fraction)")


def tooth_grid(flank, n_face: int, n_profile: int, face_margin: float, profile_margin: float,
               pitch_angle: float | None = None) -> dict:
    """Even grid over the projected active flank of a ``ToothFlank`` or a log-spiral ``DesignedFlank``.

    Parameters
    ----------
    flank : ToothFlank or DesignedFlank
    n_face, n_profile : int
        Points toe -> heel and lower limit -> top, >= 2.
    face_margin, profile_margin : float, -
        Insets as fractions of the face width and of the active depth, 0 <= value < 0.5.
    pitch_angle : float, rad, optional
        Log-spiral flank only: delta of the (R, h) coordinates (default: mean of root and face cone angles).

    Returns
    -------
    dict
        ``R, h, axial, radius`` (n_face, n_profile) mm, ``pitch_angle`` rad and ``Rm`` mm (mean cone distance: the
        blank's R_m, or the middle of the log-spiral flank's cone-distance range).

    Notes
    -----
    Generated flank: even in R between R_i and R_e (inset), even in h between the fillet/blade junction line
    (u = u_j, from a 41-station ``ToothFlank.grid`` interpolated by a cubic spline in R) and the face cone. Log-spiral
    flank (blank bounded by spheres and cones through the apex): even in cone distance rho and cone half-angle nu,
    R = rho cos(nu - delta), h = rho sin(nu - delta). R = rho sin(delta) + z cos(delta), h = rho cos(delta) -
    z sin(delta) in both cases (docs/conventions.md).
    """
    _check_grid_args(n_face, n_profile, face_margin, profile_margin)
    t = np.linspace(profile_margin, 1.0 - profile_margin, n_profile)
    if hasattr(flank, "outline") and hasattr(flank, "generator"):
        from scipy.interpolate import CubicSpline

        ol = flank.outline
        b = ol.Re - ol.Ri
        R = np.linspace(ol.Ri + face_margin * b, ol.Re - face_margin * b, n_face)
        fine = flank.grid(41, 2, curvature=False)
        jR, jh = ol.Rh(fine.axial[:, 0], fine.radius[:, 0])
        h_low = CubicSpline(jR, jh)(R)
        depth = ol.h_face(R) - h_low
        if np.any(depth <= 0):
            raise GeometryError.single("flank", repr(flank), "a junction line below the face cone", "mm",
                                       "no active flank between the fillet and the top")
        H = h_low[:, None] + t[None, :] * depth[:, None]
        RR = np.broadcast_to(R[:, None], H.shape).copy()
        axial, radius = ol.axial_radius(RR, H)
        return dict(R=RR, h=H, axial=axial, radius=radius, pitch_angle=float(ol.delta), Rm=float(ol.Rm))
    if not (hasattr(flank, "domain") and hasattr(flank, "surface")):
        raise DesignError.single("flank", type(flank).__name__, "a ToothFlank or a DesignedFlank", "-")
    s, dom = flank.surface, flank.domain
    rho_a, rho_b = sorted(float(s.rho(p)) for p in (dom.phi_min, dom.phi_max))
    d = s.base_cone_angle
    nu_a, nu_b = sorted(float(np.arccos(np.cos(abs(p)) * np.cos(d))) for p in (dom.psi_min, dom.psi_max))
    if pitch_angle is None:
        pitch_angle = 0.5 * (nu_a + nu_b)
    elif isinstance(pitch_angle, bool) or not (isinstance(pitch_angle, (int, float)) and 0 < pitch_angle < np.pi / 2):
        raise DesignError.single("pitch_angle", pitch_angle, "0 < value < pi/2", "rad")
    b = rho_b - rho_a
    rho = np.linspace(rho_a + face_margin * b, rho_b - face_margin * b, n_face)
    nu = nu_a + t * (nu_b - nu_a)
    rho, nu = np.meshgrid(rho, nu, indexing="ij")
    return dict(R=rho * np.cos(nu - pitch_angle), h=rho * np.sin(nu - pitch_angle), axial=rho * np.cos(nu),
                radius=rho * np.sin(nu), pitch_angle=float(pitch_angle), Rm=0.5 * (rho_a + rho_b))
