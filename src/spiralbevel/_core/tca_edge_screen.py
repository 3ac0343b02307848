"""Compiled screening of solved edge and corner systems of TCA (:mod:`spiralbevel.meshing.tca_edge`): which boundaries
each system holds its points on, whether each point lies on the rest of its member's boundary, and whether the solution
is a contact at all.

A system is coded as in :func:`spiralbevel.meshing.tca_edge_solve.corner_split`: member 0 with an edge index
``k1 + a K + b`` past the pinion's ``k1`` boundaries is the corner where boundary a meets boundary b (both numbered over
the pinion's boundaries, then the gear's; ``K = k1 + k2``); any other row is the edge system of boundary ``edge`` of
``member``. The screen replaces a few dozen numpy calls on arrays of a handful of rows by one compiled loop.
"""

from __future__ import annotations

import math

from .jit import kernel

__all__ = ["screen", "accept"]


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
