"""Kernels of loaded tooth contact analysis (LTCA): the load-distribution complementarity problem and the
Boussinesq (Love) half-space influence coefficients.

Pure functions on float64 arrays; mm, N, N mm, rad. No validation here (see ``spiralbevel.meshing.ltca``).

Load distribution, seed 001 Eq. (18) in the clean form of docs/theory/ltca.md, Eqs. (L1)-(L4)::

    C F + w - d = dtheta h,   h . F = T,   F >= 0,  d >= 0,  F . d = 0

is exactly the KKT system of the strictly convex quadratic programme (C symmetric positive definite)

    minimize 1/2 F^T C F + w^T F   subject to   F >= 0,  h^T F = T

with dtheta the multiplier of the torque constraint and d the multipliers of the bounds. Its solution is unique, so
any exact QP method gives the LTCA answer. Two are used: a primal-dual active-set (semismooth Newton) iteration that
converges in a few steps from a warm start, and, should it cycle, the primal active-set method (Nocedal & Wright,
Numerical Optimization, 2nd ed., Alg. 16.3), which terminates finitely for a strictly convex QP.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import cho_factor, cho_solve

__all__ = [
    "rect_integral",
    "halfspace_matrix",
    "eqp",
    "pdas",
    "primal_active_set",
]


# --------------------------------------------------------------------------------------------- half-space (Love)
def _corner(X, Y):
    """Antiderivative G(X, Y) of 1/sqrt(X^2 + Y^2) (d^2 G / dX dY = 1/r), up to terms in X or Y alone.

    G = |X| asinh(Y/X) + |Y| asinh(X/Y) with the removable limits G -> |Y| asinh(X/Y) at X = 0 (and symmetric).
    """
    X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
    ax, ay = np.abs(X), np.abs(Y)
    with np.errstate(divide="ignore", invalid="ignore"):
        gx = np.where(ax > 0, ax * np.arcsinh(Y / np.where(ax > 0, X, 1.0)), 0.0)
        gy = np.where(ay > 0, ay * np.arcsinh(X / np.where(ay > 0, Y, 1.0)), 0.0)
    return gx + gy


def rect_integral(x, y, a, b):
    """Integral of 1/r over the rectangle |x'| <= a, |y'| <= b seen from the point (x, y) [mm].

    Love (1929); Johnson, Contact Mechanics, Eq. (3.25): the surface displacement of an elastic half-space under a
    uniform pressure p on that rectangle is u_z = p (1 - nu^2) / (pi E) * rect_integral(x, y, a, b).
    """
    return (_corner(x + a, y + b) - _corner(x + a, y - b) - _corner(x - a, y + b) + _corner(x - a, y - b))


def halfspace_matrix(xy, dx, dy, estar):
    """Influence matrix C_ij [mm/N] of uniform-pressure rectangular cells on two elastic half-spaces.

    Parameters
    ----------
    xy : (n, 2) float, mm
        Cell centres in the common tangent plane.
    dx, dy : float, mm
        Cell sizes (each cell carries the force F_j as the pressure F_j / (dx dy)).
    estar : float, N/mm^2
        Contact modulus E* with 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.

    Returns
    -------
    (n, n) float, mm/N
        Normal approach of the two surfaces at cell centre i per unit force on cell j.
    """
    xy = np.asarray(xy, float)
    rx = xy[:, None, 0] - xy[None, :, 0]
    ry = xy[:, None, 1] - xy[None, :, 1]
    return rect_integral(rx, ry, 0.5 * dx, 0.5 * dy) / (np.pi * estar * dx * dy)


# ----------------------------------------------------------------------------------------- load distribution
def eqp(C, w, h, T, S):
    """Equality-constrained subproblem on the free set ``S``: C_SS F_S - lam h_S = -w_S, h_S . F_S = T.

    Returns ``(F, lam)`` with F (n,) zero off S. Raises ``scipy.linalg.LinAlgError`` if C_SS is not positive definite.
    Closed form by one Cholesky factorization: F_S = C_SS^-1 (lam h_S - w_S), lam = (T + h^T C^-1 w)/(h^T C^-1 h).
    """
    S = np.flatnonzero(S) if np.asarray(S).dtype == bool else np.asarray(S, int)
    cf = cho_factor(C[np.ix_(S, S)], lower=True, check_finite=False)
    rhs = np.stack([h[S], w[S]], axis=1)
    sol = cho_solve(cf, rhs, check_finite=False)
    ch, cw = sol[:, 0], sol[:, 1]
    lam = (T + h[S] @ cw) / (h[S] @ ch)
    F = np.zeros(len(w))
    F[S] = lam * ch - cw
    return F, lam


def _gaps(C, w, h, F, lam):
    return C @ F + w - lam * h


def pdas(C, w, h, T, active, max_iter=40, tol=1e-13):
    """Primal-dual active-set (semismooth Newton) iteration for the load distribution.

    Parameters
    ----------
    active : (n,) bool
        Starting guess of the loaded set (warm start), not empty.

    Returns
    -------
    (F, d, lam, active, iterations, ok)
        ``ok`` is False if the iteration cycled or hit ``max_iter``; the caller then uses :func:`primal_active_set`.
    """
    A = np.asarray(active, bool).copy()
    seen = set()
    hmax = np.max(np.abs(h))
    for it in range(1, max_iter + 1):
        F, lam = eqp(C, w, h, T, A)
        d = _gaps(C, w, h, F, lam)
        d[A] = 0.0
        dtol = tol * (np.max(np.abs(w)) + abs(lam) * hmax + np.max(np.abs(C @ F)))
        newA = (A & (F > 0.0)) | (~A & (d < -dtol))
        if np.array_equal(newA, A):
            return F, np.maximum(d, 0.0), lam, A, it, True
        key = newA.tobytes()
        if key in seen or not newA.any():
            return F, d, lam, A, it, False
        seen.add(key)
        A = newA
    return F, d, lam, A, max_iter, False


def primal_active_set(C, w, h, T, F0=None, max_iter=None, tol=1e-13):
    """Primal active-set method for min 1/2 F'CF + w'F s.t. F >= 0, h'F = T (Nocedal & Wright Alg. 16.3).

    Finite termination for C positive definite: every subproblem minimum reached has a strictly lower objective, so
    no free set repeats. Releases one bound at a time (the most negative multiplier d_j).

    Parameters
    ----------
    F0 : (n,) float, optional
        A feasible start (F0 >= 0, h'F0 = T); default: the whole torque on the point of smallest w_i/h_i.

    Returns
    -------
    (F, d, lam, active, iterations)
    """
    n = len(w)
    if F0 is None:
        k = int(np.argmin(w / h))
        F = np.zeros(n)
        F[k] = T / h[k]
    else:
        F = np.array(F0, float)
    S = F > 0.0
    max_iter = max_iter or 20 * n + 50
    wscale = max(np.max(np.abs(w)), 1e-300)
    for it in range(1, max_iter + 1):
        Fs, lam = eqp(C, w, h, T, S)
        p = Fs - F
        neg = S & (Fs < 0.0)
        if not neg.any():
            F = np.where(S, Fs, 0.0)
            d = _gaps(C, w, h, F, lam)
            d[S] = 0.0
            dtol = tol * (wscale + abs(lam) * np.max(np.abs(h)) + np.max(np.abs(C @ F)))
            if d.min() >= -dtol:
                return F, np.maximum(d, 0.0), lam, S, it
            S[int(np.argmin(d))] = True
            continue
        ratios = np.full(n, np.inf)
        ratios[neg] = F[neg] / (-p[neg])
        j = int(np.argmin(ratios))
        alpha = min(1.0, ratios[j])
        F = F + alpha * p
        F[j] = 0.0
        F[S & (F <= 0.0)] = 0.0
        S = S & (F > 0.0)
        if not S.any():  # cannot happen with h > 0 and T > 0; keep a safe restart
            k = int(np.argmin(w / h))
            F[k] = T / h[k]
            S[k] = True
    raise RuntimeError("primal active set: iteration cap")
