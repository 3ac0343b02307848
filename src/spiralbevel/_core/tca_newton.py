"""Compiled batched Newton of tooth contact analysis: system assembly, the 5 x 5 step, the give-up rule.

Same equations and unknowns as :mod:`spiralbevel._core.tca` (seed 001 Eq. (16), docs/theory/tca.md, Eq. (T5)):
x = (q1, q2, phi2), F in mm, surface data stacked per system as ``S (3, 6)`` with the columns (r, n, r_q0, r_q1,
n_q0, n_q1) in the member frame (:func:`spiralbevel._core.tca_batch.stack_state`). Every rule here is compiled
(:mod:`spiralbevel._core.jit`) and has one implementation:

* :func:`assemble` -- F (k,) and J (k, 5) of one system (k = 6 with an anchor equation x_j = value);
* :func:`step` -- the Newton step dx = -J^+ F: column equilibration; LU with partial pivoting where
  |det| > 5^2.5 rcond proves s_min / s_max > rcond (then the pseudo-inverse is the inverse), else the minimum-norm
  SVD step (line contact, anchored systems; one-sided Jacobi SVD, which compiles in a fraction of the time of
  numba's LAPACK binding); NaN for a non-finite system;
* the batched iteration (:func:`start`, :func:`propose`, :func:`accept`): ``propose`` gives the trial points of the
  active systems, the surfaces are evaluated there and the systems assembled, ``accept`` applies the rules: a trial
  that leaves the surfaces (non-finite F or J) is retried with the step halved, up to ``halvings`` times; a system
  whose residual has not halved its best value for ``patience`` consecutive iterations is given up (Newton cycling
  or wandering: no solution near the start); converged when max|F| < tol.

Systems are independent: the batched iteration equals a per-system one, and ``iterations`` is the largest number of
iterations any system took.

Python reaches all of it through one kernel, :func:`newton_batch`, with one argument signature: the operation is a
value read from an integer array (``iv[MODE]``), not a kernel of its own. numba links the IR of every callee into the
module of each compiled function that reaches it, and LLVM optimises it again there: one entry point instead of nine
optimises ``step`` (with its LU and SVD) and ``assemble`` once more here, not once per entry point, and compiles one
function instead of nine (``_core/jit.py``; ``bench/bench_compile.py --ir``). The Python functions below allocate
the arrays and call it:

* :func:`newton_jets` -- the whole iteration in compiled code for surfaces with compiled jets
  (:mod:`spiralbevel._core.jets`);
* :class:`Iteration` -- the same iteration as reverse communication for surfaces without one: the caller evaluates
  the surfaces at the trial points (by numpy, :meth:`spiralbevel.meshing.contact_problem.ContactProblem.newton`);
* :func:`step_batch`, :func:`tangent_batch`, :func:`singular_batch` -- the step, the path tangent and the
  line-contact test of a batch of systems.

Constants of an assembly (:func:`spiralbevel._core.tca_batch.assembly_constants`): d = o1 - o2 (3,) mm,
M2 = [B2; [a2]x B2] (6, 3), L mm the length scale of the normal equations.
"""

from __future__ import annotations

import math

import numpy as np

from .jets import surface_jet
from .jit import kernel
from .linalg import copy1, copy2

__all__ = [
    "assemble",
    "basis_rows",
    "step",
    "newton_batch",
    "newton_jets",
    "Iteration",
    "step_batch",
    "tangent_batch",
    "singular_batch",
]

#: |det| of a matrix with unit columns bounds its singular values: s_min / s_max >= |det| / s_max^5 and
#: s_max <= sqrt(5) (Frobenius), so |det| > 5^2.5 * rcond guarantees s_min / s_max > rcond.
_DET_BOUND = 5.0 ** 2.5


