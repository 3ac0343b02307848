"""Edge contact of TCA: a boundary curve of one member's real flank against the flank of the other.

Where the contact of two tooth surfaces would lie beyond a flank boundary (top edge, toe, heel, fillet junction),
the real teeth first touch along that boundary: the boundary curve c(t) of member A (on A's flank) meets the flank
of member B. As the gear turns back onto the pinion, every point c(t) would touch B at its own gear rotation; the
first touch is the point of the curve where that rotation leads furthest, a stationary point along the curve,
where B's normal is orthogonal to the curve's tangent. With the curve given implicitly on A's parameter plane by
its signed margin g(q_A) = 0 (the surfaces' ``boundary_margins``), the unknowns x = (q1, q2, phi2_eff) of the
surface contact solve the five equations

    o1 + R1(phi1) r1(q1) - o2 - R2(phi2) r2(q2) = 0          (3, mm: the curve point lies on B)
    g(q_A) = 0                                              (1: the point lies on A's boundary)
    n_B . t_A = 0,  t_A = R_A (r_A,u g_v - r_A,v g_u)/|.|     (1: tangency of the curve to B)

(the same unknowns and assembly pose as the surface contact of :mod:`spiralbevel.meshing.contact_problem`). The
Newton is compiled (:mod:`spiralbevel._core.tca_edge`: analytic Jacobian from the surface jets and the analytic
margin gradients, a forward difference of the curve tangent for its q_A-derivatives). Surfaces with compiled jets
and margins (``jet``, ``boundary_jet``) run entirely in compiled code; others are evaluated by numpy between the
compiled iterations (margins without ``boundary_jet``: ``boundary_margins`` with central differences).
"""

from __future__ import annotations

import numpy as np

from .._core import tca_batch as _b
from .._core import tca_edge as _ke
from .._core.jets import GENERATED
from .contact_surface import surface_derivatives

__all__ = ["solve_edge_contacts", "edge_stage"]

#: step of the forward difference of the curve tangent (surface parameters), and of the central difference of the
#: margin gradient of surfaces without compiled margins
_H_TAU = 1e-7
_H_PARAM = 1e-6
#: rank threshold of the Newton step (:func:`spiralbevel._core.tca_newton.step`)
_RCOND = 1e-12


def _boundary(surface):
    """``(kind, prm)`` of a surface's compiled margins, or None."""
    b = getattr(surface, "boundary_jet", None)
    if b is None:
        return None
    return int(b[0]), np.ascontiguousarray(b[1], float)


def _shares(kind, prm, b):
    """True where the margins ``b`` of a generated flank evaluate the surface's own jet ``(kind, prm)``."""
    return bool(kind == GENERATED and b[0] == _ke.MARGIN_GENERATED and np.array_equal(b[1][8:], prm))


def _all_margins(surface, q):
    """All boundary margins (m, k) of ``surface`` at ``q (m, 2)``: compiled where it has ``boundary_jet``."""
    b = _boundary(surface)
    if b is not None:
        return _ke.margins_batch(b[0], b[1], np.ascontiguousarray(q, float))[0]
    with np.errstate(invalid="ignore"):
        return np.asarray(surface.boundary_margins(q), float)


def _margin_jets(surface, q, e):
    """Margin ``e (m,)`` and its gradient of ``surface`` at ``q (m, 2)``: (g (m,), dg (m, 2))."""
    b = _boundary(surface)
    m = np.arange(len(q))
    if b is not None:
        g, dg = _ke.margins_batch(b[0], b[1], np.ascontiguousarray(q, float))
        return g[m, e], dg[m, e]
    h = _H_PARAM
    st = np.stack([q, q + (h, 0), q - (h, 0), q + (0, h), q - (0, h)], 0)  # (5, m, 2)
    with np.errstate(invalid="ignore"):
        g = np.asarray(surface.boundary_margins(st), float)[:, m, e]  # (5, m)
    return g[0], np.stack([(g[1] - g[2]) / (2 * h), (g[3] - g[4]) / (2 * h)], -1)


