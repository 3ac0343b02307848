"""Compiled edge contact of TCA: flank boundary margins with their gradients, and the batched Newton of the edge system.

Edge contact (:mod:`spiralbevel.meshing.tca_edge`): the boundary curve g(q_A) = 0 of member A's flank touches
member B's flank. Unknowns x = (q1, q2, phi2) as in the surface contact (:mod:`spiralbevel._core.tca_newton`),
equations

    F[0:3] = o1 + R1 r1(q1) - o2 - R2 r2(q2)      mm (the curve point lies on B)
    F[3]   = g_e(q_A)                             the margin of boundary e (mm or rad): the point lies on A's edge
    F[4]   = n_B . t_A                            t_A = R_A tau / |tau|, tau = r_A,q0 g_q1 - r_A,q1 g_q0

(t_A the unit tangent of the boundary curve, n_B the fixed-frame unit normal of B: tangency of the curve to B, i.e.
the gear rotation is stationary along the curve); the same batched Newton solves corner systems (two boundary curves
meeting, :mod:`spiralbevel._core.tca_corner`). The Jacobian is analytic from the first-order surface jets
(:mod:`spiralbevel._core.jets`) and the analytic margin gradients of :func:`margins`, except the q_A-columns of the
tangency row, which need second derivatives of r_A and g: there d(tau)/dq_A is a forward difference of the analytic
tau at q_A + h e_j (the residual stays exact; the Jacobian only steers Newton, and an error of order h in it leaves the
convergence quadratic down to round-off).

Margin kinds (a surface exposes ``boundary_jet = (kind, prm)``; the margins are ordered as its ``boundary_names``):

* :data:`MARGIN_LOGSPIRAL` (0): the (varphi, phi) box of the log-spiral flank (root, top, toe, heel), rad;
  ``prm`` = (sin delta, psi_lo, psi_hi, psi flipped, phi_lo, phi_hi, phi flipped, has psi range, has phi range).
* :data:`MARGIN_GENERATED` (1): the face-milled generated flank (toe, heel, top, fillet), mm:
  R - R_i, R_e - R, h_face(R) - h with R = rho sin(delta) + z cos(delta), h = rho cos(delta) - z sin(delta),
  h_face(R) = h_am + (R - R_m) tan(delta_a - delta), and u - u_j (blade parameter at the fillet junction);
  ``prm`` = (sin delta, cos delta, R_i, R_e, h_am, R_m, tan(delta_a - delta), u_j, then the blade jet's parameters
  of :mod:`spiralbevel._core.generation_blade_jet`).
"""

from __future__ import annotations

import math

import numpy as np

from .generation_blade_jet import blade_jet_u
from .jets import surface_jet
from .jit import kernel
from .tca_corner import corner_assemble
from .tca_newton import assemble, step

__all__ = [
    "MARGIN_LOGSPIRAL",
    "MARGIN_GENERATED",
    "N_MARGINS",
    "margins",
    "margins_batch",
    "orientation",
    "edge_assemble",
    "edge_update",
    "edge_newton_jets",
    "edge_step_batch",
]

MARGIN_LOGSPIRAL = 0
MARGIN_GENERATED = 1
#: margins per surface (both kinds name four boundaries)
N_MARGINS = 4
#: tolerances of a converged edge system: the margin (mm or rad) and the tangency (cosine of the angle between the
#: curve and B's normal); the point coincidence uses the caller's ``tol`` (mm)
TOL_MARGIN = 1e-12
TOL_TANGENCY = 1e-11
#: step limits of the edge Newton: surface parameters 2 units, phi2 0.05 rad (far starts are not trusted)
_LIM_PARAM = 2.0
_LIM_PHI = 0.05


