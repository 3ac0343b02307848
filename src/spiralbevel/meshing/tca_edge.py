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

__all__ = ["solve_edge_contacts", "edge_stage", "corner_split", "corner_index"]

#: step of the forward difference of the curve tangent (surface parameters), and of the central difference of the
#: margin gradient of surfaces without compiled margins
_H_TAU = 1e-7
_H_PARAM = 1e-6
#: tolerance of the tangency equation where a margin gradient is a central difference (its round-off, about
#: 1e-16 |g| / _H_PARAM, is 1e-9 of the gradient; the TE is stationary along the curve at the root, so an error of
#: the tangency of 1e-9 moves the TE by its square)
_TOL_TANGENCY_FD = 1e-9
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


def _newton_numpy(prob, c1, s1, x, member, edge, corner, tol, max_iter):
    """The edge and corner Newton with the surfaces evaluated by numpy between compiled iterations; ``x`` updated in
    place. ``corner (m, 4)``: (ma, ea, mb, eb) of a corner row (member 0), -1 elsewhere."""
    m = len(x)
    conv = np.zeros(m, bool)
    ndot = np.full(m, np.nan)
    active = np.ones(m, bool)
    h = _H_TAU
    pert = np.array([[0, 0], [h, 0], [0, h]], float)
    surfs = (prob.pinion, prob.gear)
    d, M2, _ = prob._const
    tol_t = _ke.TOL_TANGENCY if all(_boundary(sf) is not None for sf in surfs) else _TOL_TANGENCY_FD
    for _ in range(max_iter + 1):
        a = np.flatnonzero(active)
        if not a.size:
            break
        k = a.size
        SA, SB = np.empty((k, 3, 3, 6)), np.empty((k, 3, 6))
        gA, dgA = np.empty((k, 3)), np.empty((k, 3, 2))
        gB, dgB = np.zeros(k), np.zeros((k, 2))
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
        ca = corner[a]
        for col, g_, dg_ in ((0, gA[:, 0], dgA[:, 0]), (2, gB, dgB)):  # a corner: its two margins
            for mm in (0, 1):
                c = ca[:, col] == mm
                if c.any():
                    with np.errstate(all="ignore"):
                        g_[c], dg_[c] = _margin_jets(surfs[mm], x[a[c], 2 * mm:2 * mm + 2], ca[c, col + 1])
        cols = np.ascontiguousarray(np.where(ca[:, 0:1] >= 0, 2 * ca[:, 0::2], -1), np.int64)
        xa = np.ascontiguousarray(x[a])
        state, nd = np.empty(k, np.int64), np.empty(k)
        with np.errstate(all="ignore"):
            _ke.edge_step_batch(SA, gA, dgA, SB, gB, dgB, np.ascontiguousarray(member[a]), cols, c1[a], s1[a], xa,
                                d, M2, h, tol, tol_t, _RCOND, state, nd)
        x[a], ndot[a] = xa, nd
        conv[a[state == 1]] = True
        active[a[state != 0]] = False
    return conv, ndot


def corner_split(prob, member, edge):
    """Corner systems among ``(member (m,), edge (m,))``: member 0 with an edge index k1 + a K + b past the pinion's
    k1 boundaries (K = k1 + k2 boundaries of both members, :func:`corner_index`) is the corner where boundary a meets
    boundary b, both numbered over the pinion's boundaries then the gear's.

    Returns
    -------
    corner : (m,) bool
    ma, ea, mb, eb : (m,) int
        Member (0 pinion, 1 gear) and boundary index of a and of b (0 where not a corner).
    """
    k1 = len(getattr(prob.pinion, "boundary_names", ()))
    K = max(1, k1 + len(getattr(prob.gear, "boundary_names", ())))
    member, edge = np.asarray(member), np.asarray(edge)
    corner = (member == 0) & (edge >= k1)
    c = np.where(corner, edge - k1, 0)
    a, b = c // K, c % K
    ma, mb = (a >= k1).astype(int), (b >= k1).astype(int)
    return corner, ma, a - k1 * ma, mb, b - k1 * mb


