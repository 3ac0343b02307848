"""Compiled batched Newton of tooth contact analysis: system assembly and the batched iteration with its give-up rule.

Same equations and unknowns as :mod:`spiralbevel._core.tca` (seed 001 Eq. (16), docs/theory/tca.md, Eq. (T5)):
x = (q1, q2, phi2), F in mm, surface data stacked per system as ``S (3, 6)`` with the columns (r, n, r_q0, r_q1,
n_q0, n_q1) in the member frame (:func:`spiralbevel._core.tca_batch.stack_state`). Every rule here is compiled
(:mod:`spiralbevel._core.jit`) and has one implementation:

* :func:`assemble` -- F (k,) and J (k, 5) of one system (k = 6 with an anchor equation x_j = value);
* the Newton step :func:`spiralbevel._core.tca_step.step` (LU where a determinant bound proves the system regular,
  else the minimum-norm SVD step);
* :func:`newton_one` -- the same iteration on one system, for the compiled stages that solve systems one by one
  (:func:`continuation`, :func:`spiralbevel._core.tca_transfer.transfer_points`);
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
optimises ``step`` (with its LU and SVD) and ``assemble`` once here, not once per entry point, and compiles one
function instead of nine (``_core/jit.py``; ``bench/bench_compile.py --ir``). :mod:`spiralbevel._core.tca_solve`
allocates the arrays and calls it (the whole iteration for surfaces with compiled jets, reverse communication for
surfaces evaluated by numpy, the step, the path tangent and the line-contact test of a batch).

Constants of an assembly (:func:`spiralbevel._core.tca_batch.assembly_constants`): d = o1 - o2 (3,) mm,
M2 = [B2; [a2]x B2] (6, 3), L mm the length scale of the normal equations.
"""

from __future__ import annotations

import math

import numpy as np

from .jets import surface_jet
from .jit import kernel
from .linalg import copy1, copy2
from .tca_predict import predict
from .tca_step import all_finite, max_abs, singular_rows, step

__all__ = ["assemble", "basis_rows", "step", "start", "propose", "accept", "newton_batch", "newton_one"]

@kernel(inline="always")   # one call site: newton_batch
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





@kernel(inline="always")   # one call site: newton_batch
def start(F, J, tol, res, best, stall, halved, active):
    """Initial bookkeeping from the first evaluation ``F (M, k)``, ``J (M, k, 5)``; returns the number active."""
    count = 0
    for i in range(F.shape[0]):
        ok = all_finite(F[i]) and all_finite(J[i])
        res[i] = max_abs(F[i]) if ok else math.inf
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
        fin = all_finite(Fn[t]) and all_finite(Jn[t])
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
        r = max_abs(Fn[t]) if fin else math.inf
        res[i] = r
        better = r < 0.5 * best[i]
        best[i] = min(best[i], r)
        stall[i] = 0 if better else stall[i] + 1
        active[i] = r < math.inf and r >= tol and stall[i] < patience
    count = 0
    for i in range(x.shape[0]):
        count += active[i]
    return count


