"""Batched Newton solver: many small independent nonlinear systems solved at once.

Each system has ``n`` unknowns and ``n`` equations; the batch shape is arbitrary. The Jacobian is either supplied
(``(..., n, n)``) or formed by vectorized forward differences (n extra residual calls per iteration, all points at
once). Steps are solved with ``numpy.linalg.solve`` on the whole stack.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class NewtonResult:
    """Outcome of :func:`solve_batched`.

    Attributes
    ----------
    x : (..., n) float
        Final iterates.
    converged : (...) bool
        Per-system convergence flag.
    residual : (...) float
        Max-norm of the final residual per system.
    iterations : int
        Iterations performed.
    """

    x: np.ndarray
    converged: np.ndarray
    residual: np.ndarray
    iterations: int


def fd_jacobian(fun, x, f0=None, rel_step=1e-7):
    """Forward-difference Jacobian of ``fun`` at ``x (..., n)``, shape (..., n, n) (J[..., i, j] = dF_i/dx_j)."""
    x = np.asarray(x, dtype=float)
    if f0 is None:
        f0 = fun(x)
    n = x.shape[-1]
    J = np.empty(x.shape[:-1] + (f0.shape[-1], n))
    for j in range(n):
        h = rel_step * np.maximum(1.0, np.abs(x[..., j]))
        xp = x.copy()
        xp[..., j] += h
        J[..., :, j] = (fun(xp) - f0) / h[..., None]
    return J


def solve_batched(fun, x0, jac=None, tol=1e-12, max_iter=50, max_step=None):
    """Solve ``fun(x) = 0`` for a batch of independent systems by Newton's method.

    Parameters
    ----------
    fun : callable
        ``fun(x (..., n)) -> (..., n)`` residuals, vectorized over the batch.
    x0 : (..., n) float
        Starting points.
    jac : callable, optional
        ``jac(x) -> (..., n, n)``; forward differences when omitted.
    tol : float
        Convergence when the max-norm of the residual is below ``tol`` (in the residual's units).
    max_iter : int
        Iteration cap.
    max_step : (n,) float, optional
        Cap on the absolute Newton step per unknown (damping far from the root).

    Returns
    -------
    NewtonResult
        Never raises; the caller decides what non-convergence means (see ``ConvergenceError``).
    """
    x = np.array(x0, dtype=float, copy=True)
    f = fun(x)
    res = np.max(np.abs(f), axis=-1)
    it = 0
    active = ~(res < tol)
    while np.any(active) and it < max_iter:
        it += 1
        J = jac(x) if jac is not None else fd_jacobian(fun, x, f)
        with np.errstate(all="ignore"):
            try:
                dx = np.linalg.solve(J, -f[..., None])[..., 0]
            except np.linalg.LinAlgError:
                dx = np.empty_like(x)
                flatJ = J.reshape(-1, *J.shape[-2:])
                flatf = f.reshape(-1, f.shape[-1])
                out = dx.reshape(-1, x.shape[-1])
                for i in range(flatJ.shape[0]):
                    out[i] = np.linalg.lstsq(flatJ[i], -flatf[i], rcond=None)[0]
        dx = np.where(np.isfinite(dx), dx, 0.0)
        if max_step is not None:
            scale = np.max(np.abs(dx) / np.asarray(max_step, dtype=float), axis=-1, keepdims=True)
            dx = dx / np.maximum(scale, 1.0)
        x = np.where(active[..., None], x + dx, x)
        f = fun(x)
        res = np.max(np.abs(f), axis=-1)
        active = ~(res < tol)
    return NewtonResult(x=x, converged=res < tol, residual=res, iterations=it)