def corner_index(prob, a, b):
    """The edge index (with member 0) of the corner where boundary ``a = (member, index)`` meets ``b``: two
    boundaries of different members (their curves meet) or of the same member (its flank's vertex touches the
    other flank)."""
    k1 = len(prob.pinion.boundary_names)
    K = k1 + len(prob.gear.boundary_names)
    return k1 + (a[0] * k1 + a[1]) * K + b[0] * k1 + b[1]


def solve_edge_contacts(prob, phi1_eff, x0, member, edge, tol=1e-10, max_iter=30):
    """Newton solution of the edge-contact equations (module docstring) for a batch of systems, corner systems
    (:mod:`spiralbevel._core.tca_corner`: two boundary curves meeting) among them.

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
        Index into that member's ``boundary_names``; with member 0, an index :func:`corner_index` past the pinion's
        boundaries is a corner (the pinion's boundary e1 meets the gear's boundary e2, :func:`corner_split`).
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
    corner, ma, ea, mb, eb = corner_split(prob, member, edge)
    b1, b2 = _boundary(prob.pinion), _boundary(prob.gear)
    N = _ke.N_MARGINS
    if (prob._jets is not None and b1 is not None and b2 is not None
            and len(prob.pinion.boundary_names) == len(prob.gear.boundary_names) == N):
        edge = np.ascontiguousarray(np.where(corner, ma * N + ea, edge), np.int64)
        edge2 = np.ascontiguousarray(np.where(corner, mb * N + eb, -1), np.int64)
        (k1, p1), (k2, p2) = prob._jets
        d, M2, _ = prob._const
        conv, ndot, _ = _ke.edge_newton_jets(k1, p1, b1[0], b1[1], _shares(k1, p1, b1), k2, p2, b2[0], b2[1],
                                             _shares(k2, p2, b2), c1, s1, x, member, edge, edge2, d, M2, _H_TAU,
                                             tol, max_iter, _RCOND)
        return x, conv, ndot
    cols = np.where(corner[:, None], np.stack([ma, ea, mb, eb], 1), -1)
    conv, ndot = _newton_numpy(prob, c1, s1, x, member, np.where(corner, 0, edge), cols, tol, max_iter)
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

    def constraints(mem, ee):
        """The boundaries (member, index) a system puts its points on: one for an edge, two for a corner."""
        corner, ma, ea, mb, eb = corner_split(prob, mem, ee)
        return [((int(ma[a]), int(ea[a])), (int(mb[a]), int(eb[a]))) if corner[a] else ((int(mem[a]), int(ee[a])),)
                for a in range(len(mem))]

    def try_solve(ii, jj, mem, ee, x0, depth=2):
        """Solve the edge and corner systems (positions ii, pair indices jj, member, edge index) from x0 and keep
        the valid solutions that lead their pair's previous one. With ``depth`` > 0, a solution whose point runs
        past another boundary (the touched point beyond the mate's boundary, or the boundary point past the end of
        its own segment) seeds the corner of its boundaries with that one, solved in a further round.
        Returns which systems gave a new best contact of their pair."""
        if not len(ii):
            return np.zeros(0, bool)
        phi_eff = phi1[ii] + pairs[jj] * T1
        xs, conv, ndot = solve_edge_contacts(prob, phi_eff, x0, mem, ee, tol=tol)
        cons = constraints(mem, ee)
        tolm = 1e-9
        gg = [_all_margins(surfs[m], xs[:, 2 * m:2 * m + 2]) for m in (0, 1)]
        inside = [surface_contains(surfs[m], xs[:, 2 * m:2 * m + 2]) for m in (0, 1)]
        ok = conv.copy()
        for a, c in enumerate(cons):
            for m in (0, 1):
                own = [e for mm, e in c if mm == m]
                if not own:  # a member with no point held on a boundary: the point lies on its real flank
                    ok[a] &= inside[m][a]
                    continue
                g = gg[m][a].copy()
                g[own] = np.inf  # the system's own margins are 0 by construction
                with np.errstate(invalid="ignore"):
                    ok[a] &= bool(np.all(g >= -tolm))  # NaN (no surface) fails
        with np.errstate(invalid="ignore"):
            te = te_of(xs[:, 4], ii, jj)
            good = conv & (ndot < -0.5) & (np.abs(te) < np.pi / prob.z2)
        ok &= good
        new = np.zeros(len(ii), bool)
        for a in np.flatnonzero(ok):
            i, j = int(ii[a]), int(jj[a])
            if not np.isfinite(te_edge[i, j]) or te[a] > te_edge[i, j]:
                te_edge[i, j], x_edge[i, j] = te[a], xs[a]
                c = cons[a]
                if len(c) == 2:
                    ms = {m for m, _ in c}
                    who = "pinion/gear" if len(ms) == 2 else ("pinion", "gear")[c[0][0]]
                    label[(i, j)] = (who, f"{names[c[0][0]][c[0][1]]}/{names[c[1][0]][c[1][1]]} corner", 0,
                                     int(ee[a]))
                else:
                    label[(i, j)] = (("pinion", "gear")[mem[a]], names[mem[a]][ee[a]], int(mem[a]), int(ee[a]))
                new[a] = True
        if depth > 0:
            # a solution running past another boundary: the real teeth may first touch where its boundary meets
            # that one (two boundary curves meeting, or a flank's vertex against the mate), started from it
            # A corner is a point of an edge solution's boundary curve, met by the mate at a TE no larger than the
            # curve's stationary maximum: only edge solutions that could still lead their pair's other contacts seed
            # one (a corner bounds no vertex on its curve: corners seed theirs)
            with np.errstate(invalid="ignore"):
                bound = np.fmax(best_other[ii, jj] - te_tie, te_edge[ii, jj])
                lead = ~(te <= bound) | np.array([len(c) == 2 for c in cons])
            I, E = [], []
            for a in np.flatnonzero(good & ~ok & lead):
                c = cons[a]
                for m in (0, 1):
                    for f in np.flatnonzero(~(gg[m][a] >= 0)):
                        if names[m][f] == "generated" or (m, int(f)) in c:
                            continue
                        if len(c) == 1:
                            pair_ = (c[0], (m, int(f)))
                        else:  # a corner whose point of member m runs past the end of its boundary: that vertex
                            own = [b for b in c if b[0] == m]
                            if len(own) != 1 or len(c) != 2 or c[0][0] == c[1][0]:
                                continue
                            pair_ = (own[0], (m, int(f)))
                        pair_ = tuple(sorted(pair_))
                        I.append(a), E.append(corner_index(prob, *pair_))
            if I:
                I = np.array(I)
                new[I] |= try_solve(ii[I], jj[I], np.zeros(len(I), int), np.array(E), xs[I], depth - 1)
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

    def systems(m, e):
        """The systems tried at a neighbour of a contact on boundary e of member m: that one, and from a corner its
        two boundaries as edges too (past the corner one of the boundary curves runs against the mate's flank)."""
        c = constraints(np.array([m]), np.array([e]))[0]
        return [(m, e)] + ([b for b in c if names[b[0]][b[1]] != "generated"] if len(c) == 2 else [])

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
                    cand[(k, j)] = (systems(m, e), x0)
        if not cand:
            break
        keys = [(k, me) for k in cand for me in cand[k][0]]
        I = np.array([q[0][0] for q in keys])
        Jp = np.array([q[0][1] for q in keys])
        M = np.array([q[1][0] for q in keys])
        E = np.array([q[1][1] for q in keys])
        new = try_solve(I, Jp, M, E, np.array([cand[q[0]][1] for q in keys]))
        front = {(int(I[a]), int(Jp[a])) for a in np.flatnonzero(new) if leads(int(I[a]), int(Jp[a]))}
    return x_edge, te_edge, label