@kernel
def margins(mkind, mprm, q0, q1, S, g, dg):
    """All margins ``g (4,)`` (>= 0 on the flank) and their gradients ``dg (4, 2)`` w.r.t. (q0, q1) at one point.
    ``S (3, 6)`` is scratch (the blade jet of a generated flank). NaN where the surface is not defined."""
    if mkind == MARGIN_LOGSPIRAL:
        sd = mprm[0]
        for i in range(4):
            g[i] = math.inf
            dg[i, 0] = 0.0
            dg[i, 1] = 0.0
        if mprm[7] != 0.0:  # psi = (varphi - phi) sin(delta) between root and face cones
            psi = (q0 - q1) * sd
            a, b = psi - mprm[1], mprm[2] - psi
            if mprm[3] != 0.0:  # |psi| grows from the root cone to the face cone: lo > 0 keeps (root, top) order
                g[0], g[1] = a, b
                dg[0, 0], dg[0, 1], dg[1, 0], dg[1, 1] = sd, -sd, -sd, sd
            else:
                g[0], g[1] = b, a
                dg[0, 0], dg[0, 1], dg[1, 0], dg[1, 1] = -sd, sd, sd, -sd
        if mprm[8] != 0.0:  # phi between toe and heel
            a, b = q1 - mprm[4], mprm[5] - q1
            if mprm[6] != 0.0:
                g[2], g[3] = a, b
                dg[2, 1], dg[3, 1] = 1.0, -1.0
            else:
                g[2], g[3] = b, a
                dg[2, 1], dg[3, 1] = -1.0, 1.0
        return
    if mkind == MARGIN_GENERATED:
        u, u0, u1 = blade_jet_u(mprm[8:], q0, q1, S)
        sd, cd = mprm[0], mprm[1]
        x, y, z = S[0, 0], S[1, 0], S[2, 0]
        rho = math.hypot(x, y)
        R = rho * sd + z * cd
        h = rho * cd - z * sd
        tn = mprm[6]
        g[0] = R - mprm[2]
        g[1] = mprm[3] - R
        g[2] = mprm[4] + (R - mprm[5]) * tn - h
        g[3] = u - mprm[7]
        for j in range(2):
            drho = (x * S[0, 2 + j] + y * S[1, 2 + j]) / rho
            dR = drho * sd + S[2, 2 + j] * cd
            dh = drho * cd - S[2, 2 + j] * sd
            dg[0, j] = dR
            dg[1, j] = -dR
            dg[2, j] = tn * dR - dh
        dg[3, 0] = u0
        dg[3, 1] = u1
        return
    g[:] = math.nan
    dg[:, :] = math.nan


@kernel(inline="always")   # one expression
def orientation(S):
    """(r_q0 x r_q1) . n of one jet ``S (3, 6)`` (columns r, n, r_q0, r_q1, ...), in the operation order of
    ``meshing.generated_surface._orientation``: its sign tells the sheet of the envelope a generated point lies on
    (``GeneratedSurface.on_sheet``)."""
    return ((S[1, 2] * S[2, 3] - S[2, 2] * S[1, 3]) * S[0, 1] + (S[2, 2] * S[0, 3] - S[0, 2] * S[2, 3]) * S[1, 1]
            + (S[0, 2] * S[1, 3] - S[1, 2] * S[0, 3]) * S[2, 1])


@kernel
def margins_batch(mkind, mprm, q):
    """:func:`margins` at every row of ``q (m, 2)``: ``g (m, 4)``, ``dg (m, 4, 2)``, and ``o (m,)`` the
    :func:`orientation` of the jet the margins evaluate (a generated flank, kind ``MARGIN_GENERATED``; NaN for
    other kinds): the limit-line test of ``GeneratedSurface.on_sheet``."""
    m = q.shape[0]
    g = np.empty((m, N_MARGINS))
    dg = np.empty((m, N_MARGINS, 2))
    o = np.empty(m)
    S = np.empty((3, 6))
    for i in range(m):
        margins(mkind, mprm, q[i, 0], q[i, 1], S, g[i], dg[i])
        o[i] = orientation(S) if mkind == MARGIN_GENERATED else math.nan
    return g, dg, o


@kernel(inline="always")
def _tau(S, dg0, dg1, j):
    """Component j of the member-frame curve tangent tau = r_q0 g_q1 - r_q1 g_q0."""
    return S[j, 2] * dg1 - S[j, 3] * dg0


@kernel
def _to_fixed(member, v, c1, s1, c2, s2, M2, out, out_a):
    """Member-frame vector ``v (3,)`` to the fixed frame ``out`` (pinion: R_z(phi1) v; gear: B2 R_z(phi2) v, and
    ``out_a`` = a2 x (B2 R_z(phi2) v), the derivative w.r.t. phi2)."""
    if member == 0:
        out[0] = c1 * v[0] - s1 * v[1]
        out[1] = s1 * v[0] + c1 * v[1]
        out[2] = v[2]
        out_a[:] = 0.0
    else:
        u = c2 * v[0] - s2 * v[1]
        w = s2 * v[0] + c2 * v[1]
        for i in range(3):
            out[i] = M2[i, 0] * u + M2[i, 1] * w + M2[i, 2] * v[2]
            out_a[i] = M2[3 + i, 0] * u + M2[3 + i, 1] * w + M2[3 + i, 2] * v[2]


