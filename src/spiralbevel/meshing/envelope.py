"""General envelope (conjugate-surface) solver for a bevel pair with intersecting axes.

Given any parametric surface of member 1 (the pinion) and the pair kinematics, the solver finds

* for each surface point (u, v) the pinion rotation phi1 at which it is a contact point (the equation of meshing
  f(u, v, phi1) = (r1 x n1) . R(a1, -phi1) p = 0, docs/theory/gearing.md, Eq. (M5)), and the conjugate point and normal
  on member 2 in
  the gear member frame, r2 = R_y(-S) R(a2, (z1/z2) phi1) R(a1, phi1) r1 (:func:`solve_envelope`);
* the instantaneous contact line at a given phi1: for each u, the v with f(u, v, phi1) = 0
  (:func:`solve_contact_line`).

Nothing here knows the log-spiral closed form; the surface is a black box.

Surface callables
-----------------
``surface(u, v)`` is vectorized over broadcast arrays ``u, v`` and returns either ``(points, normals)`` with shape
``(..., 3)`` each (mm, unit outward normals in the member-1 frame), or ``points`` alone (or ``(points, None)``), in
which case the normals are ``orientation * (r_u x r_v) / |r_u x r_v|`` from 4th-order central differences with
parameter step ``fd_step`` (normal error about ``fd_step**4`` times the 5th derivative, plus eps/fd_step rounding).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Literal

import numpy as np

from .._core import meshing as _m
from .._core.envelope_kernel import envelope_points
from ..conventions import TOL
from ..errors import ConvergenceError, DesignError, NoContactError
from .kinematics import BevelPairKinematics

__all__ = ["EnvelopeResult", "ContactLineResult", "evaluate_surface", "solve_envelope", "solve_contact_line"]

Surface = Callable[[np.ndarray, np.ndarray], object]


def evaluate_surface(surface: Surface, u, v, fd_step: float = 1e-3, orientation: float = 1.0):
    """Points and unit normals of ``surface`` at broadcast ``u, v``.

    Parameters
    ----------
    surface : callable
        ``surface(u, v) -> (points, normals)`` or ``-> points`` (see the module notes).
    u, v : array_like, parameter units
    fd_step : float, parameter units
        Step of the finite-difference normals (used only when the surface returns no normals).
    orientation : {+1, -1}
        Sign applied to r_u x r_v for finite-difference normals.

    Returns
    -------
    points, normals : (..., 3) float, mm and -
    """
    u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
    out = surface(u, v)
    if isinstance(out, (tuple, list)):
        points = np.asarray(out[0], float)
        normals = None if len(out) < 2 or out[1] is None else np.asarray(out[1], float)
    else:
        points, normals = np.asarray(out, float), None
    if normals is None:
        def points_fun(a, b):
            res = surface(a, b)
            return np.asarray(res[0] if isinstance(res, (tuple, list)) else res, float)

        normals = _m.fd_normals(points_fun, u, v, fd_step, orientation)
    else:
        normals = normals / np.linalg.norm(normals, axis=-1, keepdims=True)
    return points, normals


@dataclass(frozen=True)
class EnvelopeResult:
    """Conjugate surface of a member-1 surface (output of :func:`solve_envelope`).

    Attributes
    ----------
    u, v : (...) float, parameter units
        Surface parameters on member 1.
    phi1 : (...) float, rad
        Pinion rotation at which (u, v) is in contact.
    phi2 : (...) float, rad
        Gear rotation, -(z1/z2) phi1.
    points, normals : (..., 3) float, mm and -
        Conjugate points and **outward normals of member 2** (= minus the image of the member-1 outward normal) in
        the gear member frame.
    pinion_points, pinion_normals : (..., 3) float
        The member-1 points and normals (member-1 frame).
    contact_points : (..., 3) float, mm
        The contact points in the fixed frame, R(a1, phi1) r1 (the surface of action).
    residual : (...) float
        |f| / |r1| at the solution (dimensionless; f = n . v(12) / |w(12)| in mm).
    converged : (...) bool
        Contact found and residual <= tol.
    branch : int or None
        Root selection used (+1, -1, or None for "nearest to the guess").
    """

    u: np.ndarray
    v: np.ndarray
    phi1: np.ndarray
    phi2: np.ndarray
    points: np.ndarray
    normals: np.ndarray
    pinion_points: np.ndarray
    pinion_normals: np.ndarray
    contact_points: np.ndarray
    residual: np.ndarray
    converged: np.ndarray
    branch: int | None


def _position(mask, *arrays):
    """Text naming the first failing entry of ``mask``."""
    idx = np.unravel_index(int(np.argmax(mask)), mask.shape)
    vals = ", ".join(f"{name}={np.asarray(a)[idx]:.12g}" for name, a in arrays)
    return f"index {tuple(int(i) for i in idx)} ({vals})"


def solve_envelope(surface: Surface, kinematics: BevelPairKinematics, u, v, *, branch: int | None = 1,
                   phi1_guess=0.0, tol: float = 10 * TOL.newton_rel, strict: bool = True,
                   fd_step: float = 1e-3, orientation: float = 1.0) -> EnvelopeResult:
    """Envelope of a member-1 surface: contact rotation phi1 and conjugate point/normal for every (u, v).

    Parameters
    ----------
    surface : callable
        Member-1 surface ``surface(u, v) -> (points, normals)`` (or points only), member-1 frame, mm.
    kinematics : BevelPairKinematics
    u, v : array_like, parameter units
        Surface parameters (broadcast together; any shape).
    branch : {1, -1, None}
        Which of the two roots of the meshing equation (two planes/surfaces of action, drive and coast):
        ``+1`` the root where f decreases through zero as phi1 grows (df/dphi1 < 0), ``-1`` the one where it
        increases, ``None`` the root nearest to ``phi1_guess``. With outward normals, ``+1`` is the plane
        phi1 + varphi = +arccos(tan d1 / tan g1) for a seed-000 flank with psi > 0 (docs/theory/gearing.md, Eq. (M7)).
    phi1_guess : array_like, rad
        Start value; every root is returned within pi of it (roots are 2 pi periodic).
    tol : float
        Accepted |f| / |r1| (dimensionless).
    strict : bool
        Raise on the first failure (default); otherwise flag it in ``converged`` (the failed entries hold NaN).
    fd_step, orientation
        Finite-difference normals, see :func:`evaluate_surface`.

    Returns
    -------
    EnvelopeResult

    Raises
    ------
    NoContactError
        A point never satisfies the meshing equation (its normal line misses the pitch line for every phi1).
    ConvergenceError
        The residual stays above ``tol``.

    Notes
    -----
    For constant-ratio rotation about a1 the meshing function is exactly f = A cos phi1 + B sin phi1 + C with
    (A, B, C) from q = r1 x n1 (docs/theory/gearing.md, Eqs. (M5a)-(M5b)), so both roots are found in closed form for
    all points at once (atan2 and arccos, no iteration) and then polished by two Newton steps with the analytic
    derivative (the arccos loses digits near a tangent root, |C| close to hypot(A, B)). The conjugate points and
    normals are mapped with the elementwise form M = R_z((z1/z2) phi1) R_y(-S) R_z(phi1) of Eq. (M6). Roots, polish,
    residual and maps run in one compiled pass over the points (``_core/envelope_kernel.py``).
    """
    if branch not in (1, -1, None):
        raise DesignError.single("branch", branch, "+1, -1 or None", "-")
    r1, n1 = evaluate_surface(surface, u, v, fd_step, orientation)
    u_b, v_b = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
    phi1, residual, exists, converged, points, normals, fixed = envelope_points(
        r1, n1, phi1_guess, 0 if branch is None else branch, kinematics.pitch_angle_pinion, kinematics.shaft_angle,
        kinematics.ratio, tol)
    if strict and not exists.all():
        raise NoContactError("no contact: the meshing equation has no root at "
                             + _position(~exists, ("u", u_b), ("v", v_b)))
    if strict and not converged.all():
        bad = ~converged
        raise ConvergenceError("meshing equation not solved at " + _position(bad, ("u", u_b), ("v", v_b)),
                               iterations=2, residual=float(np.max(residual[bad])), last=phi1)
    phi1 = np.where(converged, phi1, np.nan)
    return EnvelopeResult(
        u=u_b, v=v_b, phi1=phi1, phi2=kinematics.gear_angle(phi1),
        points=points, normals=normals, pinion_points=r1, pinion_normals=n1,
        contact_points=fixed, residual=residual, converged=converged,
        branch=branch,
    )


@dataclass(frozen=True)
class ContactLineResult:
    """Instantaneous contact line at one pinion rotation (output of :func:`solve_contact_line`).

    Attributes
    ----------
    phi1, phi2 : float, rad
        Pinion rotation and gear rotation -(z1/z2) phi1.
    u, v : (n,) float, parameter units
        Member-1 parameters of the contact points (u given, v solved; swapped when ``solve_for="u"``).
    pinion_points, pinion_normals : (n, 3) float
        Contact points and outward normals on member 1 (member-1 frame).
    points, normals : (n, 3) float
        The same contact points on member 2 and member-2 outward normals (gear member frame).
    contact_points : (n, 3) float, mm
        Contact points in the fixed frame.
    residual : (n,) float
        |f| / |r1|.
    converged : (n,) bool
    iterations : int
    """

    phi1: float
    phi2: float
    u: np.ndarray
    v: np.ndarray
    pinion_points: np.ndarray
    pinion_normals: np.ndarray
    points: np.ndarray
    normals: np.ndarray
    contact_points: np.ndarray
    residual: np.ndarray
    converged: np.ndarray
    iterations: int


def solve_contact_line(surface: Surface, kinematics: BevelPairKinematics, phi1: float, u, v_bounds, *,
                       v0=None, solve_for: Literal["u", "v"] = "v", n_scan: int = 64,
                       tol: float = TOL.newton_rel, max_iter: int = TOL.max_iter, strict: bool = True,
                       fd_step: float = 1e-3, orientation: float = 1.0) -> ContactLineResult:
    """Instantaneous contact line on member 1 at pinion rotation ``phi1``: f(u, v, phi1) = 0 solved for v per u.

    Parameters
    ----------
    surface : callable
        Member-1 surface, see :func:`evaluate_surface`.
    kinematics : BevelPairKinematics
    phi1 : float, rad
        Pinion rotation.
    u : (n,) array_like, parameter units
        Values of the given parameter.
    v_bounds : (float, float), parameter units
        Interval scanned (``n_scan`` samples, all points at once) for a sign change of f.
    v0 : (n,) array_like, optional
        Preferred v: the sign change nearest to it is taken; the first one from ``v_bounds[0]`` otherwise.
    solve_for : {"v", "u"}
        Which surface parameter is solved for (the other one is the given grid ``u``).
    n_scan : int
        Samples of the bracketing scan.
    tol : float
        Accepted |f| / |r1|.
    max_iter : int
        Cap of the safeguarded Newton iterations.
    strict : bool
        Raise on the first failure; otherwise flag it in ``converged``.

    Returns
    -------
    ContactLineResult

    Raises
    ------
    NoContactError
        f has no sign change on ``v_bounds`` for some u.
    ConvergenceError
        The safeguarded Newton iteration did not reach ``tol``.

    Notes
    -----
    The scan evaluates f = A cos phi1 + B sin phi1 + C (docs/theory/gearing.md, Eq. (M5a)) for all u at once and
    takes a sign-change bracket per u. The closed-form contact rotations of the bracket ends (Eq. (M5b)) give the
    start: the secant of the contact-rotation angle, which is linear in v on a log-spiral flank and nearly so on
    other flanks (``_core.meshing.angle_secant_start``). From there a vectorized safeguarded Newton (Newton steps
    inside the bracket, bisection when a step leaves it or stalls, derivative by forward differences) finishes.
    """
    if solve_for not in ("u", "v"):
        raise DesignError.single("solve_for", solve_for, "'u' or 'v'", "-")
    lo_b, hi_b = (float(b) for b in v_bounds)
    if not (np.isfinite(lo_b) and np.isfinite(hi_b) and lo_b < hi_b):
        raise DesignError.single("v_bounds", v_bounds, "finite (low, high) with low < high", "parameter units")
    if int(n_scan) < 2:
        raise DesignError.single("n_scan", n_scan, "integer >= 2", "-")
    surf = surface if solve_for == "v" else (lambda a, b: surface(b, a))
    uu = np.atleast_1d(np.asarray(u, float)).ravel()
    g1 = kinematics.pitch_angle_pinion

    def coefficients(uv_u, uv_v, with_scale=False):
        r, n = evaluate_surface(surf, uv_u, uv_v, fd_step, orientation)
        A, B, C = _m.meshing_coefficients(r, n, g1)
        return A, B, C, (np.linalg.norm(r, axis=-1) if with_scale else None)

    def fun(uv_v):
        A, B, C, _ = coefficients(uu, uv_v)
        return A * c1 + B * s1 + C

    c1, s1 = np.cos(phi1), np.sin(phi1)
    grid = np.linspace(lo_b, hi_b, int(n_scan))
    A, B, C, _ = coefficients(uu[:, None], grid[None, :])
    fgrid = A * c1 + B * s1 + C
    lo, hi, flo, fhi, found, idx = _m.bracket_scan(fgrid, grid, v0, return_index=True)
    if strict and not found.all():
        raise NoContactError(f"no contact at phi1 = {phi1:.12g} rad: f has no sign change on "
                             f"{solve_for} in [{lo_b:.12g}, {hi_b:.12g}] at " + _position(~found, ("u", uu)))
    rows = np.arange(uu.size)
    ends = [_m.meshing_roots(A[rows, j], B[rows, j], C[rows, j])[:2] for j in (idx, idx + 1)]
    x0 = _m.angle_secant_start(flo, fhi, ends[0], ends[1], lo, hi, phi1)
    x0 = np.where(np.isfinite(x0), x0, np.where(flo == 0, lo, np.where(fhi == 0, hi, 0.5 * (lo + hi))))
    A0, B0, C0, scale = coefficients(uu, x0, with_scale=True)
    x, res, ok, it = _m.bracketed_newton(fun, lo, hi, flo, fhi, scale, tol, max_iter, x0=x0,
                                         fx0=A0 * c1 + B0 * s1 + C0)
    converged = found & ok
    if strict and not converged.all():
        raise ConvergenceError(f"contact line at phi1 = {phi1:.12g} rad not converged at "
                               + _position(~converged, ("u", uu), (solve_for, x)), iterations=it,
                               residual=float(np.max(res[~converged])), last=x)
    x = np.where(converged, x, np.nan)
    r1, n1 = evaluate_surface(surf, uu, x, fd_step, orientation)
    (fixed, _), (points, normals) = _m.pinion_to_fixed_and_gear((r1, n1), phi1, kinematics.shaft_angle,
                                                                kinematics.ratio)
    uo, vo = (uu, x) if solve_for == "v" else (x, uu)
    return ContactLineResult(
        phi1=float(phi1), phi2=float(kinematics.gear_angle(phi1)), u=uo, v=vo, pinion_points=r1,
        pinion_normals=n1, points=points, normals=-normals,
        contact_points=fixed, residual=res, converged=converged,
        iterations=it,
    )