@kernel   # a kernel of its own, called from newton_batch (CONTINUE) and tca_transfer.transfer_points: typed once
def newton_one(kind1, p1, kind2, p2, c1, s1, x, d, M2, L, tol, max_iter, rcond, patience, halvings, F, J, S1f, E):
    """The iteration of :func:`newton_batch` (``JETS``, basis rows ``E (2, 3)`` from the gear normal at the start, no
    anchor) on one system, ``x (5,)`` updated in place, its system ``F (5,)``, ``J (5, 5)`` and fixed-frame pinion
    data ``S1f (3, 6)`` at the final iterate written; returns whether it converged (max|F| < tol). The same rules
    and arithmetic in the same order as the batch, whose systems are independent: the same iterates."""
    S1, S2, Q = np.empty((3, 6)), np.empty((3, 6)), np.empty((6, 6))
    T1, T2, T1f, TQ = np.empty((3, 6)), np.empty((3, 6)), np.empty((3, 6)), np.empty((6, 6))
    Fn, Jn = np.empty(5), np.empty((5, 5))
    dx, xn = np.zeros(5), np.empty(5)
    aj = np.int64(-1)
    surface_jet(kind1, p1, x[0], x[1], S1)
    surface_jet(kind2, p2, x[2], x[3], S2)
    basis_rows(S2, math.cos(x[4]), math.sin(x[4]), M2, E)
    assemble(S1, S2, c1, s1, x, d, M2, L, E, aj, 0.0, F, J, S1f, Q)
    ok = all_finite(F) and all_finite(J)
    res = max_abs(F) if ok else math.inf
    best = res
    stall, halved = 0, 0
    active = ok and res >= tol
    it = 0
    while it < max_iter and active:
        it += 1
        if halved == 0:
            step(J, F, rcond, dx)
        for j in range(5):
            xn[j] = x[j] + dx[j]
        surface_jet(kind1, p1, xn[0], xn[1], T1)
        surface_jet(kind2, p2, xn[2], xn[3], T2)
        assemble(T1, T2, c1, s1, xn, d, M2, L, E, aj, 0.0, Fn, Jn, T1f, TQ)
        fin = all_finite(Fn) and all_finite(Jn)
        if not fin and halved < halvings:
            for j in range(5):
                dx[j] *= 0.5
            halved += 1
            continue
        copy1(x, xn)
        copy1(F, Fn)
        copy2(J, Jn)
        copy2(S1f, T1f)
        halved = 0
        r = max_abs(Fn) if fin else math.inf
        res = r
        better = r < 0.5 * best
        best = min(best, r)
        stall = 0 if better else stall + 1
        active = r < math.inf and r >= tol and stall < patience
    return res < tol


@kernel(inline="always")   # two call sites in newton_batch (TANGENT, CONTINUE)
def tangent(J, S1f, E, L, rcond, Fp, dx):
    """Path tangent ``dx (5,)`` = -J^+ dF/dphi1 of one system ``J (k, 5)`` from its fixed-frame pinion data
    ``S1f (3, 6)`` and basis rows ``E (2, 3)`` (a1 = +z: a1 x v = (-v_y, v_x, 0); extra rows of J get dF/dphi1 = 0,
    ``Fp (k,)`` is scratch with those entries 0)."""
    Fp[0] = -S1f[1, 0]
    Fp[1] = S1f[0, 0]
    Fp[2] = 0.0
    nx, ny = -S1f[1, 1], S1f[0, 1]
    for a in range(2):
        Fp[3 + a] = L * (E[a, 0] * nx + E[a, 1] * ny)
    step(J, Fp, rcond, dx)