@kernel
def edge_assemble(SA, gA, dgA, SB, member, c1, s1, x, d, M2, h, F, J, work):
    """Edge system F (5,), J (5, 5) of one system (module docstring).

    Parameters
    ----------
    SA : (3, 3, 6) float
        Jet of member A at q_A, q_A + h e_0, q_A + h e_1.
    gA, dgA : (3,) float, (3, 2) float
        Margin of A's boundary and its gradient at the same three points.
    SB : (3, 6) float
        Jet of member B at q_B.
    member : int
        A: 0 pinion, 1 gear.
    c1, s1 : float
        cos, sin of the effective pinion angle.
    x : (5,) float
    d, M2 :
        Assembly constants (:mod:`spiralbevel._core.tca_newton`).
    h : float
        Step of the forward difference of tau.
    F, J : (5,), (5, 5) float
        Output.
    work : (13, 6) float, C-contiguous
        Scratch (no allocation per call): fixed-frame pinion data, gear data and its a2-cross, vectors.

    Returns
    -------
    float
        n1 . n2 of the fixed-frame unit normals (about -1 at a contact).
    """
    S1 = SA[0] if member == 0 else SB
    S2 = SB if member == 0 else SA[0]
    S1f = work[0:3]
    Q = work[3:9]
    # E = 0 (rows 3-4 unused): a C-contiguous (2, 3) block and an int64 aj, the types of the other callers, so
    # that assemble is compiled once
    E0 = work[9].reshape((2, 3))
    E0[:, :] = 0.0
    aval = 0.0
    assemble(S1, S2, c1, s1, x, d, M2, 1.0, E0, np.int64(-1), aval, F, J, S1f, Q)  # rows 0-2: the point coincidence
    c2, s2 = math.cos(x[4]), math.sin(x[4])
    ia = 0 if member == 0 else 2  # columns of q_A
    ib = 2 if member == 0 else 0  # columns of q_B
    nB = work[11, 0:3]
    v = work[9, 0:3]
    tf = work[10, 0:3]
    ta = work[11, 3:6]
    for i in range(3):
        nB[i] = Q[i, 1] if member == 0 else S1f[i, 1]
    for i in range(3):
        v[i] = _tau(SA[0], dgA[0, 0], dgA[0, 1], i)
    _to_fixed(member, v, c1, s1, c2, s2, M2, tf, ta)
    nrm = math.sqrt(tf[0] * tf[0] + tf[1] * tf[1] + tf[2] * tf[2])
    for i in range(3):
        tf[i] /= nrm
        ta[i] /= nrm
    F[3] = gA[0]
    F[4] = nB[0] * tf[0] + nB[1] * tf[1] + nB[2] * tf[2]
    for j in range(5):
        J[3, j] = 0.0
        J[4, j] = 0.0
    J[3, ia] = dgA[0, 0]
    J[3, ia + 1] = dgA[0, 1]
    for j in range(2):  # B's normal turns with q_B
        acc = 0.0
        for i in range(3):
            acc += (Q[i, 4 + j] if member == 0 else S1f[i, 4 + j]) * tf[i]
        J[4, ib + j] = acc
    acc = 0.0
    for i in range(3):  # phi2 turns the gear: B's normal (A = pinion) or A's tangent (A = gear)
        acc += Q[3 + i, 1] * tf[i] if member == 0 else nB[i] * ta[i]
    J[4, 4] = acc
    dv = work[9, 3:6]
    dtf = work[10, 3:6]
    dta = work[12, 0:3]
    for j in range(2):  # q_A: d(tau)/dq_j by a forward difference of the analytic tau
        for i in range(3):
            dv[i] = (_tau(SA[1 + j], dgA[1 + j, 0], dgA[1 + j, 1], i) - v[i]) / h
        _to_fixed(member, dv, c1, s1, c2, s2, M2, dtf, dta)
        tt = tf[0] * dtf[0] + tf[1] * dtf[1] + tf[2] * dtf[2]
        acc = 0.0
        for i in range(3):
            acc += nB[i] * (dtf[i] - tf[i] * tt)
        J[4, ia + j] = acc / nrm
    return S1f[0, 1] * Q[0, 1] + S1f[1, 1] * Q[1, 1] + S1f[2, 1] * Q[2, 1]


