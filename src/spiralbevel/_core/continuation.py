"""Pseudo-arclength continuation of a homotopy H(x, t) = 0 from t = 0 to t = 1.

A plain continuation steps the homotopy parameter t and solves H(x, t) = 0 for x at each step; it stalls where the
solution curve turns back in t (a turning point, dH/dx singular), because past it no nearby solution exists for a
larger t. Pseudo-arclength continuation (Keller 1977; Allgower & Georg, *Introduction to Numerical Continuation
Methods*, SIAM 2003, Ch. 2 and 3) instead follows the curve c(s) = (x, t)(s) by its arclength s: Euler predictor
along the unit tangent (the null vector of the n x (n+1) Jacobian [H_x, H_t]), and a Newton corrector on the curve
by minimum-norm steps (Moore-Penrose / Gauss-Newton), which pass a turning point because [H_x, H_t] keeps full rank
there even where H_x does not. The curve may go back in t and return: the solution at t = 1 is found where the
curve crosses it.

Unknowns are compared in scaled units x / scale (so that one unit of each is a comparable change); the curve's
direction at the start is the one in which t grows.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .newton import fd_jacobian

__all__ = ["ArclengthResult", "arclength_continuation"]


@dataclass
class ArclengthResult:
    """Outcome of :func:`arclength_continuation`.

    Attributes
    ----------
    x : (n,) float
        Last point of the curve (the solution at t = 1 when ``converged``).
    t : float
        Homotopy parameter of ``x``.
    converged : bool
        True when the curve reached t = 1 and H(x, 1) is below the final tolerance.
    residual : float
        Max-norm of H at (x, t).
    steps : int
        Accepted predictor-corrector steps.
    turning_points : int
        Sign changes of dt/ds along the path (turning points passed).
    path : (m, n + 1) float
        Accepted points (x, t) along the curve, the start first.
    """

    x: np.ndarray
    t: float
    converged: bool
    residual: float
    steps: int
    turning_points: int
    path: np.ndarray


def _tangent(J, previous):
    """Unit null vector (n+1,) of the n x (n+1) Jacobian, oriented along ``previous`` (or with dt > 0)."""
    _, s, vt = np.linalg.svd(J)
    tau = vt[-1]
    if previous is None:
        return tau if tau[-1] > 0 else -tau
    return tau if tau @ previous > 0 else -tau


def _correct(fun, y, tol, max_iter):
    """Gauss-Newton (minimum-norm) corrector of ``fun(y) = 0`` (n equations, n+1 unknowns): (y, residual, ok, J)."""
    f = fun(y)
    res = float(np.max(np.abs(f)))
    J = None
    for _ in range(max_iter):
        if res < tol:
            return y, res, True, J
        J = fd_jacobian(fun, y, f)
        if not np.all(np.isfinite(J)):
            return y, res, False, None
        dy = np.linalg.lstsq(J, -f, rcond=None)[0]
        y = y + dy
        f = fun(y)
        res_new = float(np.max(np.abs(f)))
        if not np.isfinite(res_new) or res_new > 2.0 * res:    # diverging: the step was too long
            return y, res_new, False, None
        res = res_new
    return y, res, res < tol, J


def arclength_continuation(fun, x0, scale=None, *, tol=1e-9, path_tol=None, h0=0.05, h_max=0.5, h_min=1e-5,
                           max_steps=400, max_corrector=8, t_min=-1.0):
    """Follow H(x, t) = 0 from (x0, 0) to t = 1 by pseudo-arclength continuation.

    Parameters
    ----------
    fun : callable
        ``fun(x (n,), t float) -> (n,)`` residuals H; it must vanish at (x0, 0). A failed evaluation should return a
        large finite vector (the step is then shortened).
    x0 : (n,) float
        Solution at t = 0.
    scale : (n,) float, optional
        Typical size of a change of each unknown (arclength is measured in x / scale and t); default 1.
    tol : float
        Final tolerance on max |H(x, 1)|.
    path_tol : float, optional
        Corrector tolerance along the path (default ``100 tol``).
    h0, h_max, h_min : float
        First, largest and smallest arclength step (scaled units).
    max_steps : int
        Cap on accepted steps.
    max_corrector : int
        Corrector iterations per step; a step whose corrector needs more is halved.
    t_min : float
        Give up when the curve goes back below this t (it turned away from t = 1 for good).

    Returns
    -------
    ArclengthResult
        Never raises; ``converged`` says whether t = 1 was reached.
    """
    x0 = np.asarray(x0, float)
    n = x0.size
    d = np.ones(n) if scale is None else np.asarray(scale, float)
    path_tol = 100.0 * tol if path_tol is None else float(path_tol)

    def g(y):   # y = (x / d, t)
        return np.asarray(fun(y[:n] * d, y[n]), float)

    y = np.append(x0 / d, 0.0)
    f0 = g(y)
    path, turns, steps, h = [y.copy()], 0, 0, float(h0)
    tau = _tangent(fd_jacobian(g, y, f0), None)
    res = float(np.max(np.abs(f0)))
    while steps < max_steps:
        y_new, res_new, ok, J = _correct(g, y + h * tau, path_tol, max_corrector)
        tau_new = None
        if ok:
            tau_new = _tangent(J if J is not None else fd_jacobian(g, y_new), tau)
            # the tangent must not swing by more than ~60 deg in one step (else the step jumped to another branch)
            chord = y_new - y
            ok = tau_new @ tau > 0.5 and chord @ tau > 0.0
        if not ok:
            h *= 0.5
            if h < h_min:
                break
            continue
        if y[n] < 1.0 <= y_new[n]:
            # the curve crosses t = 1 between y and y_new: solve H(x, 1) = 0 from the interpolated point
            a = (1.0 - y[n]) / (y_new[n] - y[n])
            z, res_z, ok_z = _solve_at_one(g, (1.0 - a) * y[:n] + a * y_new[:n], tol, max_corrector)
            if not ok_z:     # too coarse a step to land on t = 1: a shorter one
                h *= 0.5
                if h < h_min:
                    break
                continue
            path.append(np.append(z, 1.0))
            return ArclengthResult(z * d, 1.0, True, res_z, steps + 1, turns, np.array(path) * np.append(d, 1.0))
        steps += 1
        if np.sign(tau_new[n]) != np.sign(tau[n]) and tau[n] != 0.0:
            turns += 1
        y, tau, res = y_new, tau_new, res_new
        path.append(y.copy())
        if y[n] < t_min:
            break
        h = min(h_max, 1.5 * h)
    return ArclengthResult(y[:n] * d, float(y[n]), False, res, steps, turns, np.array(path) * np.append(d, 1.0))


def _solve_at_one(g, z, tol, max_iter):
    """Newton in x at t = 1 (square system): (z, residual, converged)."""
    def f(v):
        return g(np.append(v, 1.0))

    fz = f(z)
    res = float(np.max(np.abs(fz)))
    for _ in range(max_iter + 4):
        if res < tol:
            return z, res, True
        J = fd_jacobian(f, z, fz)
        try:
            dz = np.linalg.solve(J, -fz)
        except np.linalg.LinAlgError:
            dz = np.linalg.lstsq(J, -fz, rcond=None)[0]
        z = z + dz
        fz = f(z)
        res = float(np.max(np.abs(fz)))
    return z, res, res < tol
