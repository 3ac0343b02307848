"""Compare an envelope (computed conjugate surface) with a candidate mating surface.

The deviation is measured three ways: the distance of each envelope point to the candidate surface (foot point by
batched Newton), the normal mismatch 1 - |n_env . n_cand| at the foot point, and optionally the spread of a surface
invariant (for seed-000 flanks ln rho - phi sin(delta) cot(beta) = ln rho0, docs/theory/logspiral.md, Eq. (S2) and
docs/theory/gearing.md, Eq. (M8)). A wrong
candidate (for instance a base cone that violates sin d1 / sin g1 = sin d2 / sin g2) gives a measurable deviation
that :class:`ConjugacyReport` reports and flags.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.spatial import cKDTree

from .._core import meshing as _m
from .._core.newton import solve_batched
from ..conventions import TOL
from ..errors import ConvergenceError, DesignError
from .envelope import evaluate_surface

__all__ = ["FootPoints", "ConjugacyReport", "nearest_points", "compare_conjugate", "logspiral_invariant"]


@dataclass(frozen=True)
class FootPoints:
    """Nearest points on a candidate surface (output of :func:`nearest_points`).

    Attributes
    ----------
    u, v : (n,) float, parameter units
        Foot-point parameters on the candidate.
    points, normals : (n, 3) float, mm and -
        Foot points and candidate unit normals there.
    distance : (n,) float, mm
        Signed distance along the candidate normal: query = foot + distance * normal.
    inside : (n,) bool
        Foot point inside the parameter bounds.
    converged : (n,) bool
    """

    u: np.ndarray
    v: np.ndarray
    points: np.ndarray
    normals: np.ndarray
    distance: np.ndarray
    inside: np.ndarray
    converged: np.ndarray


def nearest_points(query, candidate, bounds, *, samples=(41, 41), uv0=None, tol: float = TOL.newton_abs,
                   max_iter: int = TOL.max_iter, strict: bool = True, fd_step: float = 1e-3,
                   orientation: float = 1.0) -> FootPoints:
    """Foot points of ``query`` points on the candidate surface, solved by batched Newton.

    Parameters
    ----------
    query : (..., 3) array_like, mm
        Points to project.
    candidate : callable
        ``candidate(u, v) -> (points, normals)`` (or points only), see :func:`~spiralbevel.meshing.envelope.
        evaluate_surface`.
    bounds : ((u_min, u_max), (v_min, v_max)), parameter units
        Parameter box sampled for the start values and used for the ``inside`` flag.
    samples : (int, int)
        Grid of the start-value search (nearest sample by k-d tree).
    uv0 : (..., 2) array_like, optional
        Start values instead of the grid search.
    tol : float, mm
        Accepted max-norm of r(u, v) + d n(u, v) - query.
    strict : bool
        Raise :class:`ConvergenceError` when a foot point is not found.

    Returns
    -------
    FootPoints
        Flattened to ``n = query.size // 3`` entries.

    Notes
    -----
    Unknowns (u, v, d), equations r(u, v) + d n(u, v) = x (3 per point): at the solution x - r is along the normal,
    i.e. the foot of the perpendicular, and |d| is the distance. Jacobian by forward differences
    (:func:`spiralbevel._core.newton.solve_batched`).
    """
    x = np.asarray(query, float).reshape(-1, 3)
    (u_lo, u_hi), (v_lo, v_hi) = ((float(a), float(b)) for a, b in bounds)
    if not (u_lo < u_hi and v_lo < v_hi):
        raise DesignError.single("bounds", bounds, "((u_min, u_max), (v_min, v_max)) with min < max",
                                 "parameter units")

    def evaluate(u, v):
        return evaluate_surface(candidate, u, v, fd_step, orientation)

    if uv0 is None:
        ug, vg = np.meshgrid(np.linspace(u_lo, u_hi, samples[0]), np.linspace(v_lo, v_hi, samples[1]),
                             indexing="ij")
        rg, _ = evaluate(ug.ravel(), vg.ravel())
        _, idx = cKDTree(rg).query(x)
        uv = np.stack([ug.ravel()[idx], vg.ravel()[idx]], -1)
    else:
        uv = np.asarray(uv0, float).reshape(-1, 2).copy()
    r0, n0 = evaluate(uv[:, 0], uv[:, 1])
    d0 = np.einsum("ij,ij->i", x - r0, n0)

    def fun(y):
        r, n = evaluate(y[..., 0], y[..., 1])
        return r + y[..., 2:3] * n - x

    span = np.array([u_hi - u_lo, v_hi - v_lo, np.inf])
    res = solve_batched(fun, np.column_stack([uv, d0]), tol=tol, max_iter=max_iter, max_step=0.25 * span)
    if strict and not res.converged.all():
        bad = int(np.argmax(~res.converged))
        raise ConvergenceError(f"foot point of query point {bad} ({x[bad].tolist()} mm) not found",
                               iterations=res.iterations, residual=float(np.max(res.residual[~res.converged])),
                               last=res.x)
    u, v, d = res.x[:, 0], res.x[:, 1], res.x[:, 2]
    r, n = evaluate(u, v)
    inside = (u >= u_lo) & (u <= u_hi) & (v >= v_lo) & (v <= v_hi)
    return FootPoints(u=u, v=v, points=r, normals=n, distance=d, inside=inside, converged=res.converged)


@dataclass(frozen=True)
class ConjugacyReport:
    """Deviation of an envelope from a candidate mating surface.

    Attributes
    ----------
    max_distance : float, mm
        Largest |point-to-surface distance|.
    rms_distance : float, mm
    max_normal_mismatch : float
        Largest 1 - |n_env . n_cand| at the foot points (-).
    invariant_spread : float or None
        max - min of the surface invariant over the envelope points (None when no invariant was given).
    n_points : int
    n_outside : int
        Foot points outside the candidate's parameter bounds (the candidate does not cover the envelope there).
    distance, normal_mismatch : (n,) float
        Per-point values (mm, -).
    distance_tol, normal_tol, invariant_tol : float
        Thresholds of :attr:`is_conjugate` (mm, -, -).
    """

    max_distance: float
    rms_distance: float
    max_normal_mismatch: float
    invariant_spread: float | None
    n_points: int
    n_outside: int
    distance: np.ndarray
    normal_mismatch: np.ndarray
    distance_tol: float
    normal_tol: float
    invariant_tol: float

    @property
    def is_conjugate(self) -> bool:
        """True when every measure is within its tolerance and the candidate covers every point."""
        ok = self.max_distance <= self.distance_tol and self.max_normal_mismatch <= self.normal_tol
        if self.invariant_spread is not None:
            ok = ok and self.invariant_spread <= self.invariant_tol
        return bool(ok and self.n_outside == 0)

    def summary(self) -> str:
        """One-paragraph text report."""
        inv = "n/a" if self.invariant_spread is None else f"{self.invariant_spread:.3e}"
        verdict = "CONJUGATE" if self.is_conjugate else "NOT CONJUGATE"
        return (f"{verdict}: {self.n_points} points, max distance {self.max_distance:.3e} mm "
                f"(rms {self.rms_distance:.3e} mm, tol {self.distance_tol:.1e}), max normal mismatch "
                f"{self.max_normal_mismatch:.3e} (tol {self.normal_tol:.1e}), invariant spread {inv} "
                f"(tol {self.invariant_tol:.1e}), {self.n_outside} foot points outside the candidate domain")


def compare_conjugate(points, normals, candidate, bounds, *, invariant: Callable | None = None,
                      distance_tol: float = 1e-6, normal_tol: float = 1e-9, invariant_tol: float = 1e-9,
                      samples=(41, 41), uv0=None, tol: float = TOL.newton_abs, fd_step: float = 1e-3,
                      orientation: float = 1.0) -> ConjugacyReport:
    """Report how far an envelope is from a candidate mating surface.

    Parameters
    ----------
    points, normals : (..., 3) array_like, mm and -
        Envelope points and normals (e.g. ``EnvelopeResult.points`` / ``.normals``), candidate's frame.
    candidate : callable
        ``candidate(u, v) -> (points, normals)`` (or points only).
    bounds : ((u_min, u_max), (v_min, v_max))
        Candidate parameter box (start values, coverage check).
    invariant : callable, optional
        ``invariant(points (n, 3)) -> (n,)``, constant on the candidate family member; its spread is reported.
    distance_tol : float, mm
    normal_tol, invariant_tol : float
        Thresholds of :attr:`ConjugacyReport.is_conjugate`.
    samples, uv0, tol, fd_step, orientation
        Passed to :func:`nearest_points` (``tol`` in mm bounds the accuracy of the measured distance).

    Returns
    -------
    ConjugacyReport
    """
    x = np.asarray(points, float).reshape(-1, 3)
    ne = np.asarray(normals, float).reshape(-1, 3)
    foot = nearest_points(x, candidate, bounds, samples=samples, uv0=uv0, tol=tol, fd_step=fd_step,
                          orientation=orientation)
    mismatch = 1.0 - np.abs(np.einsum("ij,ij->i", ne, foot.normals))
    dist = np.abs(foot.distance)
    spread = None
    if invariant is not None:
        vals = np.asarray(invariant(x), float)
        spread = float(np.max(vals) - np.min(vals))
    return ConjugacyReport(
        max_distance=float(dist.max()), rms_distance=float(np.sqrt(np.mean(dist**2))),
        max_normal_mismatch=float(mismatch.max()), invariant_spread=spread, n_points=int(x.shape[0]),
        n_outside=int(np.count_nonzero(~foot.inside)), distance=dist, normal_mismatch=mismatch,
        distance_tol=float(distance_tol), normal_tol=float(normal_tol), invariant_tol=float(invariant_tol),
    )


def logspiral_invariant(points, base_cone_angle: float, spiral_angle: float, psi_sign: float = 1.0):
    """ln(rho0 / 1 mm) of the seed-000 flank (base cone, spiral angle) through each point.

    ln rho - phi sin(delta) cot(beta) is constant on one log-spiral flank (docs/theory/logspiral.md, Eq. (S2) and
    docs/theory/gearing.md, Eq. (M8)). The value is defined
    modulo 2 pi sin(delta) |cot(beta)| (turns of the spiral); it is returned reduced to within half a period of its
    median, so its spread measures how far the points are from a single flank.

    Parameters
    ----------
    points : (..., 3) array_like, mm
        Points in the flank's member frame.
    base_cone_angle, spiral_angle : float, rad
        delta and beta of the candidate flank.
    psi_sign : {+1, -1}
        Branch of the flank (sign of psi).

    Returns
    -------
    (...) float
    """
    pts = np.asarray(points, float)
    inv = _m.logspiral_invariant(pts, base_cone_angle, spiral_angle, psi_sign)[0]
    period = 2 * np.pi * np.sin(base_cone_angle) / abs(np.tan(spiral_angle))
    return _m.reduce_periodic(inv, period)
