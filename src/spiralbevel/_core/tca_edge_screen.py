"""Compiled screening of solved edge and corner systems of TCA (:mod:`spiralbevel.meshing.tca_edge`): which boundaries
each system holds its points on, whether each point lies on the rest of its member's boundary, and whether the solution
is a contact at all.

A system is coded as in :func:`spiralbevel.meshing.tca_edge_solve.corner_split`: member 0 with an edge index
``k1 + a K + b`` past the pinion's ``k1`` boundaries is the corner where boundary a meets boundary b (both numbered over
the pinion's boundaries, then the gear's; ``K = k1 + k2``); any other row is the edge system of boundary ``edge`` of
``member``. The screen replaces a few dozen numpy calls on arrays of a handful of rows by one compiled loop;
:func:`edge_try` runs the Newton of the systems, their margins, TE and flank tests and the screen in one call (surfaces
with compiled jets and margins whose ``contains`` is "every margin >= -tol").
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel
from .tca_corner_screen import FILLET, corner_excluded
from .tca_edge import MARGIN_GENERATED, N_MARGINS, edge_newton_jets, margins, orientation

__all__ = ["screen", "accept", "edge_try", "solve_screen", "decode_systems", "orientation"]


@kernel
def screen(G0, G1, member, edge, k1, K, conv, ndot, te, te_lim, tolm, C0, C1, ii, jj, xs, floor, te_edge, x_edge,
           last, corner, ma, ea, mb, eb, good, ok, new, win):
    """Screen of ``m`` solved edge/corner systems (module docstring), outputs written in place.

    Parameters
    ----------
    G0, G1 : (m, k1) float, (m, k2) float
        All boundary margins of the pinion and gear points of the solutions (>= 0 on the flank; NaN off the surface).
    member, edge : (m,) int
        The systems (module docstring).
    k1, K : int
        Boundaries of the pinion; of both members (at least 1).
    conv : (m,) bool
        Converged.
    ndot : (m,) float
        n1 . n2 of the fixed-frame normals.
    te : (m,) float, rad
        TE of the solutions.
    te_lim : float, rad
        |TE| below which a solution belongs to a tooth pair of the mesh (half a gear pitch).
    tolm : float
        Margin below which a point not held on a boundary counts as beyond it.
    C0, C1 : (m,) bool
        The pinion / gear point lies on the real flank (the surface's ``contains``; read only for a member whose
        point the system holds on no boundary, and only where converged).
    ii, jj, xs, floor, te_edge, x_edge : see :func:`accept`
    last : (n, P) int
        Scratch of :func:`accept`.
    corner : (m,) bool
        Output: corner system.
    ma, ea, mb, eb : (m,) int
        Output: member and boundary index of the corner's boundaries a and b (0 where not a corner).
    good : (m,) bool
        Output: converged, opposed normals (n1 . n2 < -0.5) and |TE| < te_lim.
    ok : (m,) bool
        Output: good, and each point on its member's flank: on the rest of the boundaries it is held on (every other
        margin >= -tolm; NaN fails), on the real flank (``C0``, ``C1``) where it is held on none.
    new, win : (m,) bool
        Output: the rows ``ok`` that :func:`accept` keeps.
    """
    m = member.shape[0]
    for i in range(m):
        c = member[i] == 0 and edge[i] >= k1
        corner[i] = c
        a = (edge[i] - k1) // K if c else 0
        b = (edge[i] - k1) % K if c else 0
        ma[i] = 1 if a >= k1 else 0
        mb[i] = 1 if b >= k1 else 0
        ea[i] = a - k1 * ma[i]
        eb[i] = b - k1 * mb[i]
        # the boundaries held: an edge's one, a corner's two (member, index)
        h0m, h0e = (ma[i], ea[i]) if c else (member[i], edge[i])
        h1m, h1e = (mb[i], eb[i]) if c else (-1, -1)
        good[i] = conv[i] and ndot[i] < -0.5 and math.fabs(te[i]) < te_lim
        inside = bool(conv[i])
        for mm in range(2):
            if h0m == mm or h1m == mm:
                G = G0 if mm == 0 else G1
                for e in range(G.shape[1]):
                    held = (h0m == mm and h0e == e) or (h1m == mm and h1e == e)
                    if not held and not G[i, e] >= -tolm:
                        inside = False
            elif not (C0[i] if mm == 0 else C1[i]):
                inside = False
        ok[i] = inside and good[i]
    accept(ok, te, ii, jj, xs, floor, te_edge, x_edge, last, new, win)


@kernel
def accept(ok, te, ii, jj, xs, floor, te_edge, x_edge, last, new, win):
    """Keep the screened solutions (``ok (m,)``) that lead their pair's best contact so far, in row order.

    Row a (position ``ii[a]``, pair index ``jj[a]``, TE ``te[a]``, solution ``xs[a] (5,)``) replaces the pair's
    edge contact ``te_edge[i, j]``, ``x_edge[i, j] (5,)`` (in place) when its TE exceeds ``floor[i, j]`` and the pair
    has none (NaN) or a smaller TE; ``new[a]`` marks such rows, ``win[a]`` the last of them at each pair (whose
    boundaries label the contact). ``last (n, P)`` int is scratch.
    """
    for a in range(ok.shape[0]):
        last[ii[a], jj[a]] = -1
    for a in range(ok.shape[0]):
        new[a] = False
        win[a] = False
        if not ok[a]:
            continue
        i, j = ii[a], jj[a]
        if te[a] <= floor[i, j]:  # trails the pair's own surface contact of the real flanks
            continue
        if not math.isfinite(te_edge[i, j]) or te[a] > te_edge[i, j]:
            te_edge[i, j] = te[a]
            for k in range(5):
                x_edge[i, j, k] = xs[a, k]
            new[a] = True
            last[i, j] = a
    for a in range(ok.shape[0]):
        if new[a] and last[ii[a], jj[a]] == a:
            win[a] = True


@kernel
def edge_try(kinds, p1, mp1, p2, mp2, ctol, junction, c1, s1, x, member, edge, d, M2, h, tol, max_iter, rcond,
             screen_it, tep, phi1, pairs, ii, jj, floor, te_edge, x_edge, last, G0, G1, te, conv, ndot, corner, ma, ea,
             mb, eb, good, ok, new, win):
    """:func:`solve_screen` with its arguments one by one (the package calls it through
    :func:`spiralbevel._core.tca_edge_stage.edge_stage_run`; parameters: the corresponding parts of
    :func:`solve_screen`'s)."""
    m = x.shape[0]
    cs = np.empty((2, m))
    for i in range(m):
        cs[0, i] = c1[i]
        cs[1, i] = s1[i]
    fpar = np.empty(9)
    fpar[0] = h
    fpar[1] = tol
    fpar[2] = rcond
    for i in range(6):
        fpar[3 + i] = tep[i]
    G = np.empty((2, m, N_MARGINS))
    fo = np.empty((2, m))
    flags = np.empty((6, m), np.bool_)
    codes = np.empty((4, m), np.int64)
    solve_screen(kinds, p1, mp1, p2, mp2, ctol, junction, cs, x, member, edge, d, M2, fpar, max_iter, screen_it, phi1,
                 pairs, ii, jj, floor, te_edge, x_edge, last, G, fo, flags, codes)
    for i in range(m):
        conv[i] = flags[0, i]
        ndot[i] = fo[1, i]
        if screen_it != 0:
            te[i] = fo[0, i]
            for e in range(N_MARGINS):
                G0[i, e] = G[0, i, e]
                G1[i, e] = G[1, i, e]
            corner[i], good[i], ok[i], new[i], win[i] = flags[1, i], flags[2, i], flags[3, i], flags[4, i], flags[5, i]
            ma[i], ea[i], mb[i], eb[i] = codes[0, i], codes[1, i], codes[2, i], codes[3, i]


@kernel(inline="always")   # one call site in each compiled caller (solve_screen, tca_transfer._te_one)
def decode_systems(member, edge, junction, mk1, mk2, c1, s1, d, M2, mp2):
    """Boundaries of ``m`` edge/corner systems in the code of :func:`screen` for
    :func:`~spiralbevel._core.tca_edge.edge_newton_jets`: ``(ed (m,), ed2 (m,), skip (m,))``.

    A corner row (member 0, edge ``N_MARGINS + a K + b``, K = 2 N_MARGINS) has boundaries a and b numbered over both
    members; any other row has ``ed = edge``, ``ed2 = -1``. ``skip`` is True where the corner of the pinion's fillet
    junction (boundary FILLET) with the gear's toe, heel or top is proved to have no root on the sampled junction
    (:func:`~spiralbevel._core.tca_corner_screen.corner_excluded`; only with ``junction`` of 3 or more samples and
    both margin kinds ``mk1``, ``mk2`` generated). ``c1``, ``s1``: cos, sin of the effective pinion rotations (m,).
    """
    m = member.shape[0]
    N = N_MARGINS
    K = 2 * N
    ed = np.empty(m, np.int64)
    ed2 = np.empty(m, np.int64)
    for i in range(m):
        c = edge[i] - N
        if member[i] == 0 and c >= 0:
            ed[i] = c // K
            ed2[i] = c % K
        else:
            ed[i] = edge[i]
            ed2[i] = -1
    skip = np.zeros(m, np.bool_)
    if junction.shape[0] >= 3 and mk1 == MARGIN_GENERATED and mk2 == MARGIN_GENERATED:
        for i in range(m):
            if ed2[i] >= 0 and ed[i] == FILLET and N <= ed2[i] <= N + 2:
                skip[i] = corner_excluded(junction, c1[i], s1[i], d, M2, mp2, ed2[i] - N)
    return ed, ed2, skip


@kernel(inline="always")   # one call site in each compiled entry point
def solve_screen(kinds, p1, mp1, p2, mp2, ctol, junction, cs, x, member, edge, d, M2, fpar, max_iter, screen_it, phi1,
                 pairs, ii, jj, floor, te_edge, x_edge, last, G, fo, flags, codes):
    """Solve and screen ``m`` edge/corner systems in one compiled call: the Newton of
    :func:`~spiralbevel._core.tca_edge.edge_newton_jets` on ``x (m, 5)`` in place, then (``screen_it`` != 0) all
    margins of both points, the TE, the flank tests and :func:`screen`.

    Parameters
    ----------
    kinds : (6,) int
        Jet kind, margin kind and "margins share the jet" flag of the pinion, then of the gear.
    p1, mp1, p2, mp2 : float arrays
        Jet and margin parameters of the pinion and the gear.
    ctol : (4,) float
        Per member (pinion, gear): ``contains(q)`` is "every margin >= -ctol[member]" (NaN fails) and, where
        ``ctol[2 + member]`` is not 0, "on the sheet": :func:`orientation` of the jet at q times ``ctol[2 + member]``
        (the sign at the mean point) > 0 (NaN fails; ``GeneratedSurface.on_sheet``). The sheet test reads the jet that
        the margins evaluate: only for margins of kind ``MARGIN_GENERATED`` that share the surface's jet. A converged
        solution off the sheet of either member counts as not converged (``conv`` False), as in the separate steps of
        :func:`spiralbevel.meshing.tca_edge.edge_stage`.
    junction : (k, 3) float, mm
        Samples of the pinion's fillet junction curve (:func:`~spiralbevel._core.tca_corner_screen.junction_curve`,
        pinion frame), or k = 0: corner systems of that curve against the gear's toe, heel or top edge that
        :func:`~spiralbevel._core.tca_corner_screen.corner_excluded` proves to have no root on the sampled stretch
        are not solved (not converged).
    cs : (2, m) float
        cos, sin of the effective pinion rotations.
    x : (m, 5) float
        Starts, solutions on return.
    member, edge : (m,) int
        The systems in the code of :func:`screen` (corner rows: member 0, edge ``k1 + a K + b``; here k1 = k2 =
        N_MARGINS).
    d, M2 :
        As :func:`~spiralbevel._core.tca_edge.edge_newton_jets`.
    fpar : (9,) float, or longer (the rest unread)
        h, tol and rcond of :func:`~spiralbevel._core.tca_edge.edge_newton_jets`, then ``tep``: drive sign, phi2 of
        the mean point (rad), ratio z1/z2, phi1 of the mean point (rad), z2, and |TE| limit (rad):
        TE = drive (-(phi2_eff + 2 pi k / z2 - phi2_mean) - ratio (phi1 - phi1_mean)).
    max_iter : int
        As :func:`~spiralbevel._core.tca_edge.edge_newton_jets`.
    screen_it : int
        0: the Newton alone (outputs ``conv``, ``ndot``); else everything below.
    phi1 : (n,) float, rad
    pairs : (P,) float
        Tooth pair numbers k.
    ii, jj, floor, te_edge, x_edge, last :
        As :func:`screen` and :func:`accept`.
    G : (2, m, 4) float
        Output: all margins of the pinion (``G[0]``) and gear (``G[1]``) points.
    fo : (2, m) float
        Output: TE of the solutions (rad), and ``ndot``.
    flags : (6, m) bool
        Output: ``conv``, ``corner``, ``good``, ``ok``, ``new``, ``win`` as :func:`screen` (``conv`` and ``ndot``: as
        the Newton returns them; with ``screen_it``, ``conv`` also False off the sheet).
    codes : (4, m) int
        Output: ``ma``, ``ea``, ``mb``, ``eb`` as :func:`screen`.

    At most 30 arguments: CPython compiles a call with more as ``f(*args)``, which numba does not inline.
    """
    c1, s1 = cs[0], cs[1]
    h, tol, rcond = fpar[0], fpar[1], fpar[2]
    tep = fpar[3:9]
    G0, G1 = G[0], G[1]
    te, ndot = fo[0], fo[1]
    conv, corner, good, ok, new, win = flags[0], flags[1], flags[2], flags[3], flags[4], flags[5]
    ma, ea, mb, eb = codes[0], codes[1], codes[2], codes[3]
    m = x.shape[0]
    N = N_MARGINS
    K = 2 * N
    ed, ed2, skip = decode_systems(member, edge, junction, kinds[1], kinds[4], c1, s1, d, M2, mp2)
    cv, nd, _ = edge_newton_jets(kinds[0], p1, kinds[1], mp1, kinds[2] != 0, kinds[3], p2, kinds[4], mp2,
                                 kinds[5] != 0, c1, s1, x, member, ed, ed2, d, M2, h, tol, max_iter, rcond, skip)
    for i in range(m):
        conv[i] = cv[i]
        ndot[i] = nd[i]
    if screen_it != 0:
        S = np.empty((3, 6))
        dg = np.empty((N, 2))
        C0 = np.empty(m, np.bool_)
        C1 = np.empty(m, np.bool_)
        for i in range(m):
            margins(kinds[1], mp1, x[i, 0], x[i, 1], S, G0[i], dg)
            on = ctol[2] == 0.0 or orientation(S) * ctol[2] > 0.0   # S: the pinion's jet (margins of a generated flank)
            margins(kinds[4], mp2, x[i, 2], x[i, 3], S, G1[i], dg)
            on = on and (ctol[3] == 0.0 or orientation(S) * ctol[3] > 0.0)
            if not on:   # past a limit line of generation: no contact of the real teeth
                conv[i] = False
            in0 = conv[i]
            in1 = conv[i]
            for e in range(N):
                if not G0[i, e] >= -ctol[0]:
                    in0 = False
                if not G1[i, e] >= -ctol[1]:
                    in1 = False
            C0[i] = in0
            C1[i] = in1
            # TE in the operation order of meshing.tca (gear_angle, then the TE of the pair)
            phi2 = x[i, 4] + 2 * math.pi * pairs[jj[i]] / tep[4]
            te[i] = tep[0] * (-(phi2 - tep[1]) - tep[2] * (phi1[ii[i]] - tep[3]))
        screen(G0, G1, member, edge, np.int64(N), np.int64(K), conv, ndot, te, tep[5], 1e-9, C0, C1, ii, jj, x, floor,
               te_edge, x_edge, last, corner, ma, ea, mb, eb, good, ok, new, win)