@kernel
def basis_rows(S2, c2, s2, M2, E):
    """Rows e_1, e_2 of ``E (2, 3)``: unit vectors orthogonal to the gear's fixed-frame normal and to each other."""
    nx = c2 * S2[0, 1] - s2 * S2[1, 1]
    ny = s2 * S2[0, 1] + c2 * S2[1, 1]
    nz = S2[2, 1]
    n0 = M2[0, 0] * nx + M2[0, 1] * ny + M2[0, 2] * nz
    n1 = M2[1, 0] * nx + M2[1, 1] * ny + M2[1, 2] * nz
    n2 = M2[2, 0] * nx + M2[2, 1] * ny + M2[2, 2] * nz
    # helper e_x where |n_x| < 0.6, else e_y (spiralbevel._core.tca.tangent_basis)
    if abs(n0) < 0.6:
        a0, a1, a2 = 0.0, n2, -n1
    else:
        a0, a1, a2 = -n2, 0.0, n0
    nrm = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
    a0, a1, a2 = a0 / nrm, a1 / nrm, a2 / nrm
    E[0, 0], E[0, 1], E[0, 2] = a0, a1, a2
    E[1, 0] = n1 * a2 - n2 * a1
    E[1, 1] = n2 * a0 - n0 * a2
    E[1, 2] = n0 * a1 - n1 * a0




@kernel
def assemble(S1, S2, c1, s1, x, d, M2, L, E, aj, aval, F, J, S1f, Q):
    """Contact system of one system: F (k,) mm, J (k, 5), fixed-frame data S1f (3, 6) and Q (6, 6).

    F[0:3] = o1 + R1 r1 - o2 - R2 r2, F[3:5] = L E (R1 n1 + R2 n2); dF/dq1 = (R1 r1_q, L E R1 n1_q),
    dF/dq2 = (-R2 r2_q, L E R2 n2_q), dF/dphi2 = (-a2 x R2 r2, L E (a2 x R2 n2)), with R1 = R_z(phi1) and
    R2 = B2 R_z(phi2) (Q rows 0-2: R2 S2; rows 3-5: a2 x R2 S2). With ``aj >= 0``, the row F[5] = L (x_aj - aval).
    """
    c2, s2 = math.cos(x[4]), math.sin(x[4])
    for j in range(6):
        S1f[0, j] = c1 * S1[0, j] - s1 * S1[1, j]
        S1f[1, j] = s1 * S1[0, j] + c1 * S1[1, j]
        S1f[2, j] = S1[2, j]
        u = c2 * S2[0, j] - s2 * S2[1, j]
        v = s2 * S2[0, j] + c2 * S2[1, j]
        w = S2[2, j]
        for i in range(6):
            Q[i, j] = M2[i, 0] * u + M2[i, 1] * v + M2[i, 2] * w
    for i in range(3):
        F[i] = d[i] + S1f[i, 0] - Q[i, 0]
        J[i, 0] = S1f[i, 2]
        J[i, 1] = S1f[i, 3]
        J[i, 2] = -Q[i, 2]
        J[i, 3] = -Q[i, 3]
        J[i, 4] = -Q[3 + i, 0]
    for a in range(2):
        e0, e1, e2 = E[a, 0], E[a, 1], E[a, 2]
        F[3 + a] = L * (e0 * (S1f[0, 1] + Q[0, 1]) + e1 * (S1f[1, 1] + Q[1, 1]) + e2 * (S1f[2, 1] + Q[2, 1]))
        J[3 + a, 0] = L * (e0 * S1f[0, 4] + e1 * S1f[1, 4] + e2 * S1f[2, 4])
        J[3 + a, 1] = L * (e0 * S1f[0, 5] + e1 * S1f[1, 5] + e2 * S1f[2, 5])
        J[3 + a, 2] = L * (e0 * Q[0, 4] + e1 * Q[1, 4] + e2 * Q[2, 4])
        J[3 + a, 3] = L * (e0 * Q[0, 5] + e1 * Q[1, 5] + e2 * Q[2, 5])
        J[3 + a, 4] = L * (e0 * Q[3, 1] + e1 * Q[4, 1] + e2 * Q[5, 1])
    if aj >= 0:
        F[5] = L * (x[aj] - aval)
        for j in range(5):
            J[5, j] = 0.0
        J[5, aj] = L