@kernel(inline="always")   # one call site: newton_batch (CONTINUE)
def continuation(kind1, p1, kind2, p2, d, M2, L, tol, max_iter, rcond, patience, halvings, phi1_mean, h, need_hi,
                 need_lo, X, Xp, off, fail):
    """Nodes of the solution path from the mean point out to ``need_hi`` steps ``h`` (rad) above ``phi1_mean`` and
    ``need_lo`` below (the rules of ``meshing.tca._continuation``, in its operation order): level 1 solves the nodes
    +-h from the tangent predictor; each further level advances every side by up to two steps at once, predicted by
    the quintic Hermite polynomial through the side's last three nodes (:func:`spiralbevel._core.tca_predict.predict`)
    or linearly from its last node where it has two; the path tangent at a node comes from the Jacobian of its last
    Newton iteration (:func:`tangent`). A side ends at its first node that does not converge (or has no finite
    tangent): its offset goes to ``fail (2,)`` (below, above; -inf, inf where none failed).

    ``X``, ``Xp (need_lo + need_hi + 1, 5)`` hold the mean point and its tangent in row ``need_lo`` on entry and the
    nodes (sorted) in their first rows on return, ``off`` their offsets (rad); returns the number of nodes."""
    K = X.shape[0]
    have = np.zeros(K, np.bool_)
    have[need_lo] = True
    last = np.zeros(2, np.int64)   # per side (0: up, 1: down), the last node's step index
    alive = np.zeros(2, np.bool_)
    alive[0], alive[1] = need_hi > 0, need_lo > 0
    fail[0], fail[1] = -math.inf, math.inf
    idx = np.empty(4, np.int64)
    G = np.empty((4, 5))
    good = np.zeros(4, np.bool_)
    T = np.empty((4, 5))
    nodes, Xk, Xpk = np.empty(3), np.empty((3, 5)), np.empty((3, 5))
    F, J, S1f, E, Fp = np.empty(5), np.empty((5, 5)), np.empty((3, 6)), np.empty((2, 3)), np.zeros(5)
    while alive[0] or alive[1]:
        cnt = 0
        for side in range(2):
            if not alive[side]:
                continue
            dd = 1 if side == 0 else -1
            need = need_hi if side == 0 else need_lo
            j0 = last[side]
            if j0 == 0:
                idx[cnt] = dd
                for k in range(5):
                    G[cnt, k] = X[need_lo, k] + dd * h * Xp[need_lo, k]
                cnt += 1
                continue
            nn = 0
            for mm in range(1, 3):
                if abs(j0) + mm <= need:
                    idx[cnt + nn] = j0 + dd * mm
                    nn += 1
            jb = j0 - 2 * dd
            if -need_lo <= jb <= need_hi and have[jb + need_lo]:   # the quintic through the side's three nodes
                for t in range(3):
                    j = j0 + (t if dd < 0 else t - 2)   # sorted: j0 - 2, j0 - 1, j0 (up) or j0, j0 + 1, j0 + 2
                    nodes[t] = j * h
                    for k in range(5):
                        Xk[t, k] = X[j + need_lo, k]
                        Xpk[t, k] = Xp[j + need_lo, k]
                o, out = np.empty(nn), np.empty((nn, 5))
                for t in range(nn):
                    o[t] = idx[cnt + t] * h
                predict(o, nodes, Xk, Xpk, out)
                for t in range(nn):
                    for k in range(5):
                        G[cnt + t, k] = out[t, k]
            else:
                for t in range(nn):
                    for k in range(5):
                        G[cnt + t, k] = X[j0 + need_lo, k] + (idx[cnt + t] - j0) * h * Xp[j0 + need_lo, k]
            cnt += nn
        for t in range(cnt):
            # a node within reach converges quadratically from its predictor; two iterations without halving the
            # residual mean the path has ended there
            phi = phi1_mean + idx[t] * h
            conv = newton_one(kind1, p1, kind2, p2, math.cos(phi), math.sin(phi), G[t], d, M2, L, tol, max_iter,
                              rcond, patience, halvings, F, J, S1f, E)
            tangent(J, S1f, E, L, rcond, Fp, T[t])
            good[t] = conv and all_finite(T[t])
        for side in range(2):
            if not alive[side]:
                continue
            dd = 1 if side == 0 else -1
            for t in range(cnt):   # in the order of |index|
                if (idx[t] > 0) != (dd > 0):
                    continue
                if not good[t]:
                    alive[side] = False
                    fail[side ^ 1] = idx[t] * h
                    break
                r = idx[t] + need_lo
                for k in range(5):
                    X[r, k] = G[t, k]
                    Xp[r, k] = T[t, k]
                have[r] = True
                last[side] = idx[t]
            if abs(last[side]) >= (need_hi if side == 0 else need_lo):
                alive[side] = False
    first = last[1] + need_lo
    count = last[0] - last[1] + 1
    for r in range(count):
        off[r] = (last[1] + r) * h
        for k in range(5):
            X[r, k] = X[first + r, k]
            Xp[r, k] = Xp[first + r, k]
    return count


# operations of newton_batch (iv[MODE])
JETS, BEGIN, ADVANCE, START, ACCEPT, STEP, TANGENT, SINGULAR, CONTINUE = range(9)
# entries of its integer vector iv; ``C``, ``IT``, ``N_ACTIVE`` are written back; ``NEED_HI``, ``NEED_LO``: CONTINUE
MODE, KIND1, KIND2, HAVE_E, AJ, MAX_ITER, PATIENCE, HALVINGS, C, IT, N_ACTIVE, NEED_HI, NEED_LO = range(13)
# entries of its float vector fv (``PHI1_MEAN``, ``H`` and the written-back ``FAIL``: CONTINUE)
SCALE, TOL, RCOND, PHI1_MEAN, H, FAIL = range(6)


