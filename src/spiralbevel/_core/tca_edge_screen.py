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

__all__ = ["screen"]


@kernel
def screen(G0, G1, member, edge, k1, K, conv, ndot, te, te_lim, tolm, corner, ma, ea, mb, eb, inside, own, good):
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
    corner : (m,) bool
        Output: corner system.
    ma, ea, mb, eb : (m,) int
        Output: member and boundary index of the corner's boundaries a and b (0 where not a corner).
    inside : (m, 2) bool
        Output: the point of member 0 / 1 lies on the rest of its boundaries (every margin >= -tolm, but those of the
        boundaries the system holds it on; NaN fails).
    own : (m, 2) bool
        Output: the system holds the point of member 0 / 1 on a boundary (else it must lie on the real flank).
    good : (m,) bool
        Output: converged, opposed normals (n1 . n2 < -0.5) and |TE| < te_lim.
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
        for mm in range(2):
            G = G0 if mm == 0 else G1
            ok = True
            for e in range(G.shape[1]):
                held = (h0m == mm and h0e == e) or (h1m == mm and h1e == e)
                if not held and not G[i, e] >= -tolm:
                    ok = False
            inside[i, mm] = ok
            own[i, mm] = h0m == mm or h1m == mm
        good[i] = conv[i] and ndot[i] < -0.5 and math.fabs(te[i]) < te_lim