@kernel(inline="always")   # a few statements: cheaper typed at each call site than compiled alone
def _all_finite(a):
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
    if not (_all_finite(J) and _all_finite(F)):
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
    V = np.eye(n)
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




@kernel(inline="always")   # a few statements (see _all_finite)
def _max_abs(a):
    m = 0.0
    for v in a:
        if abs(v) > m:
            m = abs(v)
    return m


@kernel(inline="always")   # one call site: newton_batch
def start(F, J, tol, res, best, stall, halved, active):
    """Initial bookkeeping from the first evaluation ``F (M, k)``, ``J (M, k, 5)``; returns the number active."""
    count = 0
    for i in range(F.shape[0]):
        ok = _all_finite(F[i]) and _all_finite(J[i])
        res[i] = _max_abs(F[i]) if ok else math.inf
        best[i] = res[i]
        stall[i] = 0
        halved[i] = 0
        active[i] = ok and res[i] >= tol
        count += active[i]
    return count


@kernel(inline="always")   # one call site: newton_batch
def propose(x, F, J, dx, halved, active, rcond, xn, idx):
    """Trial points ``xn[:c]`` of the ``c`` active systems ``idx[:c]`` (fresh Newton step, or the halved previous
    one after a trial that left the surfaces); returns c."""
    c = 0
    for i in range(x.shape[0]):
        if active[i]:
            if halved[i] == 0:
                step(J[i], F[i], rcond, dx[i])
            for j in range(5):
                xn[c, j] = x[i, j] + dx[i, j]
            idx[c] = i
            c += 1
    return c


@kernel(inline="always")   # one call site: newton_batch
def accept(idx, c, xn, Fn, Jn, x, F, J, dx, res, best, stall, halved, active, tol, patience, halvings, acc):
    """Apply the trial evaluations ``Fn[:c]``, ``Jn[:c]`` (see the module docstring); ``acc[:c]`` tells which trials
    were taken (their surface data should be kept by the caller); returns the number still active."""
    for t in range(c):
        i = idx[t]
        fin = _all_finite(Fn[t]) and _all_finite(Jn[t])
        if not fin and halved[i] < halvings:
            for j in range(5):
                dx[i, j] *= 0.5
            halved[i] += 1
            acc[t] = False
            continue
        acc[t] = True
        copy1(x[i], xn[t])   # copies by loops, not x[i] = xn[t]: compile time (_core/jit.py)
        copy1(F[i], Fn[t])
        copy2(J[i], Jn[t])
        halved[i] = 0
        r = _max_abs(Fn[t]) if fin else math.inf
        res[i] = r
        better = r < 0.5 * best[i]
        best[i] = min(best[i], r)
        stall[i] = 0 if better else stall[i] + 1
        active[i] = r < math.inf and r >= tol and stall[i] < patience
    count = 0
    for i in range(x.shape[0]):
        count += active[i]
    return count




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




@kernel(inline="always")   # one call site: newton_batch
def _singular(J, tol, out):
    """``out[i]``: whether s_min / s_max of the column-equilibrated ``J[i] (k, 5)`` is below ``tol`` (line contact;
    see :func:`singular_batch`)."""
    d = np.empty(5)
    for i in range(J.shape[0]):
        out[i] = False
        if not _all_finite(J[i]):
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


# operations of newton_batch (iv[MODE])
JETS, BEGIN, ADVANCE, START, ACCEPT, STEP, TANGENT, SINGULAR = range(8)
# entries of its integer vector iv; ``C``, ``IT``, ``N_ACTIVE`` are written back
MODE, KIND1, KIND2, HAVE_E, AJ, MAX_ITER, PATIENCE, HALVINGS, C, IT, N_ACTIVE = range(11)
# entries of its float vector fv
SCALE, TOL, RCOND = range(3)