@kernel
def edge_update(F, J, x, tol, rcond, tol4):
    """One Newton update of an edge system in place (``tol4``: the tolerance of F[4], :data:`TOL_TANGENCY` or, for
    a corner system, :data:`TOL_MARGIN`); returns 1 converged (x unchanged), -1 failed (non-finite system or step),
    0 stepped."""
    for v in F:
        if not math.isfinite(v):
            return -1
    for v in J.flat:
        if not math.isfinite(v):
            return -1
    if (max(abs(F[0]), abs(F[1]), abs(F[2])) < tol and abs(F[3]) < TOL_MARGIN and abs(F[4]) < tol4):
        return 1
    dx = np.empty(5)
    step(J, F, rcond, dx)
    s = 1.0
    for j in range(5):
        if not math.isfinite(dx[j]):
            return -1
        lim = _LIM_PHI if j == 4 else _LIM_PARAM
        if abs(dx[j]) > lim:
            s = min(s, lim / abs(dx[j]))
    for j in range(5):
        x[j] += s * dx[j]
    return 0


@kernel
def _jet_points(kind, prm, mkind, mprm, share, e, q0, q1, h, SA, gA, dgA, Sm, gm, dgm):
    """Jet of member A and margin e (value, gradient) at q_A and q_A + h e_j into ``SA (3, 3, 6)``, ``gA (3,)``,
    ``dgA (3, 2)`` (``Sm``, ``gm``, ``dgm`` scratch). ``share``: the margins evaluate A's own jet (a generated flank:
    the blade jet of the margins is A's jet, written straight into SA, not evaluated twice)."""
    for k in range(3):
        a = q0 + (h if k == 1 else 0.0)
        b = q1 + (h if k == 2 else 0.0)
        if share:
            margins(mkind, mprm, a, b, SA[k], gm, dgm)
        else:
            surface_jet(kind, prm, a, b, SA[k])
            margins(mkind, mprm, a, b, Sm, gm, dgm)
        gA[k] = gm[e]
        dgA[k, 0] = dgm[e, 0]
        dgA[k, 1] = dgm[e, 1]


@kernel
def _corner_point(kind, prm, mkind, mprm, share, q0, q1, S, Sm, gm, dgm):
    """Jet ``S (3, 6)`` of a surface at (q0, q1) and all its margins ``gm (4,)`` with gradients ``dgm (4, 2)``."""
    if share:
        margins(mkind, mprm, q0, q1, S, gm, dgm)
    else:
        surface_jet(kind, prm, q0, q1, S)
        margins(mkind, mprm, q0, q1, Sm, gm, dgm)


