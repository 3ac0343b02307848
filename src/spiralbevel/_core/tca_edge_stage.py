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
        Scratch (the floor of a solution's TE, :func:`~spiralbevel._core.tca_edge_screen.accept`).
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
    T1 = fp[9]
    N = N_MARGINS
    n, P = status.shape
    info[0] = 0
    phys = np.empty((n, P), np.bool_)
    best = np.empty((n, P), np.float64)
    last = np.empty((n, P), np.int64)
    cand = np.empty((n, P), np.int64)
    lorder = np.empty((2, n * P), np.int64)
    front = np.empty((2, n * P), np.int64)
    span = _stage_init(status, te_s, phi1, T1, phys, best, floor, te_edge, x_edge, lab)
    # margins of the surface contacts' points (both members), computed where a phase reads them: here alone (the
    # margins of a generated flank evaluate its blade jet; a kernel calling them would have LLVM optimise that again)
    Gs = np.empty((n * P, 2, N), np.float64)
    have = np.zeros(n * P, np.bool_)
    req = np.empty(n * P, np.int64)
    S = np.empty((3, 6), np.float64)
    dg = np.empty((N, 2), np.float64)
    nfront = 0
    # rows of the next batch: position, pair index, member, edge code, parent row; starts
    cap = 2 * N * n * P + 1
    R = np.empty((5, cap), np.int64)
    RX = np.empty((cap, 5), np.float64)
    # the new rows of the levels of a round (a batch and the corners it seeds, two levels deep) and their parents
    new0 = np.empty(0, np.bool_)
    new1 = np.empty(0, np.bool_)
    new2 = np.empty(0, np.bool_)
    par1 = np.empty(0, np.int64)
    par2 = np.empty(0, np.int64)
    top_i = np.empty(0, np.int64)
    top_j = np.empty(0, np.int64)
    phase = 0        # stage: 0 start, 1 candidates beyond a boundary, 2 seeds next to lost contacts, 3 march, 4 done
    level = 3        # level of the next batch in its round (3: the round is done)
    nlab = np.int64(0)
    nb = 0
    done = False
    while True:
        # ---- the next batch
        if mode == 0:
            if done:
                break
            done = True
            k = x.shape[0]
            rows = np.empty((5, 0), np.int64)
            ri, rj, rm, re, rp, rx = rows[0], rows[1], member, edge, rows[4], x
            cs = np.empty((2, k), np.float64)
            for a in range(k):
                cs[0, a] = c1[a]
                cs[1, a] = s1[a]
            screen_it = 0
        else:
            if level == 3:
                # the round is done: new of the deeper levels into the top one; then the next round
                if new2.shape[0]:
                    _propagate(new1, par2, new2)
                if new1.shape[0]:
                    _propagate(new0, par1, new1)
                new1 = np.empty(0, np.bool_)
                new2 = np.empty(0, np.bool_)
                nb = 0
                while nb == 0 and phase < 4:
                    if phase == 2:
                        phase = 3
                        nfront = _front_start(phys, te_s, fp, floor, te_edge, best, lorder, nlab, front)
                    elif phase == 3:
                        nfront = _front_next(new0, top_i, top_j, te_edge, best, cand, front)
                    nreq = _requests(phase, status, te_s, best, fp, phys, front, nfront, req)
                    for q in range(nreq):
                        r = req[q]
                        if not have[r]:
                            have[r] = True
                            for m in range(2):
                                margins(kinds[1 + 3 * m], mp1 if m == 0 else mp2, x[r, 2 * m], x[r, 2 * m + 1], S,
                                        Gs[r, m], dg)
                    if phase == 0:
                        phase = 1
                        nb = _rows_beyond(ip, x, status, te_s, best, fp, Gs, R, RX)
                    elif phase == 1:
                        phase = 2
                        nb = _rows_lost(ip, fp, x, phys, lab, phi1, Gs, R, RX)
                    else:
                        if nfront:
                            nb = _rows_march(ip, fp, phys, lab, phi1, pairs, span, x_edge, front, nfront, cand, Gs, R,
                                             RX)
                        if nb == 0:
                            phase = 4
                if nb == 0:
                    break
                level = 0
            k = nb
            rows = np.empty((5, k), np.int64)
            rx = np.empty((k, 5), np.float64)
            _take(R, RX, rows, rx)
            ri, rj, rm, re, rp = rows[0], rows[1], rows[2], rows[3], rows[4]
            cs = np.empty((2, k), np.float64)
            for a in range(k):
                phi = phi1[ri[a]] + pairs[rj[a]] * T1
                cs[0, a] = math.cos(phi)
                cs[1, a] = math.sin(phi)
            if ip[2] != 0 and _needs_junction(rm, re):
                info[0] = 1
                return
            screen_it = 1
        # ---- solve and screen it
        G = np.empty((2, k, N), np.float64)
        fo = np.empty((2, k), np.float64)
        flags = np.empty((6, k), np.bool_)
        codes = np.empty((4, k), np.int64)
        solve_screen(kinds, p1, mp1, p2, mp2, ctol, junction, cs, rx, rm, re, d, M2, fp, max_iter, screen_it, phi1,
                     pairs, ri, rj, floor, te_edge, x_edge, last, G, fo, flags, codes)
        if mode == 0:
            for a in range(k):
                conv[a] = flags[0, a]
                ndot[a] = fo[1, a]
            continue
        nlab = _labels(flags, rows, lab, lorder, nlab)
        if level == 0:
            new0 = flags[4].copy()
            top_i = ri.copy()
            top_j = rj.copy()
        elif level == 1:
            new1 = flags[4].copy()
            par1 = rp.copy()
        else:
            new2 = flags[4].copy()
            par2 = rp.copy()
        nb = 0
        if level < 2:
            if 2 * N * k > R.shape[1]:
                R = np.empty((5, 2 * N * k), np.int64)
                RX = np.empty((2 * N * k, 5), np.float64)
            nb = _children(ip, fp, rows, rx, G, fo, flags, best, te_edge, R, RX)
        level = level + 1 if nb else 3


@kernel
def _stage_init(status, te_s, phi1, T1, phys, best, floor, te_edge, x_edge, lab):
    """The stage's per-pair state: real contacts ``phys``, the largest TE of the real contacts of the other pairs
    ``best`` (-inf for P = 1), ``floor`` -inf, no edge contact and no label. Returns 1 where the positions span one
    pitch evenly (neighbours across the pairs: ``meshing/tca_edge.py``), else 0."""
    n, P = status.shape
    for i in range(n):
        for j in range(P):
            phys[i, j] = status[i, j] == 0 or status[i, j] == 1
            best[i, j] = -math.inf
            floor[i, j] = -math.inf
            te_edge[i, j] = math.nan
            for c in range(5):
                x_edge[i, j, c] = math.nan
            for c in range(3):
                lab[i, j, c] = -1
        if P > 1:
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
    span = 0
    if n > 1:
        span = 1
        st = T1 / (n - 1)
        for i in range(n - 1):
            if not math.fabs((phi1[i + 1] - phi1[i]) - st) <= 1e-9 * st:
                span = 0
    return span


@kernel
def _requests(phase, status, te_s, best, fp, phys, front, nfront, req):
    """The surface contacts (rows ``i P + j``) whose margins the next phase reads: 0 the candidates beyond a
    boundary, 1 the real contacts next to a lost one, 3 the front's contacts off the real flanks. Returns their
    number."""
    n, P = status.shape
    te_tie = fp[10]
    nr = 0
    if phase == 3:
        for f in range(nfront):
            i, j = front[0, f], front[1, f]
            if not phys[i, j]:
                req[nr] = i * P + j
                nr += 1
        return nr
    for i in range(n):
        for j in range(P):
            if phase == 0:
                use = status[i, j] == 2 and not te_s[i, j] < best[i, j] - te_tie
            else:
                use = phys[i, j] and ((i > 0 and not phys[i - 1, j]) or (i < n - 1 and not phys[i + 1, j]))
            if use:
                req[nr] = i * P + j
                nr += 1
    return nr


@kernel
def _crossed(Gs, r, cr):
    """``cr (2, N)``: the points of surface contact r lie beyond each boundary of their member (margins ``Gs (n P, 2,
    N)``: < 0 or NaN)."""
    for m in range(2):
        for e in range(N_MARGINS):
            cr[m, e] = not Gs[r, m, e] >= 0.0


@kernel
def _put(R, RX, k, i, j, m, e, xs, r, parent):
    """Row k of the next batch: position i, pair index j, system (m, e), start ``xs[r] (5,)``, parent row."""
    R[0, k] = i
    R[1, k] = j
    R[2, k] = m
    R[3, k] = e
    R[4, k] = parent
    for c in range(5):
        RX[k, c] = xs[r, c]


@kernel
def _take(R, RX, rows, rx):
    """The first k rows of ``R``, ``RX`` into ``rows (5, k)``, ``rx (k, 5)``."""
    for a in range(rows.shape[1]):
        for c in range(5):
            rows[c, a] = R[c, a]
            rx[a, c] = RX[a, c]


@kernel
def _rows_beyond(ip, x, status, te_s, best, fp, Gs, R, RX):
    """1. Pairs whose extended contact lies beyond a boundary and does not trail the best real contact of another pair:
    every boundary crossed and the boundary of the mate meeting it, from the extended contact; in the order (position,
    pair, member, boundary). Returns the number of rows."""
    N = N_MARGINS
    n, P = status.shape
    te_tie = fp[10]
    cr = np.empty((2, N), np.bool_)
    none = np.int64(-1)   # a typed value, not a literal: one signature of _put
    nb = 0
    for i in range(n):
        for j in range(P):
            if status[i, j] != 2 or te_s[i, j] < best[i, j] - te_tie:
                continue
            r = i * P + j
            _crossed(Gs, r, cr)
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
                        _put(R, RX, nb, i, j, M, E, x, r, none)
                        nb += 1
    return nb


@kernel
def _rows_lost(ip, fp, x, phys, lab, phi1, Gs, R, RX):
    """1b. Next to a position where a pair's real contact is lost (and not labelled yet): the boundary nearest that
    contact on each member and the mate's boundary meeting it, from that contact; in the order (position, pair,
    side), each system once (the first start kept). Returns the number of rows."""
    N = N_MARGINS
    n, P = phys.shape
    ratio = fp[5]
    x0 = np.empty((1, 5), np.float64)
    zero, none = np.int64(0), np.int64(-1)   # typed values, not literals: one signature of _put
    nb = 0
    for i in range(n):
        for j in range(P):
            for dd in range(2):
                kk = i - 1 if dd == 0 else i + 1
                if not (0 <= kk < n and phys[i, j] and not phys[kk, j]) or lab[kk, j, 0] >= 0:
                    continue
                r = i * P + j
                for c in range(5):
                    x0[0, c] = x[r, c]
                x0[0, 4] -= ratio * (phi1[kk] - phi1[i])
                for m in range(2):
                    g = Gs[r, m]
                    eb = -1
                    for e in range(N):
                        if ip[3 + m * N + e] == 0 and math.isfinite(g[e]) and (eb < 0 or g[e] < g[eb]):
                            eb = e
                    if eb < 0:
                        continue
                    for t in range(3):
                        mm = m if t == 0 else 1 - m
                        ee = eb if t == 0 else ip[3 + 2 * N + (m * N + eb) * 2 + t - 1]
                        if ee < 0:
                            continue
                        seen = False
                        for q in range(nb):
                            if R[0, q] == kk and R[1, q] == j and R[2, q] == mm and R[3, q] == ee:
                                seen = True
                        if not seen:
                            _put(R, RX, nb, kk, j, mm, ee, x0, zero, none)
                            nb += 1
    return nb


@kernel
def _front_start(phys, te_s, fp, floor, te_edge, best, lorder, nlab, front):
    """2. The march's floor (the TE of a pair's own real contact plus the tie) and its first front: the labelled
    pairs whose edge contact leads the other pairs' real contacts, in the order they were labelled. Returns its
    size."""
    n, P = phys.shape
    te_tie = fp[10]
    for i in range(n):
        for j in range(P):
            if phys[i, j]:
                floor[i, j] = te_s[i, j] + te_tie
    nf = 0
    for o in range(nlab):
        i, j = lorder[0, o], lorder[1, o]
        if te_edge[i, j] >= best[i, j]:
            front[0, nf] = i
            front[1, nf] = j
            nf += 1
    return nf


@kernel
def _front_next(new0, top_i, top_j, te_edge, best, cand, front):
    """The next front: the pairs whose contact the last round renewed and that lead, in row order, each once."""
    n, P = cand.shape
    for i in range(n):
        for j in range(P):
            cand[i, j] = -1
    nf = 0
    for a in range(new0.shape[0]):
        i, j = top_i[a], top_j[a]
        if new0[a] and te_edge[i, j] >= best[i, j] and cand[i, j] < 0:
            cand[i, j] = 0
            front[0, nf] = i
            front[1, nf] = j
            nf += 1
    return nf


@kernel
def _held(m, e, out):
    """The boundaries (member, index) the system (m, e) holds its points on, in ``out (2, 2)``; returns 1 or 2."""
    N = N_MARGINS
    if m == 0 and e >= N:
        c = e - N
        a, b = c // (2 * N), c % (2 * N)
        out[0, 0] = 1 if a >= N else 0
        out[0, 1] = a - N * out[0, 0]
        out[1, 0] = 1 if b >= N else 0
        out[1, 1] = b - N * out[1, 0]
        return 2
    out[0, 0] = m
    out[0, 1] = e
    return 1


@kernel
def _rows_march(ip, fp, phys, lab, phi1, pairs, span, x_edge, front, nfront, cand, Gs, R, RX):
    """2. One step of the march: the neighbours in the effective rotation (``meshing/tca_edge.py``) of each contact
    of the front that are not labelled, each from the first contact reaching it, with the contact's system (and from
    a corner its two boundaries as edges); into a real contact only the systems holding no boundary that the
    contact's extended solution crossed. Returns the number of rows (grouped by neighbour)."""
    N = N_MARGINS
    n, P = phys.shape
    T1, ratio = fp[9], fp[5]
    for i in range(n):
        for j in range(P):
            cand[i, j] = -1
    cr = np.empty((2, N), np.bool_)
    sy = np.empty((3, 2), np.int64)
    ha = np.empty((2, 2), np.int64)
    hb = np.empty((2, 2), np.int64)
    nbr = np.empty((2 + 3 * P, 2), np.int64)
    x0 = np.empty((1, 5), np.float64)
    zero, none = np.int64(0), np.int64(-1)   # typed values, not literals: one signature of _put
    nb = 0
    for f in range(nfront):
        i, j = front[0, f], front[1, f]
        # the systems: the contact's own, and from a corner its two boundaries as edges
        sy[0, 0] = lab[i, j, 0]
        sy[0, 1] = lab[i, j, 1]
        ns = 1
        if _held(sy[0, 0], sy[0, 1], ha) == 2:
            for b in range(2):
                if ip[3 + ha[b, 0] * N + ha[b, 1]] == 0:
                    sy[ns, 0] = ha[b, 0]
                    sy[ns, 1] = ha[b, 1]
                    ns += 1
        have_cr = False
        # neighbours: the same pair's positions before and after; near an end of the cycle the other pairs' at the
        # same and the adjacent effective rotations
        c = 0
        for dd in range(2):
            kk = i - 1 if dd == 0 else i + 1
            if 0 <= kk < n:
                nbr[c, 0] = kk
                nbr[c, 1] = j
                c += 1
        if span != 0 and not 1 < i < n - 2:
            gi = i + (n - 1) * int(pairs[j])
            for dd in range(3):
                for jk in range(P):
                    kk = gi + dd - 1 - (n - 1) * int(pairs[jk])
                    if jk != j and 0 <= kk < n:
                        nbr[c, 0] = kk
                        nbr[c, 1] = jk
                        c += 1
        for q in range(c):
            kk, jk = nbr[q, 0], nbr[q, 1]
            if lab[kk, jk, 0] >= 0 or cand[kk, jk] >= 0:
                continue
            if phys[kk, jk] and not have_cr:
                have_cr = True
                if phys[i, j]:
                    for m in range(2):
                        for e in range(N):
                            cr[m, e] = False
                else:
                    _crossed(Gs, i * P + j, cr)
            for c_ in range(5):
                x0[0, c_] = x_edge[i, j, c_]
            x0[0, 4] -= ratio * (phi1[kk] - phi1[i] + (pairs[jk] - pairs[j]) * T1)
            n0 = nb
            for s_ in range(ns):
                keep = True
                if phys[kk, jk]:
                    for b in range(_held(sy[s_, 0], sy[s_, 1], hb)):
                        if cr[hb[b, 0], hb[b, 1]]:
                            keep = False
                if keep:
                    _put(R, RX, nb, kk, jk, sy[s_, 0], sy[s_, 1], x0, zero, none)
                    nb += 1
            if nb > n0:
                cand[kk, jk] = 0
    return nb


@kernel
def _needs_junction(rm, re):
    """A row is a corner of the pinion's fillet junction with the gear's toe, heel or top edge."""
    N = N_MARGINS
    for a in range(rm.shape[0]):
        if rm[a] == 0 and re[a] >= N:
            c = re[a] - N
            if c // (2 * N) == FILLET and N <= c % (2 * N) <= N + 2:
                return True
    return False


@kernel
def _labels(flags, rows, lab, lorder, nlab):
    """The labels of the pairs' new contacts (rows ``win``, ``flags[5]``), the first labelling of each pair in order.
    Returns the number of labelled pairs."""
    for a in range(rows.shape[1]):
        if flags[5, a]:
            i, j = rows[0, a], rows[1, a]
            if lab[i, j, 2] < 0:
                lab[i, j, 2] = nlab
                lorder[0, nlab] = i
                lorder[1, nlab] = j
                nlab += 1
            lab[i, j, 0] = rows[2, a]
            lab[i, j, 1] = rows[3, a]
    return nlab


@kernel
def _children(ip, fp, rows, rx, G, fo, flags, best, te_edge, R, RX):
    """The corners seeded by a batch: a valid solution that is not on its flank (``good``, not ``ok``) and could still
    lead its pair (its TE above the other pairs' best real contact less the tie and above the pair's edge contact, or a
    corner) and whose point runs past another boundary (not the end of the generated surface): the corner of its
    boundary with that one, from the solution; a corner whose point of one member runs past that member's boundary:
    the vertex of its own boundary of that member with it (corners of two boundaries of the same member seed none).
    Returns the number of rows (parent: the seeding row)."""
    N = N_MARGINS
    te_tie = fp[10]
    hb = np.empty((2, 2), np.int64)
    zero = np.int64(0)   # a typed value, not a literal: one signature of _put
    nb = 0
    for a in range(rows.shape[1]):
        i, j = rows[0, a], rows[1, a]
        bound = best[i, j] - te_tie        # numpy's fmax of the two
        if math.isnan(bound):
            bound = te_edge[i, j]
        elif te_edge[i, j] > bound:
            bound = te_edge[i, j]
        lead = not (fo[0, a] <= bound) or flags[1, a]
        if not (flags[2, a] and not flags[3, a] and lead):
            continue
        nh = _held(rows[2, a], rows[3, a], hb)
        for m in range(2):
            for f in range(N):
                if G[m, a, f] >= 0.0 or ip[3 + m * N + f] != 0:
                    continue
                held = False
                for b in range(nh):
                    if hb[b, 0] == m and hb[b, 1] == f:
                        held = True
                if held:
                    continue
                if nh == 1:
                    am, ae = hb[0, 0], hb[0, 1]
                elif hb[0, 0] == hb[1, 0]:
                    continue
                else:
                    b = 0 if hb[0, 0] == m else 1
                    am, ae = hb[b, 0], hb[b, 1]
                if m < am or (m == am and f < ae):   # the two boundaries in order
                    code = N + (m * N + f) * 2 * N + am * N + ae
                else:
                    code = N + (am * N + ae) * 2 * N + m * N + f
                _put(R, RX, nb, i, j, zero, code, rx, a, a)
                nb += 1
    return nb


@kernel
def _propagate(new_p, parent, new_c):
    """``new_p[parent] |= new_c`` with numpy's fancy-index semantics (of rows sharing a parent the last one writes:
    ``new_p[parent[r]] = old new_p[parent[r]] | new_c[r]``)."""
    old = new_p.copy()
    for r in range(new_c.shape[0]):
        new_p[parent[r]] = old[parent[r]] | new_c[r]
