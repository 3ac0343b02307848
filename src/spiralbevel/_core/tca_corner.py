"""Compiled corner contact of TCA: two flank boundary curves meeting.

Where an edge contact (:mod:`spiralbevel._core.tca_edge`) would touch the mate beyond the mate's own boundary, the
real teeth first touch where the two boundary curves meet: the pinion point on its boundary a, the gear point on
its boundary b, coincident in the fixed frame. Where the touching point runs past the end of its own boundary
segment, the flank's vertex (two boundaries of the same member meeting) touches the mate's flank: the same system
with both margins of that member. Unknowns x = (q1, q2, phi2) as in the edge contact, equations

    F[0:3] = o1 + R1 r1(q1) - o2 - R2 r2(q2)      mm (the two points coincide)
    F[3]   = g_a(q_ma)                            margin a of member ma (mm or rad): on boundary a
    F[4]   = g_b(q_mb)                            margin b of member mb: on boundary b

(no tangency: two curves in space meet at one gear rotation, a vertex touches a flank at one, and there the TE is
not stationary; the first touch of the teeth is the largest TE over all contacts, as for edges). The Jacobian is
analytic: rows 0-2 from the surface jets (:func:`spiralbevel._core.tca_newton.assemble`), rows 3-4 the analytic
margin gradients of :func:`spiralbevel._core.tca_edge.margins`.
"""

from __future__ import annotations

import numpy as np

from .jit import kernel
from .tca_newton import assemble

__all__ = ["corner_assemble"]


@kernel
def corner_assemble(S1, S2, g1, dg1, col1, g2, dg2, col2, c1, s1, x, d, M2, F, J, work):
    """Corner system F (5,), J (5, 5) of one system (module docstring).

    Parameters
    ----------
    S1, S2 : (3, 6) float
        Jets of the pinion at q1 and of the gear at q2 (member frames).
    g1, g2 : float
        Margins a and b at the points of their members (mm or rad).
    dg1, dg2 : (2,) float
        Their gradients w.r.t. their member's parameters.
    col1, col2 : int
        Columns of those parameters in x: 0 (pinion, q1) or 2 (gear, q2).
    c1, s1 : float
        cos, sin of the effective pinion angle.
    x : (5,) float
    d, M2 :
        Assembly constants (:mod:`spiralbevel._core.tca_newton`).
    F, J : (5,), (5, 5) float
        Output.
    work : (13, 6) float, C-contiguous
        Scratch: rows 0-2 the fixed-frame pinion data, rows 3-8 the gear data and its a2-cross.

    Returns
    -------
    float
        n1 . n2 of the fixed-frame unit normals.
    """
    S1f = work[0:3]
    Q = work[3:9]
    # E = 0 (rows 3-4 unused): a C-contiguous (2, 3) block and an int64 aj, the types of the other callers, so
    # that assemble is compiled once
    E0 = work[9].reshape((2, 3))
    E0[:, :] = 0.0
    assemble(S1, S2, c1, s1, x, d, M2, 1.0, E0, np.int64(-1), 0.0, F, J, S1f, Q)  # rows 0-2: the point coincidence
    F[3] = g1
    F[4] = g2
    for j in range(5):
        J[3, j] = 0.0
        J[4, j] = 0.0
    J[3, col1] = dg1[0]
    J[3, col1 + 1] = dg1[1]
    J[4, col2] = dg2[0]
    J[4, col2 + 1] = dg2[1]
    return S1f[0, 1] * Q[0, 1] + S1f[1, 1] * Q[1, 1] + S1f[2, 1] * Q[2, 1]