@kernel
def edge_newton_jets(kind1, p1, mk1, mp1, share1, kind2, p2, mk2, mp2, share2, c1, s1, x, member, edge, edge2, d, M2,
                     h, tol, max_iter, rcond, skip):
    """Batched edge and corner Newton for two surfaces with compiled jets and margins, ``x (m, 5)`` updated in place
    (``share1``, ``share2``: see :func:`_jet_points`). A row with ``edge2 >= 0`` is a corner system
    (:mod:`spiralbevel._core.tca_corner`) of the boundaries ``edge`` and ``edge2``, each coded m N + e (boundary e
    of member m, N = :data:`N_MARGINS`; ``member`` is then ignored); otherwise the edge system of boundary ``edge``
    of ``member``. Rows with ``skip (m,) bool`` are not solved (not converged, ndot NaN, x unchanged: systems shown
    to have no root, :mod:`spiralbevel._core.tca_corner_screen`).

    Returns
    -------
    converged : (m,) bool
    ndot : (m,) float
        n1 . n2 of the fixed-frame normals at the final iterate.
    iterations : int
        Largest number of Newton updates of any system.
    """
    m = x.shape[0]
    conv = np.zeros(m, np.bool_)
    ndot = np.empty(m)
    SA = np.empty((3, 3, 6))
    SB = np.empty((3, 6))
    gA = np.empty(3)
    dgA = np.empty((3, 2))
    Sm = np.empty((3, 6))
    gm = np.empty(N_MARGINS)
    dgm = np.empty((N_MARGINS, 2))
    gm2 = np.empty((2, N_MARGINS))
    dgm2 = np.empty((2, N_MARGINS, 2))
    F = np.empty(5)
    J = np.empty((5, 5))
    work = np.empty((13, 6))
    iters = 0
    for i in range(m):
        if skip[i]:
            ndot[i] = math.nan
            continue
        A = member[i]
        corner = edge2[i] >= 0
        for it in range(max_iter + 1):
            if corner:
                _corner_point(kind1, p1, mk1, mp1, share1, x[i, 0], x[i, 1], SA[0], Sm, gm2[0], dgm2[0])
                _corner_point(kind2, p2, mk2, mp2, share2, x[i, 2], x[i, 3], SB, Sm, gm2[1], dgm2[1])
                ma, ea = edge[i] // N_MARGINS, edge[i] % N_MARGINS
                mb, eb = edge2[i] // N_MARGINS, edge2[i] % N_MARGINS
                ndot[i] = corner_assemble(SA[0], SB, gm2[ma, ea], dgm2[ma, ea], 2 * ma, gm2[mb, eb], dgm2[mb, eb],
                                          2 * mb, c1[i], s1[i], x[i], d, M2, F, J, work)
                r = edge_update(F, J, x[i], tol, rcond, TOL_MARGIN)
            else:
                if A == 0:
                    _jet_points(kind1, p1, mk1, mp1, share1, edge[i], x[i, 0], x[i, 1], h, SA, gA, dgA, Sm, gm, dgm)
                    surface_jet(kind2, p2, x[i, 2], x[i, 3], SB)
                else:
                    _jet_points(kind2, p2, mk2, mp2, share2, edge[i], x[i, 2], x[i, 3], h, SA, gA, dgA, Sm, gm, dgm)
                    surface_jet(kind1, p1, x[i, 0], x[i, 1], SB)
                ndot[i] = edge_assemble(SA, gA, dgA, SB, A, c1[i], s1[i], x[i], d, M2, h, F, J, work)
                r = edge_update(F, J, x[i], tol, rcond, TOL_TANGENCY)
            if r != 0 or it == max_iter:
                conv[i] = r == 1
                iters = max(iters, it)
                break
    return conv, ndot, iters


@kernel
def edge_step_batch(SA, gA, dgA, SB, gB, dgB, member, cols, c1, s1, x, d, M2, h, tol, tol_tangency, rcond, state,
                    ndot):
    """One iteration of the edge or corner Newton for surfaces evaluated by the caller: for every row,
    :func:`edge_assemble` from ``SA (m, 3, 3, 6)``, ``gA (m, 3)``, ``dgA (m, 3, 2)``, ``SB (m, 3, 6)`` (a corner
    row, ``cols (m, 2) >= 0``: :func:`~spiralbevel._core.tca_corner.corner_assemble` from the pinion's jet
    ``SA[:, 0]``, the gear's ``SB``, the margins ``gA[:, 0]``, ``dgA[:, 0]`` and ``gB (m,)``, ``dgB (m, 2)`` of the
    members at columns ``cols``; its n1 . n2 into ``ndot (m,)``),
    then :func:`edge_update` of ``x (m, 5)`` in place (the tangency to ``tol_tangency``); ``state (m,)`` receives its
    result (1 converged, -1 failed, 0 stepped)."""
    F = np.empty(5)
    J = np.empty((5, 5))
    work = np.empty((13, 6))
    for i in range(x.shape[0]):
        if cols[i, 0] >= 0:
            ndot[i] = corner_assemble(SA[i, 0], SB[i], gA[i, 0], dgA[i, 0], cols[i, 0], gB[i], dgB[i], cols[i, 1],
                                      c1[i], s1[i], x[i], d, M2, F, J, work)
            state[i] = edge_update(F, J, x[i], tol, rcond, TOL_MARGIN)
        else:
            ndot[i] = edge_assemble(SA[i], gA[i], dgA[i], SB[i], member[i], c1[i], s1[i], x[i], d, M2, h, F, J,
                                    work)
            state[i] = edge_update(F, J, x[i], tol, rcond, tol_tangency)
