"""The whole edge stage of TCA (:func:`spiralbevel.meshing.tca_edge.edge_stage`) in one compiled call, for surfaces
with compiled jets and margins whose ``contains`` is a margin test (the case of
:func:`~spiralbevel._core.tca_edge_screen.solve_screen`): the candidates of the extended contacts beyond a boundary,
the boundaries next to a lost contact, the corners and vertices seeded by solutions running past another boundary (two
further rounds of a batch), and the march over the effective pinion rotation, each batch solved and screened by
:func:`~spiralbevel._core.tca_edge_screen.solve_screen`.

The order of everything follows the Python statement of the stage in ``meshing/tca_edge.py`` (the reference, run for
other surfaces): candidates in the order (position, pair, member, boundary), the seeds next to lost contacts in the
order (position, pair, side) and first come first kept, the rounds of a batch depth first. The march's front is taken
in the order its contacts were found (the Python statement holds it as a set, whose order is that of the hashes): a
neighbour reached from two contacts of one front is started from the first. Where no neighbour is reached from two,
the same rows are solved from the same starts in the same batches, and the results are the same to the bit.

The same entry point solves a given batch alone (mode 0, the Newton of
:func:`spiralbevel.meshing.tca_edge_solve.solve_edge_contacts`): one compiled entry point per family, one call site
of the solve (see ``_core/jit.py``).
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel
from .tca_corner_screen import FILLET
from .tca_edge import N_MARGINS, margins
from .tca_edge_screen import solve_screen

__all__ = ["edge_stage_run", "FP_SIZE", "IP_SIZE"]

#: lengths of the float and integer parameter arrays of :func:`edge_stage_run`
FP_SIZE = 11
IP_SIZE = 3 + 2 * N_MARGINS + 4 * N_MARGINS


@kernel
def _crossed(mk, mp, q0, q1, S, g, dg, out):
    """``out (N,)``: the point q of a member lies beyond each boundary (margin < 0 or NaN)."""
    margins(mk, mp, q0, q1, S, g, dg)
    for e in range(N_MARGINS):
        out[e] = not g[e] >= 0.0


@kernel
def _append(bi, bj, bm, be, bx, bp, k, i, j, m, e, x0, parent):
    """Row k of a batch (arrays grown by the caller): position i, pair index j, system (m, e), start x0 (5,)."""
    bi[k] = i
    bj[k] = j
    bm[k] = m
    be[k] = e
    for c in range(5):
        bx[k, c] = x0[c]
    bp[k] = parent


@kernel
def _grow(bi, bj, bm, be, bx, bp, need):
    """The row arrays with room for ``need`` rows (copies when they are too short)."""
    cap = bi.shape[0]
    if need <= cap:
        return bi, bj, bm, be, bx, bp
    c = max(need, 2 * cap)
    ni, nj, nm, ne = (np.empty(c, np.int64), np.empty(c, np.int64), np.empty(c, np.int64),
                      np.empty(c, np.int64))
    nx, npr = np.empty((c, 5)), np.empty(c, np.int64)
    for k in range(cap):
        ni[k] = bi[k]
        nj[k] = bj[k]
        nm[k] = bm[k]
        ne[k] = be[k]
        npr[k] = bp[k]
        for q in range(5):
            nx[k, q] = bx[k, q]
    return ni, nj, nm, ne, nx, npr


@kernel
def _propagate(new_p, parent, new_c, k):
    """``new_p[parent] |= new_c`` over the k child rows with numpy's fancy-index semantics (of rows sharing a parent
    the last one writes: ``new_p[parent[r]] = old new_p[parent[r]] | new_c[r]``)."""
    old = new_p.copy()
    for r in range(k):
        new_p[parent[r]] = old[parent[r]] | new_c[r]


@kernel
def edge_stage_run(kinds, p1, mp1, p2, mp2, ctol, junction, d, M2, fp, ip, c1, s1, x, member, edge, conv, ndot,
                   status, te_s, phi1, pairs, floor, te_edge, x_edge, lab, info):
    """The edge stage (``ip[0]`` 1) or the Newton of one batch (``ip[0]`` 0).

    Parameters
    ----------
    kinds, p1, mp1, p2, mp2, ctol, junction, d, M2 :
        As :func:`~spiralbevel._core.tca_edge_screen.edge_try`.
    fp : (FP_SIZE,) float
        Newton step h of the curve tangent, tolerance (mm), rank threshold; the TE frame ``tep (6,)`` of ``edge_try``
        (drive, phi2_mean, ratio, phi1_mean, z2, |TE| limit); the pinion pitch 2 pi / z1 (rad) and the TE tie (rad).
    ip : (IP_SIZE,) int
        Mode (0: solve the batch ``c1``, ``s1``, ``x``, ``member``, ``edge``; 1: the edge stage), Newton iterations
        at most, 1 where the samples of the pinion's fillet junction are not computed yet (the stage then stops at
        the first batch that would read them: ``info[0]`` 1); then per member and boundary 1 for the end of the
        generated surface (no edge of its own), then per member and boundary the two boundaries of the other member
        that meet it (-1: none).
    c1, s1, x, member, edge, conv, ndot :
        Mode 0: the batch and its outputs as in ``edge_try`` (``screen_it`` 0). Mode 1: ``x (n P, 5)`` the surface
        contacts (position-major, the pairs' rows of a position together); the others unused.
    status : (n, P) int
        ContactStatus of the surface contacts (0 OK, 1 LINE, 2 EDGE).
    te_s : (n, P) float, rad
        Their TE.
    phi1 : (n,) float, rad
    pairs : (P,) float
        Tooth pair numbers.
    floor : (n, P) float
        Scratch (the march's floor of a solution's TE).
    te_edge, x_edge : (n, P) float, (n, P, 5) float
        Output: the edge contacts (NaN where none).
    lab : (n, P, 3) int
        Output: member and edge code of the system that labels each pair's contact, and the order in which the pairs
        were first labelled (-1 for all three where none).
    info : (1,) int
        Output: 1 where the stage stopped for the junction samples (then run it again with them), else 0.
    """
    mode = ip[0]
    max_iter = ip[1]
    T1, te_tie, ratio = fp[9], fp[10], fp[5]
    N = N_MARGINS
    K = 2 * N
    n, P = status.shape
    info[0] = 0
    # 1 (n, P) stage state
    phys = np.zeros((n, P), np.bool_)
    best = np.full((n, P), -math.inf)
    last = np.empty((n, P), np.int64)
    lab_i = np.empty(n * P, np.int64)
    lab_j = np.empty(n * P, np.int64)
    nlab = 0
    for i in range(n):
        for j in range(P):
            phys[i, j] = status[i, j] == 0 or status[i, j] == 1
            floor[i, j] = -math.inf
            te_edge[i, j] = math.nan
            for c in range(5):
                x_edge[i, j, c] = math.nan
            for c in range(3):
                lab[i, j, c] = -1
        if P > 1:   # the largest TE of the real contacts of the other pairs
            first = 0
            for j in range(P):
                v = te_s[i, j] if phys[i, j] else -math.inf
                v0 = te_s[i, first] if phys[i, first] else -math.inf
                if v > v0:
                    first = j
            top = te_s[i, first] if phys[i, first] else -math.inf
            second = -math.inf
            for j in range(P):
                if j != first:
                    v = te_s[i, j] if phys[i, j] else -math.inf
                    if v > second:
                        second = v
            for j in range(P):
                best[i, j] = second if j == first else top
    span = False
    if n > 1:
        span = True
        st = T1 / (n - 1)
        for i in range(n - 1):
            if not math.fabs((phi1[i + 1] - phi1[i]) - st) <= 1e-9 * st:
                span = False
    S = np.empty((3, 6))
    g = np.empty(N)
    dg = np.empty((N, 2))
    cr = np.zeros((2, N), np.bool_)
    x0 = np.empty(5)
    # the rows of the current round (a batch and the corners it seeds, two levels deep) and of the next batch
    cap = 8
    bi, bj, bm, be = (np.empty(cap, np.int64), np.empty(cap, np.int64), np.empty(cap, np.int64),
                      np.empty(cap, np.int64))
    bx, bp = np.empty((cap, 5)), np.empty(cap, np.int64)
    nb = 0
    # new rows of the levels of a round, their parents, the top level's positions and pairs
    new0, new1, new2 = np.zeros(0, np.bool_), np.zeros(0, np.bool_), np.zeros(0, np.bool_)
    par1, par2 = np.zeros(0, np.int64), np.zeros(0, np.int64)
    top_i, top_j, rp = np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0, np.int64)
    cand = np.full((n, P), -1, np.int64)
    front_i, front_j = np.empty(n * P, np.int64), np.empty(n * P, np.int64)
    nfront = 0
    phase = 0        # stage: 0 start, 1 candidates beyond a boundary, 2 seeds next to lost contacts, 3 march
    level = 3        # level of the next batch in its round (3: the round is done)
    done = False
    while True:
        # ---- the next batch
        if mode == 0:
            if done:
                break
            done = True
            ri, rj, rm, re, rx = np.zeros(0, np.int64), np.zeros(0, np.int64), member, edge, x
            k = x.shape[0]
            cs = np.empty((2, k))
            for a in range(k):
                cs[0, a] = c1[a]
                cs[1, a] = s1[a]
            screen_it = 0
        else:
            if level == 3:
                # the round is done: new of the deeper levels into the top one
                if new2.shape[0]:
                    _propagate(new1, par2, new2, new2.shape[0])
                if new1.shape[0]:
                    _propagate(new0, par1, new1, new1.shape[0])
                new1, new2 = np.zeros(0, np.bool_), np.zeros(0, np.bool_)
                nb = 0
                while nb == 0 and phase < 4:
                    if phase == 0:
                        # 1. pairs whose extended contact lies beyond a boundary (and does not trail the best real
                        # contact of another pair): every boundary crossed and the boundary of the mate meeting it
                        phase = 1
                        for i in range(n):
                            for j in range(P):
                                if status[i, j] != 2 or te_s[i, j] < best[i, j] - te_tie:
                                    continue
                                r = i * P + j
                                for m in range(2):
                                    _crossed(kinds[1] if m == 0 else kinds[4], mp1 if m == 0 else mp2,
                                             x[r, 2 * m], x[r, 2 * m + 1], S, g, dg, cr[m])
                                for M in range(2):
                                    for E in range(N):
                                        want = False
                                        for m in range(2):
                                            for e in range(N):
                                                if not cr[m, e] or ip[3 + m * N + e] != 0:
                                                    continue
                                                if m == M and e == E:
                                                    want = True
                                                elif m != M:
                                                    for t in range(2):
                                                        if ip[3 + 2 * N + (m * N + e) * 2 + t] == E:
                                                            want = True
                                        if want:
                                            bi, bj, bm, be, bx, bp = _grow(bi, bj, bm, be, bx, bp, nb + 1)
                                            _append(bi, bj, bm, be, bx, bp, nb, i, j, M, E, x[r], -1)
                                            nb += 1
                    elif phase == 1:
                        # 1b. next to a position where a pair's real contact is lost: the boundary nearest that
                        # contact on each member and the mate's boundary meeting it, first come first kept
                        phase = 2
                        for i in range(n):
                            for j in range(P):
                                for dd in range(2):
                                    kk = i - 1 if dd == 0 else i + 1
                                    if not (0 <= kk < n and phys[i, j] and not phys[kk, j]):
                                        continue
                                    if lab[kk, j, 0] >= 0:
                                        continue
                                    r = i * P + j
                                    for c in range(5):
                                        x0[c] = x[r, c]
                                    x0[4] -= ratio * (phi1[kk] - phi1[i])
                                    for m in range(2):
                                        margins(kinds[1] if m == 0 else kinds[4], mp1 if m == 0 else mp2,
                                                x[r, 2 * m], x[r, 2 * m + 1], S, g, dg)
                                        eb = -1
                                        for e in range(N):
                                            if ip[3 + m * N + e] == 0 and math.isfinite(g[e]) and (
                                                    eb < 0 or g[e] < g[eb]):
                                                eb = e
                                        if eb < 0:
                                            continue
                                        for t in range(3):
                                            mm, ee = (m, eb) if t == 0 else (
                                                1 - m, ip[3 + 2 * N + (m * N + eb) * 2 + t - 1])
                                            if ee < 0:
                                                continue
                                            seen = False
                                            for q in range(nb):
                                                if bi[q] == kk and bj[q] == j and bm[q] == mm and be[q] == ee:
                                                    seen = True
                                            if not seen:
                                                bi, bj, bm, be, bx, bp = _grow(bi, bj, bm, be, bx, bp, nb + 1)
                                                _append(bi, bj, bm, be, bx, bp, nb, kk, j, mm, ee, x0, -1)
                                                nb += 1
                    else:
                        # 2. the march from the contacts that lead to their neighbours in the effective rotation
                        if phase == 2:
                            phase = 3
                            for i in range(n):
                                for j in range(P):
                                    if phys[i, j]:
                                        floor[i, j] = te_s[i, j] + te_tie
                            nfront = 0
                            for o in range(nlab):
                                i, j = lab_i[o], lab_j[o]
                                if te_edge[i, j] >= best[i, j]:
                                    front_i[nfront] = i
                                    front_j[nfront] = j
                                    nfront += 1
                        else:   # the contacts found by the last round that lead, in row order, each once
                            for i in range(n):
                                for j in range(P):
                                    cand[i, j] = -1
                            nfront = 0
                            for a in range(new0.shape[0]):
                                i, j = top_i[a], top_j[a]
                                if new0[a] and te_edge[i, j] >= best[i, j] and cand[i, j] < 0:
                                    cand[i, j] = 0
                                    front_i[nfront] = i
                                    front_j[nfront] = j
                                    nfront += 1
                        if nfront == 0:
                            phase = 4
                            break
                        for i in range(n):
                            for j in range(P):
                                cand[i, j] = -1
                        # candidates (first come), then their systems: rows grouped by candidate
                        ncand = 0
                        ck, cj = np.empty(n * P, np.int64), np.empty(n * P, np.int64)
                        csys = np.empty((n * P, 3, 2), np.int64)
                        cns = np.empty(n * P, np.int64)
                        cx = np.empty((n * P, 5))
                        for f in range(nfront):
                            i, j = front_i[f], front_j[f]
                            m0, e0 = lab[i, j, 0], lab[i, j, 1]
                            # the systems: the contact's own, and from a corner its two boundaries as edges
                            sy = np.empty((3, 2), np.int64)
                            ns = 1
                            sy[0, 0], sy[0, 1] = m0, e0
                            ha = np.empty((2, 2), np.int64)   # the boundaries the contact's system holds
                            nh = _held(m0, e0, N, K, ha)
                            if nh == 2:
                                for b in range(2):
                                    if ip[3 + ha[b, 0] * N + ha[b, 1]] == 0:
                                        sy[ns, 0], sy[ns, 1] = ha[b, 0], ha[b, 1]
                                        ns += 1
                            have_cr = False
                            nbrs = _neighbours(i, j, n, P, pairs, span)
                            for q in range(nbrs.shape[0]):
                                kk, jk = nbrs[q, 0], nbrs[q, 1]
                                if lab[kk, jk, 0] >= 0 or cand[kk, jk] >= 0:
                                    continue
                                if phys[kk, jk] and not have_cr:
                                    have_cr = True
                                    r = i * P + j
                                    for m in range(2):
                                        if phys[i, j]:
                                            for e in range(N):
                                                cr[m, e] = False
                                        else:
                                            _crossed(kinds[1] if m == 0 else kinds[4], mp1 if m == 0 else mp2,
                                                     x[r, 2 * m], x[r, 2 * m + 1], S, g, dg, cr[m])
                                nk = 0
                                hb = np.empty((2, 2), np.int64)
                                for s_ in range(ns):
                                    keep = True
                                    if phys[kk, jk]:   # not on a boundary the contact marched from crossed
                                        nhb = _held(sy[s_, 0], sy[s_, 1], N, K, hb)
                                        for b in range(nhb):
                                            if cr[hb[b, 0], hb[b, 1]]:
                                                keep = False
                                    if keep:
                                        csys[ncand, nk, 0], csys[ncand, nk, 1] = sy[s_, 0], sy[s_, 1]
                                        nk += 1
                                if nk:
                                    cand[kk, jk] = ncand
                                    ck[ncand], cj[ncand], cns[ncand] = kk, jk, nk
                                    for c in range(5):
                                        cx[ncand, c] = x_edge[i, j, c]
                                    cx[ncand, 4] -= ratio * (phi1[kk] - phi1[i] + (pairs[jk] - pairs[j]) * T1)
                                    ncand += 1
                        if ncand == 0:
                            phase = 4
                            break
                        for a in range(ncand):
                            for s_ in range(cns[a]):
                                bi, bj, bm, be, bx, bp = _grow(bi, bj, bm, be, bx, bp, nb + 1)
                                _append(bi, bj, bm, be, bx, bp, nb, ck[a], cj[a], csys[a, s_, 0], csys[a, s_, 1],
                                        cx[a], -1)
                                nb += 1
                if nb == 0:
                    break
                level = 0
            k = nb
            ri, rj, rm, re = bi[:k].copy(), bj[:k].copy(), bm[:k].copy(), be[:k].copy()
            rx = bx[:k].copy()
            rp = bp[:k].copy()
            cs = np.empty((2, k))
            for a in range(k):
                phi = phi1[ri[a]] + pairs[rj[a]] * T1
                cs[0, a] = math.cos(phi)
                cs[1, a] = math.sin(phi)
                if ip[2] != 0 and rm[a] == 0 and re[a] >= N:   # a corner of the pinion's fillet junction?
                    c = re[a] - N
                    if c // K == FILLET and N <= c % K <= N + 2:
                        info[0] = 1
            if info[0] != 0:
                return
            screen_it = 1
        # ---- solve and screen it
        G, fo = np.empty((2, k, N)), np.empty((2, k))
        flags, codes = np.empty((6, k), np.bool_), np.empty((4, k), np.int64)
        solve_screen(kinds, p1, mp1, p2, mp2, ctol, junction, cs, rx, rm, re, d, M2, fp, max_iter, screen_it, phi1,
                     pairs, ri, rj, floor, te_edge, x_edge, last, G, fo, flags, codes)
        if mode == 0:
            for a in range(k):
                conv[a] = flags[0, a]
                ndot[a] = fo[1, a]
            continue
        G0, G1, te = G[0], G[1], fo[0]
        corner, good, ok, new, win = flags[1], flags[2], flags[3], flags[4], flags[5]
        # ---- labels of the pairs' new contacts
        for a in range(k):
            if win[a]:
                i, j = ri[a], rj[a]
                if lab[i, j, 2] < 0:
                    lab[i, j, 2] = nlab
                    lab_i[nlab] = i
                    lab_j[nlab] = j
                    nlab += 1
                lab[i, j, 0] = rm[a]
                lab[i, j, 1] = re[a]
        if level == 0:
            new0, top_i, top_j = new.copy(), ri, rj
        elif level == 1:
            new1, par1 = new.copy(), rp
        else:
            new2, par2 = new.copy(), rp
        # ---- solutions running past another boundary seed the corner of their boundaries (a corner: its vertex)
        nb = 0
        if level < 2:
            hb = np.empty((2, 2), np.int64)
            for a in range(k):
                i, j = ri[a], rj[a]
                bound = best[i, j] - te_tie
                if math.isnan(bound):
                    bound = te_edge[i, j]
                elif not math.isnan(te_edge[i, j]) and te_edge[i, j] > bound:
                    bound = te_edge[i, j]
                lead = not (te[a] <= bound) or corner[a]
                if not (good[a] and not ok[a] and lead):
                    continue
                nh = _held(rm[a], re[a], N, K, hb)
                for m in range(2):
                    for f in range(N):
                        if (G0[a, f] if m == 0 else G1[a, f]) >= 0.0 or ip[3 + m * N + f] != 0:
                            continue
                        held = False
                        for b in range(nh):
                            if hb[b, 0] == m and hb[b, 1] == f:
                                held = True
                        if held:
                            continue
                        if nh == 1:
                            am, ae = hb[0, 0], hb[0, 1]
                        else:   # a corner whose point of member m runs past its boundary: that vertex
                            if hb[0, 0] == hb[1, 0]:
                                continue
                            b = 0 if hb[0, 0] == m else 1
                            am, ae = hb[b, 0], hb[b, 1]
                        if m < am or (m == am and f < ae):   # the two boundaries in order
                            am, ae, bm_, be2 = m, f, am, ae
                        else:
                            bm_, be2 = m, f
                        code = N + (am * N + ae) * K + bm_ * N + be2
                        bi, bj, bm, be, bx, bp = _grow(bi, bj, bm, be, bx, bp, nb + 1)
                        _append(bi, bj, bm, be, bx, bp, nb, i, j, 0, code, rx[a], a)
                        nb += 1
        level = level + 1 if nb else 3


@kernel
def _held(m, e, N, K, out):
    """The boundaries (member, index) the system (m, e) holds its points on, in ``out (2, 2)``; returns 1 or 2."""
    if m == 0 and e >= N:
        c = e - N
        a, b = c // K, c % K
        out[0, 0] = 1 if a >= N else 0
        out[0, 1] = a - N * out[0, 0]
        out[1, 0] = 1 if b >= N else 0
        out[1, 1] = b - N * out[1, 0]
        return 2
    out[0, 0] = m
    out[0, 1] = e
    return 1


@kernel
def _neighbours(i, j, n, P, pairs, span):
    """(position, pair index) rows of the same and adjacent effective rotations of (i, j), but (i, j) itself, in the
    order of ``meshing/tca_edge.py``."""
    out = np.empty((2 + 3 * P, 2), np.int64)
    c = 0
    for kk in (i - 1, i + 1):
        if 0 <= kk < n:
            out[c, 0] = kk
            out[c, 1] = j
            c += 1
    if span and not 1 < i < n - 2:
        gi = i + (n - 1) * int(pairs[j])
        for dd in range(-1, 2):
            for jk in range(P):
                if jk != j:
                    kk = gi + dd - (n - 1) * int(pairs[jk])
                    if 0 <= kk < n:
                        out[c, 0] = kk
                        out[c, 1] = jk
                        c += 1
    return out[:c]