@kernel
def newton_batch(iv, fv, p1, p2, c1, s1, aval, d, M2, x, E, F, J, S1, S2, S1f, Q, xn, Fn, Jn, T1, T2, T1f, TQ, dx, res,
                 best, stall, halved, idx, active, acc):
    """Every batched operation of this module, chosen by ``iv[MODE]`` (one kernel, one argument signature).

    Parameters
    ----------
    iv : (11,) int64
        ``MODE``; the jets ``KIND1``, ``KIND2`` of pinion and gear (:mod:`spiralbevel._core.jets`); ``HAVE_E`` (0: fill
        the basis rows ``E`` from the gear normal at x); the anchor row ``AJ`` (< 0: none); ``MAX_ITER``,
        ``PATIENCE``, ``HALVINGS`` (module docstring); written back: ``C`` the number of trial points ``xn[:C]``
        (systems ``idx[:C]``) to evaluate, ``IT`` the iterations so far, ``N_ACTIVE`` the systems still iterating.
    fv : (3,) float
        ``SCALE`` L (mm), ``TOL`` (mm on max|F|; the s_min / s_max threshold for ``SINGULAR``), ``RCOND``.
    p1, p2 : (k,) float
        Jet parameters of pinion and gear (``JETS``).
    c1, s1, aval : (M,) float
        cos, sin of the effective pinion angles; anchor values.
    d, M2 :
        Assembly constants (module docstring).
    x (M, 5), E (M, 2, 3), F (M, k), J (M, k, 5), S1, S2, S1f (M, 3, 6), Q (M, 6, 6) : float
        Iterates, basis rows, systems and surface data at the iterates (member frame; S1f, Q fixed frame).
    xn (M, 5), Fn (M, k), Jn (M, k, 5), T1, T2, T1f (M, 3, 6), TQ (M, 6, 6) : float
        The same at the trial points.
    dx (M, 5), res, best (M,) float; stall, halved, idx (M,) int64; active, acc (M,) bool
        Steps and the bookkeeping of the iteration.

    Notes
    -----
    ``JETS``: the whole iteration from x, the surfaces evaluated by their compiled jets. ``BEGIN``: assembly at x
    from the member-frame data ``S1, S2`` evaluated by the caller, then the first trial points. ``ADVANCE``: assembly
    at the trial points from ``T1, T2`` evaluated by the caller, the rules, the next trial points. ``START`` and
    ``ACCEPT``: as ``BEGIN`` and ``ADVANCE`` with the systems ``F, J`` (``Fn, Jn``) given instead of assembled.
    ``STEP``: ``dx`` = the step of every system ``J, F``. ``TANGENT``: ``dx`` = the path tangent dx/dphi1 =
    -J^+ dF/dphi1 from ``J`` and ``S1f`` (a1 = +z: a1 x v = (-v_y, v_x, 0); extra rows of J get dF/dphi1 = 0).
    ``SINGULAR``: ``active`` = whether s_min / s_max of the column-equilibrated J is below ``TOL``
    (:func:`singular_batch`). Arrays a mode does not use may be empty.
    """
    mode = iv[MODE]
    L, tol, rcond = fv[SCALE], fv[TOL], fv[RCOND]
    if mode == STEP:
        for i in range(J.shape[0]):
            step(J[i], F[i], rcond, dx[i])
        return
    if mode == TANGENT:
        k = J.shape[1]
        Fp = np.zeros(k)
        for i in range(J.shape[0]):
            Fp[0] = -S1f[i, 1, 0]
            Fp[1] = S1f[i, 0, 0]
            Fp[2] = 0.0
            nx, ny = -S1f[i, 1, 1], S1f[i, 0, 1]
            for a in range(2):
                Fp[3 + a] = L * (E[i, a, 0] * nx + E[i, a, 1] * ny)
            step(J[i], Fp, rcond, dx[i])
        return
    if mode == SINGULAR:
        _singular(J, tol, active)
        return
    kind1, kind2, aj = iv[KIND1], iv[KIND2], iv[AJ]
    max_iter, patience, halvings = iv[MAX_ITER], iv[PATIENCE], iv[HALVINGS]
    first = mode == JETS or mode == BEGIN or mode == START
    assembled = mode != START and mode != ACCEPT
    if first and assembled:
        for i in range(x.shape[0]):
            if mode == JETS:
                surface_jet(kind1, p1, x[i, 0], x[i, 1], S1[i])
                surface_jet(kind2, p2, x[i, 2], x[i, 3], S2[i])
            if iv[HAVE_E] == 0:
                basis_rows(S2[i], math.cos(x[i, 4]), math.sin(x[i, 4]), M2, E[i])
            assemble(S1[i], S2[i], c1[i], s1[i], x[i], d, M2, L, E[i], aj, aval[i], F[i], J[i], S1f[i], Q[i])
    it, c, n_active = 0, 0, 0
    if first:
        n_active = start(F, J, tol, res, best, stall, halved, active)
    else:
        it, c = iv[IT], iv[C]
    pending = not first   # trial points evaluated, to be applied
    while True:
        if pending:
            for t in range(c):
                i = idx[t]
                if mode == JETS:
                    surface_jet(kind1, p1, xn[t, 0], xn[t, 1], T1[t])
                    surface_jet(kind2, p2, xn[t, 2], xn[t, 3], T2[t])
                if assembled:
                    assemble(T1[t], T2[t], c1[i], s1[i], xn[t], d, M2, L, E[i], aj, aval[i], Fn[t], Jn[t], T1f[t],
                             TQ[t])
            n_active = accept(idx, c, xn, Fn, Jn, x, F, J, dx, res, best, stall, halved, active, tol, patience,
                              halvings, acc)
            if assembled:
                for t in range(c):
                    if acc[t]:
                        i = idx[t]
                        copy2(S1[i], T1[t])   # copies by loops, not S1[i] = T1[t]: compile time (_core/jit.py)
                        copy2(S2[i], T2[t])
                        copy2(S1f[i], T1f[t])
                        copy2(Q[i], TQ[t])
        c = 0
        if it < max_iter and n_active > 0:
            it += 1
            c = propose(x, F, J, dx, halved, active, rcond, xn, idx)
        if mode != JETS or c == 0:
            break
        pending = True
    iv[C], iv[IT], iv[N_ACTIVE] = c, it, n_active


