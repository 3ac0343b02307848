"""Small dense linear solves and copies inside compiled kernels.

One Gaussian elimination with partial pivoting serves the compiled Newton iterations of the settings fit
(``settings_fit``, 7 x 7) and of multi-point control (``multipoint_newton``, 6 x 6). :func:`copy1` and :func:`copy2`
copy a row or a block between arrays of the same shape: ``dst[i] = src[t]`` between arrays would compile numba's
broadcasting set-item with its shape-mismatch message, about 1.5 s per number of dimensions on a cold start (see
``_core/jit.py``).
"""

from __future__ import annotations

import math

from .jit import kernel


@kernel
def lu_solve(J, b, dx):
    """dx = J^-1 b by Gaussian elimination with partial pivoting (J (n, n), b (n,) overwritten); False if J is singular.

    Parameters
    ----------
    J : (n, n) float64
        The matrix; overwritten by its upper triangular factor.
    b : (n,) float64
        The right-hand side; overwritten.
    dx : (n,) float64
        Receives the solution.

    Returns
    -------
    bool
        False where a pivot is zero or not finite (dx is then not set).
    """
    n = b.size
    for k in range(n):
        p = k
        for i in range(k + 1, n):
            if abs(J[i, k]) > abs(J[p, k]):
                p = i
        if J[p, k] == 0.0 or not math.isfinite(J[p, k]):
            return False
        if p != k:
            for j in range(n):
                J[k, j], J[p, j] = J[p, j], J[k, j]
            b[k], b[p] = b[p], b[k]
        for i in range(k + 1, n):
            m = J[i, k] / J[k, k]
            for j in range(k, n):
                J[i, j] -= m * J[k, j]
            b[i] -= m * b[k]
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= J[i, j] * dx[j]
        dx[i] = s / J[i, i]
    return True


@kernel(inline="always")   # a loop: cheaper typed at each call site than compiled alone
def copy1(dst, src):
    """dst[:] = src for (n,) arrays of the same length (a loop: see the module docstring)."""
    for i in range(dst.shape[0]):
        dst[i] = src[i]


@kernel(inline="always")   # a loop: cheaper typed at each call site than compiled alone
def copy2(dst, src):
    """dst[:, :] = src for (n, k) arrays of the same shape (a loop: see the module docstring)."""
    for i in range(dst.shape[0]):
        for j in range(dst.shape[1]):
            dst[i, j] = src[i, j]