def _newton_numpy(prob, c1, s1, x, member, edge, tol, max_iter):
    """The edge Newton with the surfaces evaluated by numpy between compiled iterations; ``x`` updated in place."""
    m = len(x)
    conv = np.zeros(m, bool)
    ndot = np.full(m, np.nan)
    active = np.ones(m, bool)
    h = _H_TAU
    pert = np.array([[0, 0], [h, 0], [0, h]], float)
    surfs = (prob.pinion, prob.gear)
    d, M2, _ = prob._const
    for _ in range(max_iter + 1):
        a = np.flatnonzero(active)
        if not a.size:
            break
        k = a.size
        SA, SB = np.empty((k, 3, 3, 6)), np.empty((k, 3, 6))
        gA, dgA = np.empty((k, 3)), np.empty((k, 3, 2))
        for A in (0, 1):
            s = member[a] == A
            if not s.any():
                continue
            qa = (x[a[s], 2 * A:2 * A + 2][:, None, :] + pert).reshape(-1, 2)
            with np.errstate(all="ignore"):
                SA[s] = _b.stack_state(*surface_derivatives(surfs[A], qa)).reshape(-1, 3, 3, 6)
                SB[s] = _b.stack_state(*surface_derivatives(surfs[1 - A], x[a[s], 2 - 2 * A:4 - 2 * A]))
                g, dg = _margin_jets(surfs[A], qa, np.repeat(edge[a[s]], 3))
            gA[s], dgA[s] = g.reshape(-1, 3), dg.reshape(-1, 3, 2)
        xa = np.ascontiguousarray(x[a])
        state, nd = np.empty(k, np.int64), np.empty(k)
        with np.errstate(all="ignore"):
            _ke.edge_step_batch(SA, gA, dgA, SB, np.ascontiguousarray(member[a]), c1[a], s1[a], xa, d, M2, h, tol,
                                _RCOND, state, nd)
        x[a], ndot[a] = xa, nd
        conv[a[state == 1]] = True
        active[a[state != 0]] = False
    return conv, ndot


def solve_edge_contacts(prob, phi1_eff, x0, member, edge, tol=1e-10, max_iter=30):
    """Newton solution of the edge-contact equations (module docstring) for a batch of systems.

    Parameters
    ----------
    prob : ContactProblem
        The assembled pair (surfaces with ``boundary_margins``).
    phi1_eff : (m,) float, rad
        Effective pinion rotations (pair k: phi1 + 2 pi k / z1).
    x0 : (m, 5) float
        Starting points (q1, q2, phi2_eff), e.g. the surface contact beyond the boundary.
    member : (m,) int
        0: a boundary curve of the pinion against the gear flank; 1: of the gear against the pinion flank.
    edge : (m,) int
        Index into that member's ``boundary_names``.
    tol : float, mm
        Tolerance on the point coincidence (the boundary equation to 1e-12, the tangency to 1e-11:
        :mod:`spiralbevel._core.tca_edge`).
    max_iter : int
        Newton iterations at most (a step is limited to 2 parameter units and 0.05 rad of phi2).

    Returns
    -------
    x : (m, 5) float
    converged : (m,) bool
    ndot : (m,) float
        n1 . n2 of the fixed-frame unit normals at x (about -1 at a contact).
    """
    phi1_eff = np.asarray(phi1_eff, float).reshape(-1)
    x = np.array(x0, float, order="C").reshape(-1, 5)
    member = np.ascontiguousarray(member, np.int64)
    edge = np.ascontiguousarray(edge, np.int64)
    if len(x) == 0:
        return x, np.zeros(0, bool), np.zeros(0)
    c1, s1 = np.cos(phi1_eff), np.sin(phi1_eff)
    b1, b2 = _boundary(prob.pinion), _boundary(prob.gear)
    if prob._jets is not None and b1 is not None and b2 is not None:
        (k1, p1), (k2, p2) = prob._jets
        d, M2, _ = prob._const
        conv, ndot, _ = _ke.edge_newton_jets(k1, p1, b1[0], b1[1], _shares(k1, p1, b1), k2, p2, b2[0], b2[1],
                                             _shares(k2, p2, b2), c1, s1, x, member, edge, d, M2, _H_TAU, tol,
                                             max_iter, _RCOND)
        return x, conv, ndot
    conv, ndot = _newton_numpy(prob, c1, s1, x, member, edge, tol, max_iter)
    return x, conv, ndot


def _best_of_others(te):
    """For every entry of ``te (n, P)`` the largest value of the other entries of its row (-inf for P = 1)."""
    n, P = te.shape
    if P == 1:
        return np.full((n, 1), -np.inf)
    top = np.sort(te, axis=1)
    first = np.argmax(te, axis=1)
    return np.where(np.arange(P)[None, :] == first[:, None], top[:, -2:-1], top[:, -1:])