@kernel
def newton_batch(iv, fv, p1, p2, c1, s1, aval, d, M2, x, E, F, J, S1, S2, S1f, Q, xn, Fn, Jn, T1, T2, T1f, TQ, dx, res,
                 best, stall, halved, idx, active, acc):
    """Every batched operation of this module, chosen by ``iv[MODE]`` (one kernel, one argument signature).

    Parameters
    ----------
    iv : (11,) int64 (13 for ``CONTINUE``)
        ``MODE``; the jets ``KIND1``, ``KIND2`` of pinion and gear (:mod:`spiralbevel._core.jets`); ``HAVE_E`` (0: fill
        the basis rows ``E`` from the gear normal at x); the anchor row ``AJ`` (< 0: none); ``MAX_ITER``,
        ``PATIENCE``, ``HALVINGS`` (module docstring); written back: ``C`` the number of trial points ``xn[:C]``
        (systems ``idx[:C]``) to evaluate, ``IT`` the iterations so far, ``N_ACTIVE`` the systems still iterating.
    fv : (3,) float (7 for ``CONTINUE``)
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
    (:func:`spiralbevel._core.tca_solve.singular_batch`). ``CONTINUE``: the continuation of the path of contact
    (:func:`continuation`) from the mean point in row ``iv[NEED_LO]`` of ``x`` (its tangent in that row of ``dx``)
    out to ``iv[NEED_LO]`` steps ``fv[H]`` (rad) below ``fv[PHI1_MEAN]`` and ``iv[NEED_HI]`` above: the nodes and
    tangents in the first ``iv[C]`` rows of ``x``, ``dx``, their offsets in ``res``, the offsets of the first failed
    node below and above in ``fv[FAIL]``, ``fv[FAIL + 1]`` (:func:`spiralbevel._core.tca_solve.continuation_jets`).
    Arrays a mode does not use may be empty; so may the work arrays of ``JETS`` (``xn`` to ``TQ``, ``dx``,
    ``best``, ``stall``, ``halved``, ``idx``, ``active``, ``acc``).
    """
    mode = iv[MODE]
    L, tol, rcond = fv[SCALE], fv[TOL], fv[RCOND]
    if mode == STEP:
        for i in range(J.shape[0]):
            step(J[i], F[i], rcond, dx[i])
        return
    if mode == TANGENT:
        Fp = np.zeros(J.shape[1])
        for i in range(J.shape[0]):
            tangent(J[i], S1f[i], E[i], L, rcond, Fp, dx[i])
        return
    if mode == SINGULAR:
        singular_rows(J, tol, active)
        return
    if mode == CONTINUE:
        iv[C] = continuation(iv[KIND1], p1, iv[KIND2], p2, d, M2, L, tol, iv[MAX_ITER], rcond, iv[PATIENCE],
                             iv[HALVINGS], fv[PHI1_MEAN], fv[H], iv[NEED_HI], iv[NEED_LO], x, dx, res, fv[FAIL:])
        return
    kind1, kind2, aj = iv[KIND1], iv[KIND2], iv[AJ]
    max_iter, patience, halvings = iv[MAX_ITER], iv[PATIENCE], iv[HALVINGS]
    first = mode == JETS or mode == BEGIN or mode == START
    assembled = mode != START and mode != ACCEPT
    M, k = x.shape[0], F.shape[1]
    if mode == JETS and xn.shape[0] < M:   # work arrays not given: allocated here (cheaper than from Python)
        xn, Fn, Jn, dx = np.empty((M, 5)), np.empty((M, k)), np.empty((M, k, 5)), np.zeros((M, 5))
        T1, T2, T1f, TQ = np.empty((M, 3, 6)), np.empty((M, 3, 6)), np.empty((M, 3, 6)), np.empty((M, 6, 6))
        best, stall, halved = np.empty(M), np.zeros(M, np.int64), np.zeros(M, np.int64)
        idx, active, acc = np.empty(M, np.int64), np.zeros(M, np.bool_), np.zeros(M, np.bool_)
    if first and assembled:
        for i in range(M):
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