_F1, _F2, _F3 = np.empty(0), np.empty((0, 0)), np.empty((0, 0, 0))
_I1, _B1 = np.empty(0, np.int64), np.empty(0, np.bool_)
_ARGS = {"p1": _F1, "p2": _F1, "c1": _F1, "s1": _F1, "aval": _F1, "d": _F1, "M2": _F2, "x": _F2, "E": _F3, "F": _F2,
         "J": _F3, "S1": _F3, "S2": _F3, "S1f": _F3, "Q": _F3, "xn": _F2, "Fn": _F2, "Jn": _F3, "T1": _F3, "T2": _F3,
         "T1f": _F3, "TQ": _F3, "dx": _F2, "res": _F1, "best": _F1, "stall": _I1, "halved": _I1, "idx": _I1,
         "active": _B1, "acc": _B1}


def _call(mode, ints=(), fv=(0.0, 0.0, 0.0), **arrays):
    """:func:`newton_batch` with the integer vector ``(mode, *ints)`` (zeros after) and empty unused arrays."""
    iv = np.zeros(11, np.int64)
    iv[MODE] = mode
    iv[1:1 + len(ints)] = ints
    newton_batch(iv, np.array(fv, float), *(arrays.get(n, e) for n, e in _ARGS.items()))
    return iv


def _arr(a):
    """``a`` as a writable, aligned, C-contiguous float64 array (copied only if needed): one argument type."""
    return np.require(a, np.float64, "CWA")


