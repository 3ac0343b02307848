"""The Newton step of the compiled TCA: dx = -J^+ F of one 5 x 5 (or 6 x 5, anchored) system, and the line-contact
test of a batch of systems.

:func:`step`: column equilibration; LU with partial pivoting where |det| > 5^2.5 rcond proves s_min / s_max > rcond
(then the pseudo-inverse is the inverse), else the minimum-norm SVD step (line contact, anchored systems; a one-sided
Jacobi SVD, which compiles in a fraction of the time of numba's LAPACK binding); NaN for a non-finite system.
:func:`singular_rows`: s_min / s_max below a threshold, by certificates (QR diagonal, determinant) and the SVD where
they do not decide. Compiled callees of :mod:`spiralbevel._core.tca_newton` and of the edge-contact kernels
(:mod:`spiralbevel._core.tca_edge`); Python reaches them through :mod:`spiralbevel._core.tca_solve`.
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel

__all__ = ["all_finite", "max_abs", "step", "singular_rows"]

#: |det| of a matrix with unit columns bounds its singular values: s_min / s_max >= |det| / s_max^5 and
#: s_max <= sqrt(5) (Frobenius), so |det| > 5^2.5 * rcond guarantees s_min / s_max > rcond.
_DET_BOUND = 5.0 ** 2.5


@kernel(inline="always")   # a few statements: cheaper typed at each call site than compiled alone
def all_finite(a):
    for v in a.flat:
        if not math.isfinite(v):
            return False
    return True


@kernel(inline="always")   # one call site: step
def _lu_solve5(A, b, rcond, dx):
    """Solve A dx = b (5 x 5, unit columns) by LU with partial pivoting if |det A| > 5^2.5 rcond; False otherwise."""
    n = 5
    U = A.copy()
    y = b.copy()
    det = 1.0
    for k in range(n):
        p = k
        big = abs(U[k, k])
        for i in range(k + 1, n):
            if abs(U[i, k]) > big:
                big = abs(U[i, k])
                p = i
        if p != k:
            det = -det
            for j in range(n):
                U[k, j], U[p, j] = U[p, j], U[k, j]
            y[k], y[p] = y[p], y[k]
        piv = U[k, k]
        det *= piv
        if piv == 0.0:
            return False
        for i in range(k + 1, n):
            f = U[i, k] / piv
            U[i, k] = f
            for j in range(k + 1, n):
                U[i, j] -= f * U[k, j]
            y[i] -= f * y[k]
    if not abs(det) > _DET_BOUND * rcond:
        return False
    for k in range(n - 1, -1, -1):
        acc = y[k]
        for j in range(k + 1, n):
            acc -= U[k, j] * dx[j]
        dx[k] = acc / U[k, k]
    return True


@kernel
def _equilibrate(J):
    k, n = J.shape
    cn = np.empty(n)
    Js = np.empty((k, n))
    for j in range(n):
        acc = 0.0
        for i in range(k):
            acc += J[i, j] * J[i, j]
        c = math.sqrt(acc)
        cn[j] = c if c > 0 else 1.0
        for i in range(k):
            Js[i, j] = J[i, j] / cn[j]
    return Js, cn


@kernel
def step(J, F, rcond, dx):
    """Newton step ``dx (5,)`` = -J^+ F of one system ``J (k, 5)``, ``F (k,)`` (see the module docstring)."""
    k = J.shape[0]
    if not (all_finite(J) and all_finite(F)):
        for j in range(5):
            dx[j] = math.nan
        return
    Js, cn = _equilibrate(J)
    if k == 5:
        b = np.empty(5)
        for i in range(5):
            b[i] = -F[i]
        if _lu_solve5(Js, b, rcond, dx):
            for j in range(5):
                dx[j] /= cn[j]
            return
    # minimum-norm least-squares step with singular values below rcond s_max discarded (contact line)
    A, cn2 = _equilibrate(Js)
    V = _jacobi_svd(A)
    smax = 0.0
    sv = np.empty(5)
    for a in range(5):
        acc = 0.0
        for i in range(k):
            acc += A[i, a] * A[i, a]
        sv[a] = math.sqrt(acc)
        smax = max(smax, sv[a])
    y = np.zeros(5)
    for a in range(5):
        if sv[a] > rcond * smax:
            acc = 0.0
            for i in range(k):
                acc -= A[i, a] * F[i]
            y[a] = acc / (sv[a] * sv[a])  # column a of A is s_a u_a
    for j in range(5):
        acc = 0.0
        for a in range(5):
            acc += V[j, a] * y[a]
        dx[j] = acc / cn2[j] / cn[j]


@kernel
def _jacobi_svd(A):
    """One-sided Jacobi SVD (Hestenes) of ``A (k, 5)``, k >= 5, in place: on return the columns of A are s_a u_a
    (mutually orthogonal) and ``V (5, 5)`` is returned, A_in = A_out V^T. Rotations until every pair of columns is
    orthogonal to 1e-15 relative (high relative accuracy; a few sweeps for 5 columns)."""
    k, n = A.shape
    V = np.zeros((n, n))   # the identity by a loop: np.eye compiles numba's generic implementation (_core/jit.py)
    for i in range(n):
        V[i, i] = 1.0
    for _ in range(60):
        rotated = False
        for p in range(n - 1):
            for q in range(p + 1, n):
                alpha = 0.0
                beta = 0.0
                gamma = 0.0
                for i in range(k):
                    alpha += A[i, p] * A[i, p]
                    beta += A[i, q] * A[i, q]
                    gamma += A[i, p] * A[i, q]
                if gamma == 0.0 or abs(gamma) <= 1e-15 * math.sqrt(alpha * beta):
                    continue
                rotated = True
                zeta = (beta - alpha) / (2.0 * gamma)
                t = (1.0 if zeta >= 0 else -1.0) / (abs(zeta) + math.sqrt(1.0 + zeta * zeta))
                c = 1.0 / math.sqrt(1.0 + t * t)
                s = c * t
                for i in range(k):
                    up, uq = A[i, p], A[i, q]
                    A[i, p] = c * up - s * uq
                    A[i, q] = s * up + c * uq
                for i in range(n):
                    vp, vq = V[i, p], V[i, q]
                    V[i, p] = c * vp - s * vq
                    V[i, q] = s * vp + c * vq
        if not rotated:
            break
    return V





@kernel(inline="always")   # a few statements (see all_finite)
def max_abs(a):
    m = 0.0
    for v in a:
        if abs(v) > m:
            m = abs(v)
    return m



@kernel(inline="always")   # one call site: _singular
def _qr_diag(A, d):
    """|R_kk| (k = 0..4) of a Householder QR of ``A (k, 5)`` (overwritten) into ``d (5,)``."""
    k, n = A.shape
    for j in range(n):
        nrm = 0.0
        for i in range(j, k):
            nrm += A[i, j] * A[i, j]
        nrm = math.sqrt(nrm)
        d[j] = nrm
        if nrm == 0.0:
            continue
        alpha = -nrm if A[j, j] >= 0 else nrm
        A[j, j] -= alpha  # v = a - alpha e_j, stored in column j
        vv = 0.0
        for i in range(j, k):
            vv += A[i, j] * A[i, j]
        if vv == 0.0:
            continue
        for c in range(j + 1, n):
            dot = 0.0
            for i in range(j, k):
                dot += A[i, j] * A[i, c]
            f = 2.0 * dot / vv
            for i in range(j, k):
                A[i, c] -= f * A[i, j]




@kernel(inline="always")   # one call site: tca_newton.newton_batch
def singular_rows(J, tol, out):
    """``out[i]``: whether s_min / s_max of the column-equilibrated ``J[i] (k, 5)`` is below ``tol`` (line contact;
    see :func:`singular_batch`)."""
    d = np.empty(5)
    for i in range(J.shape[0]):
        out[i] = False
        if not all_finite(J[i]):
            continue
        A, _ = _equilibrate(J[i])
        B = A.copy()
        _qr_diag(B, d)
        dmin, prod = d[0], 1.0
        for j in range(5):
            dmin = min(dmin, d[j])
            prod *= d[j]
        if dmin < tol:
            out[i] = True
        elif not prod > _DET_BOUND * tol:
            _jacobi_svd(A)
            smin, smax = math.inf, 0.0
            for a in range(5):
                acc = 0.0
                for r in range(A.shape[0]):
                    acc += A[r, a] * A[r, a]
                s = math.sqrt(acc)
                smin, smax = min(smin, s), max(smax, s)
            out[i] = smin < tol * smax