def edge_stage(prob, x, status, te_surface, te_of, phi1, pairs, tol=1e-10, te_tie=1e-11):
    """Edge contacts of every tooth pair whose surface contact leaves a real flank, and of the positions next to
    them where the surface contact is lost altogether.

    Parameters
    ----------
    prob : ContactProblem
    x : (n, P, 5) float
        Surface-contact solutions (q1, q2, phi2_eff) per position and pair.
    status : (n, P) int
        :class:`~spiralbevel.meshing.tca_result.ContactStatus` of the surface contacts (EDGE: the solution of the
        extended surfaces lies beyond a flank boundary).
    te_surface : (n, P) float, rad
        TE of the surface contacts (of the extended surfaces where ``status`` is EDGE).
    te_of : callable
        ``te_of(phi2_eff (m,), i (m,), j (m,)) -> (m,)`` TE (rad) of pair j at position i.
    phi1 : (n,) float, rad
    pairs : (P,) int
    tol : float, mm
        Tolerance of the edge solves.
    te_tie : float, rad
        TE differences below this are ties (a pair within te_tie of the best real contact may still lead).

    Returns
    -------
    x_edge : (n, P, 5) float
        Edge-contact solutions (NaN where none).
    te_edge : (n, P) float, rad
        Their TE (NaN where none).
    label : dict
        (i, j) -> (member "pinion"/"gear" whose boundary touches, boundary name, member index 0/1, boundary index).

    Notes
    -----
    Candidates at a pair whose surface contact is EDGE and does not trail the best real contact of another pair: every
    named boundary of both members (but the end of the
    generated surface), started from the extended solution projected onto that boundary. A solution counts if the
    edge point lies on the rest of its own flank's boundary segment (every other margin >= 0), the touched point on
    the other member's real flank, the flank normals of the two members are opposed and the TE is within half a gear
    pitch. Then a march over positions: a pair without a valid contact next to a position where its edge contact
    leads the surface contacts of the other pairs is solved from that neighbour (the same edge), until no new one
    is found (edge contacts that lead nowhere do not decide the contact and are not followed).
    """
    from .contact_surface import surface_contains

    n, P = status.shape
    T1 = 2 * np.pi / prob.z1
    surfs = (prob.pinion, prob.gear)
    names = [tuple(getattr(s, "boundary_names", ())) for s in surfs]
    x_edge = np.full((n, P, 5), np.nan)
    te_edge = np.full((n, P), np.nan)
    label = {}
    if not all(names):
        return x_edge, te_edge, label

    def try_solve(ii, jj, mem, ee, x0):
        if not len(ii):
            return np.zeros(0, bool)
        phi_eff = phi1[ii] + pairs[jj] * T1
        xs, conv, ndot = solve_edge_contacts(prob, phi_eff, x0, mem, ee, tol=tol)
        ok = conv.copy()
        tolm = 1e-9
        for m in (0, 1):
            s = mem == m
            if not s.any():
                continue
            gg = _all_margins(surfs[m], xs[s, 2 * m:2 * m + 2])
            gg[np.arange(s.sum()), ee[s]] = np.inf  # the edge's own margin is 0 by construction
            with np.errstate(invalid="ignore"):
                ok[s] &= np.all(gg >= -tolm, axis=1)  # NaN (no surface) fails
        ok &= np.where(mem == 0, surface_contains(prob.gear, xs[:, 2:4]), surface_contains(prob.pinion, xs[:, 0:2]))
        with np.errstate(invalid="ignore"):
            ok &= ndot < -0.5
            te = te_of(xs[:, 4], ii, jj)
            ok &= np.abs(te) < np.pi / prob.z2
        new = np.zeros(len(ii), bool)
        for a in np.flatnonzero(ok):
            i, j = int(ii[a]), int(jj[a])
            if not np.isfinite(te_edge[i, j]) or te[a] > te_edge[i, j]:
                te_edge[i, j], x_edge[i, j] = te[a], xs[a]
                label[(i, j)] = (("pinion", "gear")[mem[a]], names[mem[a]][ee[a]], int(mem[a]), int(ee[a]))
                new[a] = True
        return new

    # 1. pairs whose surface contact lies beyond a boundary: the boundaries crossed there on either member, and the
    # boundary of the other member that meets it (a top edge runs into the mate's root: fillet junction)
    phys = (status == 0) | (status == 1)
    te_phys = np.where(phys, te_surface, -np.inf)
    # an edge contact trails the extended surfaces' contact beyond that edge (it is a touch of a part of the same
    # flank): pairs whose extended contact trails the best real contact of another pair cannot lead, are not solved
    best_other = _best_of_others(te_phys)
    ii, jj = np.nonzero((status == 2) & ~(te_surface < best_other - te_tie))  # ContactStatus.EDGE
    mate = {"top": ("fillet", "root"), "fillet": ("top",), "root": ("top",)}
    I, Jp, M, E = [], [], [], []
    if ii.size:
        g = [_all_margins(surfs[0], x[ii, jj, 0:2]), _all_margins(surfs[1], x[ii, jj, 2:4])]
        for a in range(ii.size):
            want = set()
            for m in (0, 1):
                for e in np.flatnonzero(~(g[m][a] >= 0)):
                    nm = names[m][e]
                    if nm == "generated":
                        continue
                    want.add((m, int(e)))
                    for other in mate.get(nm, ()):
                        if other in names[1 - m]:
                            want.add((1 - m, names[1 - m].index(other)))
            for m, e in sorted(want):
                I.append(ii[a]), Jp.append(jj[a]), M.append(m), E.append(e)
    if I:
        I, Jp, M, E = (np.array(v, int) for v in (I, Jp, M, E))
        try_solve(I, Jp, M, E, x[I, Jp])
    # 1b. a pair whose surface solve is lost altogether next to a position where it touches on the real flanks: the
    # boundary nearest that contact on each member (and the mate's boundary that meets it) is tried from there
    seeds = {}
    # real contacts next to a position of the same pair that has none (d = -1: the one before is lost, +1: after)
    lost = np.zeros((2, n, P), bool)
    lost[0, 1:] = phys[1:] & ~phys[:-1]
    lost[1, :-1] = phys[:-1] & ~phys[1:]
    near = lost.any(axis=0)
    g_phys = [np.full((n, P, len(names[m])), np.nan) for m in (0, 1)]
    if near.any():
        for m in (0, 1):
            g_phys[m][near] = _all_margins(surfs[m], x[near][:, 2 * m:2 * m + 2])
    dd, ii, jj = np.nonzero(lost)
    for i, j, d in sorted(zip(ii.tolist(), jj.tolist(), (2 * dd - 1).tolist())):  # the order of (i, j, d)
        k = i + d
        if (k, j) in label:
            continue
        x0 = x[i, j].copy()
        x0[4] -= prob.ratio * (phi1[k] - phi1[i])
        for m in (0, 1):
            gm = g_phys[m][i, j]
            usable = [e for e, nm in enumerate(names[m]) if nm != "generated" and np.isfinite(gm[e])]
            if not usable:
                continue
            e = min(usable, key=lambda e: gm[e])
            seeds.setdefault((k, j, m, e), x0)
            for other in mate.get(names[m][e], ()):
                if other in names[1 - m]:
                    seeds.setdefault((k, j, 1 - m, names[1 - m].index(other)), x0)
    if seeds:
        keys = list(seeds)
        try_solve(np.array([q[0] for q in keys]), np.array([q[1] for q in keys]), np.array([q[2] for q in keys]),
                  np.array([q[3] for q in keys]), np.array([seeds[q] for q in keys]))

    # 2. march to neighbouring positions without a contact of the real flanks (the surface contact of the pair is
    # lost there altogether), from the neighbour's edge solution
    def leads(i, j):
        """Pair j's edge contact at position i leads the surface contacts of the other pairs there."""
        return te_edge[i, j] >= best_other[i, j]

    front = {key for key in label if leads(*key)}
    while front:
        cand = {}
        for (i, j) in front:
            _, _, m, e = label[(i, j)]
            for d in (-1, 1):
                k = i + d
                if 0 <= k < n and not phys[k, j] and (k, j) not in label and (k, j) not in cand:
                    x0 = x_edge[i, j].copy()
                    x0[4] -= prob.ratio * (phi1[k] - phi1[i])
                    cand[(k, j)] = (m, e, x0)
        if not cand:
            break
        keys = list(cand)
        I = np.array([k[0] for k in keys])
        Jp = np.array([k[1] for k in keys])
        M = np.array([cand[k][0] for k in keys])
        E = np.array([cand[k][1] for k in keys])
        new = try_solve(I, Jp, M, E, np.array([cand[k][2] for k in keys]))
        front = {(int(I[a]), int(Jp[a])) for a in np.flatnonzero(new) if leads(int(I[a]), int(Jp[a]))}
    return x_edge, te_edge, label