def _consts(d, M2):
    return _arr(d), _arr(M2)


def newton_jets(kind1, p1, kind2, p2, c1, s1, x0, E, have_E, d, M2, L, aj, aval, tol, max_iter, rcond, patience,
                halvings):
    """The whole batched Newton for two surfaces with compiled jets (:func:`spiralbevel._core.jets.surface_jet`).

    Parameters
    ----------
    kind1, p1, kind2, p2 : int, (k,) float
        Jets of pinion and gear.
    c1, s1 : (M,) float
        cos, sin of the effective pinion angles.
    x0 : (M, 5) float
    E : (M, 2, 3) float
        Basis rows of the normal equations; filled from the gear normal at x0 unless ``have_E``.
    d, M2, L :
        Assembly constants (module docstring).
    aj, aval : int, (M,) float
        Anchor equation x_aj = aval (aj < 0: none).
    tol, max_iter, rcond, patience, halvings :
        See the module docstring.

    Returns
    -------
    x (M, 5), F (M, k), J (M, k, 5), res (M,), S1, S2 (M, 3, 6), S1f (M, 3, 6), Q (M, 6, 6), iterations
    """
    M = x0.shape[0]
    k = 6 if aj >= 0 else 5
    it = Iteration(M, k, c1, s1, E, d, M2, L, aj, aval, tol, max_iter, rcond, patience, halvings)
    it.x[:] = x0
    a = it.arrays
    S1, S2 = np.empty((M, 3, 6)), np.empty((M, 3, 6))
    iv = _call(JETS, (kind1, kind2, bool(have_E), aj, max_iter, patience, halvings), it.fv, p1=_arr(p1),
               p2=_arr(p2), S1=S1, S2=S2, T1=np.empty((M, 3, 6)), T2=np.empty((M, 3, 6)), **a)
    return it.x, it.F, it.J, it.res, S1, S2, it.S1f, it.Q, int(iv[IT])


class Iteration:
    """The batched Newton as reverse communication, for surfaces that the caller evaluates (by numpy).

    ``begin`` assembles the systems at the start and returns the number ``c`` of trial points ``xn[:c]`` (systems
    ``idx[:c]``); the caller evaluates the surfaces there and hands them to ``advance``, which returns the next ``c``;
    c = 0 when every system has converged, been given up or reached ``max_iter`` (:func:`newton_batch`).

    Parameters
    ----------
    M, k : int
        Number of systems, equations per system (6 with an anchor).
    c1, s1, E, d, M2, L, aj, aval, tol, max_iter, rcond, patience, halvings :
        As :func:`newton_jets`.

    Attributes
    ----------
    x (M, 5), F (M, k), J (M, k, 5), res (M,), E (M, 2, 3), S1f (M, 3, 6), Q (M, 6, 6) : float
        Iterates, their systems and residuals max|F| (inf: not finite), basis rows, fixed-frame data.
    xn (M, 5) float, idx (M,) int
        Trial points and their systems (the first ``c``).
    accepted (M,) bool
        Which of the last ``c`` trials were taken (the others are retried with the step halved).
    iterations : int
    """

    def __init__(self, M, k, c1, s1, E, d, M2, L, aj, aval, tol, max_iter, rcond, patience, halvings):
        d, M2 = _consts(d, M2)
        self.fv = (float(L), float(tol), float(rcond))
        self.ints = (0, 0, 0, int(aj), int(max_iter), int(patience), int(halvings))
        c1, s1, aval, E = _arr(c1), _arr(s1), _arr(aval), _arr(E)
        self.x, self.E = np.empty((M, 5)), E
        self.F, self.J = np.empty((M, k)), np.empty((M, k, 5))
        self.S1f, self.Q = np.empty((M, 3, 6)), np.empty((M, 6, 6))
        self.res, self.accepted = np.empty(M), np.zeros(M, np.bool_)
        self.xn, self.idx = np.empty((M, 5)), np.empty(M, np.int64)
        self.arrays = dict(c1=c1, s1=s1, aval=aval, d=d, M2=M2, x=self.x, E=E, F=self.F, J=self.J, S1f=self.S1f,
                           Q=self.Q, xn=self.xn, Fn=np.empty((M, k)), Jn=np.empty((M, k, 5)), T1f=np.empty((M, 3, 6)),
                           TQ=np.empty((M, 6, 6)), dx=np.zeros((M, 5)), res=self.res, best=np.empty(M),
                           stall=np.zeros(M, np.int64), halved=np.zeros(M, np.int64), idx=self.idx,
                           active=np.zeros(M, np.bool_), acc=self.accepted)
        self.iterations = 0
        self._S = None

    def _run(self, mode, ints, **arrays):
        iv = _call(mode, ints, self.fv, **{**self.arrays, **arrays})
        self.iterations = int(iv[IT])
        self._iv = iv
        return int(iv[C])

    def begin(self, x0, S1=None, S2=None, have_E=False, F=None, J=None):
        """Start from ``x0 (M, 5)`` with the member-frame surface data ``S1, S2 (M, 3, 6)`` there (the basis rows
        ``E`` filled from the gear normal unless ``have_E``), or with the systems ``F, J`` given; returns c."""
        self.x[:] = x0
        ints = (0, 0, int(bool(have_E))) + self.ints[3:]
        if S1 is None:
            self.F[:], self.J[:] = F, J
            return self._run(START, ints)
        self._S = (S1, S2)
        return self._run(BEGIN, ints, S1=S1, S2=S2)

    def advance(self, T1=None, T2=None, Fn=None, Jn=None):
        """Apply the member-frame surface data ``T1, T2 (c, 3, 6)`` at the trial points (the accepted ones are copied
        into ``S1, S2`` of :meth:`begin`), or the systems ``Fn (c, k)``, ``Jn (c, k, 5)`` there; returns the next c."""
        ints = (0, 0, 0) + self.ints[3:] + (int(self._iv[C]), self.iterations)
        if T1 is None:
            return self._run(ACCEPT, ints, Fn=_arr(Fn), Jn=_arr(Jn))
        S1, S2 = self._S
        return self._run(ADVANCE, ints, S1=S1, S2=S2, T1=T1, T2=T2)


def step_batch(J, F, rcond):
    """:func:`step` for every row of ``J (m, k, 5)``, ``F (m, k)``; returns ``dx (m, 5)``."""
    J, F = _arr(J), _arr(F)
    dx = np.empty((J.shape[0], 5))
    _call(STEP, (), (0.0, 0.0, float(rcond)), J=J, F=F, dx=dx)
    return dx


def tangent_batch(J, S1f, E, L, rcond):
    """Path tangent dx/dphi1 (m, 5) = -J^+ dF/dphi1 from ``J (m, k, 5)`` and the fixed-frame pinion data
    ``S1f (m, 3, 6)``, basis rows ``E (m, 2, 3)`` (see :func:`newton_batch`)."""
    J = _arr(J)
    dx = np.empty((J.shape[0], 5))
    _call(TANGENT, (), (float(L), 0.0, float(rcond)), J=J, S1f=_arr(S1f),
          E=_arr(E), dx=dx)
    return dx


def singular_batch(J, tol):
    """Whether s_min / s_max of the column-equilibrated ``J (m, k, 5)`` is below ``tol``, per system (line contact).

    Certificates first, the Jacobi SVD only where they do not decide: with unit columns s_max >= 1 and, for the
    triangular factor R of a QR decomposition, s_min <= min_j |R_jj|: singular when min_j |R_jj| < tol; regular when
    |det| = prod_j |R_jj| > 5^2.5 tol (see :func:`step`). Non-finite systems are not singular."""
    J = _arr(J)
    out = np.zeros(J.shape[0], np.bool_)
    _call(SINGULAR, (), (0.0, float(tol), 0.0), J=J, active=out)
    return out
