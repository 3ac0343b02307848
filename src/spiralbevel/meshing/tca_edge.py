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

(the same unknowns and assembly pose as the surface contact of :mod:`spiralbevel.meshing.contact_problem`).
Where the touched point would lie beyond the mate's boundary, the teeth first touch where the two boundary curves
meet, a corner: the tangency is replaced by the mate's boundary equation (both points on their own boundaries and
coincident); where the boundary point runs past the end of its own boundary, the flank's vertex touches the mate (both
equations of the same member) (:mod:`spiralbevel._core.tca_corner`; the TE is not stationary there). The
Newton (:mod:`spiralbevel.meshing.tca_edge_solve`) is compiled (:mod:`spiralbevel._core.tca_edge`: analytic
Jacobian from the surface jets and the analytic margin gradients, a forward difference of the curve tangent for its
q_A-derivatives). Surfaces with compiled jets
and margins (``jet``, ``boundary_jet``) run entirely in compiled code; others are evaluated by numpy between the
compiled iterations (margins without ``boundary_jet``: ``boundary_margins`` with central differences).
"""

from __future__ import annotations

import numpy as np

from .._core import tca_edge_screen as _ks
from .._core import tca_edge_stage as _kst
from .tca_edge_solve import _all_margins, corner_index, corner_split, margins_of, solve_edge_contacts  # noqa: F401
from .tca_edge_solve import _H_TAU, _RCOND, _setup, compiled_args, junction_samples

__all__ = ["solve_edge_contacts", "edge_stage", "corner_split", "corner_index"]


def _best_of_others(te):
    """For every entry of ``te (n, P)`` the largest value of the other entries of its row (-inf for P = 1)."""
    n, P = te.shape
    if P == 1:
        return np.full((n, 1), -np.inf)
    top = np.sort(te, axis=1)
    first = np.argmax(te, axis=1)
    return np.where(np.arange(P)[None, :] == first[:, None], top[:, -2:-1], top[:, -1:])


#: the boundaries of the other member that meet a boundary (a top edge runs into the mate's root: fillet junction)
_MATE = {"top": ("fillet", "root"), "fillet": ("top",), "root": ("top",)}


def _stage_ints(names):
    """The integer parameters of :func:`spiralbevel._core.tca_edge_stage.edge_stage_run` fixed by the boundary names
    of both members (kept per pair of name tuples): the end-of-generated-surface flags and the mate table of both
    members' boundaries (mode, iterations and the junction flag are set per call)."""
    key = (names[0], names[1])
    ip = _STAGE_INTS.get(key)
    if ip is None:
        N = _kst.N_MARGINS
        ip = np.zeros(_kst.IP_SIZE, np.int64)
        mates = ip[3 + 2 * N:].reshape(2, N, 2)
        mates[:] = -1
        for m in (0, 1):
            for e, nm in enumerate(names[m]):
                ip[3 + m * N + e] = nm == "generated"
                t = 0
                for other in _MATE.get(nm, ()):
                    if other in names[1 - m]:
                        mates[m, e, t] = names[1 - m].index(other)
                        t += 1
        _STAGE_INTS[key] = ip
    return ip


_STAGE_INTS: dict[tuple, np.ndarray] = {}


def _label(names, k1, K, m, e):
    """The label of a contact of system (m, e) (:func:`edge_stage`, Returns)."""
    if m == 0 and e >= k1:   # a corner (corner_split)
        a, b = divmod(e - k1, K)
        ma, mb = int(a >= k1), int(b >= k1)
        ea, eb = a - k1 * ma, b - k1 * mb
        who = "pinion/gear" if ma != mb else ("pinion", "gear")[ma]
        return who, f"{names[ma][ea]}/{names[mb][eb]} corner", 0, e
    return ("pinion", "gear")[m], names[m][e], m, e


def _stage_compiled(prob, fast, x, status, te_surface, phi1, pairs, tol, te_tie, te_frame, names):
    """:func:`edge_stage` in one compiled call (:func:`spiralbevel._core.tca_edge_stage.edge_stage_run`), run again
    with the junction samples of the corner proof where the stage first needs them."""
    n, P = status.shape
    kinds, p1, mp1, p2, mp2, ctol = fast
    d, M2, _ = prob._const
    fp = np.array([_H_TAU, tol, _RCOND, te_frame[0], te_frame[1], prob.ratio, te_frame[2], prob.z2, np.pi / prob.z2,
                   2 * np.pi / prob.z1, te_tie], float)
    ip = _stage_ints(names).copy()
    ip[0], ip[1] = 1, 30
    junction = junction_samples(prob, _I0, _I0)
    ip[2] = "_junction" not in prob.__dict__   # not computed yet: the stage stops where it needs them
    xs = np.ascontiguousarray(x, float).reshape(n * P, 5)
    st = np.ascontiguousarray(status, np.int64)
    tes = np.ascontiguousarray(te_surface, float)
    phi1c, pairs_f = np.ascontiguousarray(phi1, float), np.ascontiguousarray(pairs, float)
    info = np.zeros(1, np.int64)
    while True:
        x_edge, te_edge = np.empty((n, P, 5)), np.empty((n, P))
        lab, floor = np.empty((n, P, 3), np.int64), np.empty((n, P))
        _kst.edge_stage_run(kinds, p1, mp1, p2, mp2, ctol, junction, d, M2, fp, ip, _F0, _F0, xs, _I0, _I0, _B0,
                            _F0, st, tes, phi1c, pairs_f, floor, te_edge, x_edge, lab, info)
        if not info[0]:
            break
        junction = junction_samples(prob, np.zeros(1, np.int64),
                                    np.array([corner_index(prob, (0, _kst.FILLET), (1, 0))], np.int64))
        ip[2] = 0
    label = {}
    k1, K = len(names[0]), len(names[0]) + len(names[1])
    o = lab[..., 2].reshape(-1)
    on = (o >= 0).nonzero()[0]
    lm, le = lab[..., 0].reshape(-1).tolist(), lab[..., 1].reshape(-1).tolist()
    for f in on[np.argsort(o[on], kind="stable")].tolist():
        label[divmod(f, P)] = _label(names, k1, K, lm[f], le[f])
    return x_edge, te_edge, label


_I0, _F0, _B0, _X0 = np.zeros(0, np.int64), np.zeros(0), np.zeros(0, bool), np.zeros((0, 5))


def edge_stage(prob, x, status, te_surface, te_of, phi1, pairs, tol=1e-10, te_tie=1e-11, te_frame=None):
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
    te_frame : (drive, phi2_mean, phi1_mean), optional
        The TE of ``te_of`` as numbers, TE = drive (-(phi2 - phi2_mean) - ratio (phi1 - phi1_mean)) with phi2 the
        gear rotation of the pair (rad): given, batches of surfaces with compiled jets and margins are solved and
        screened in one compiled call (:func:`spiralbevel._core.tca_edge_screen.edge_try`).

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
    pitch. Then a march over the effective pinion rotation (positions of a pair, continued at the ends of the cycle
    by the adjacent pair's, which repeat the same rotations one pitch apart): a pair next to a position where its
    edge contact leads the surface contacts of the other pairs is solved from that neighbour (the same edge; from a
    corner also its two boundaries as edges), where it has no valid contact, and also where it has a surface contact
    of the real flanks, which the edge must then lead (a boundary of the same teeth touching first, e.g. the gear's
    fillet junction against the pinion flank; not on a boundary that the pair's extended contact crossed at the
    position marched from), until no new one is found (edge contacts that lead nowhere do not decide the contact and
    are not followed). Corners are seeded by solutions that run past another boundary (an edge's touched
    point beyond the mate's boundary, where it could still lead: the corner's TE is bounded by the edge's; a
    corner's point past the end of its own boundary: that flank's vertex) and labelled ("pinion/gear",
    "heel/top corner") or, for a vertex, ("pinion", "heel/fillet corner").
    """
    n, P = status.shape
    T1 = 2 * np.pi / prob.z1
    surfs = (prob.pinion, prob.gear)
    names = [tuple(getattr(s, "boundary_names", ())) for s in surfs]
    if all(names) and te_frame is not None:
        # the whole stage in one compiled call (spiralbevel._core.tca_edge_stage) where both surfaces have compiled
        # jets and margins and a margin test (with the limit-line test of a generated flank) as ``contains``, and
        # the TE's frame is given; the statement below is its reference, run for other surfaces
        fast = compiled_args(prob)
        if fast is not None and min(fast[5][:2]) >= 0:
            return _stage_compiled(prob, fast, x, status, te_surface, phi1, pairs, tol, te_tie, te_frame, names)
    x_edge = np.full((n, P, 5), np.nan)
    te_edge = np.full((n, P), np.nan)
    label = {}
    # a solution at (i, j) counts only above floor[i, j]: -inf, but in the march (2.) the TE of the pair's own surface
    # contact of the real flanks where it has one
    floor = np.full((n, P), -np.inf)
    last = np.empty((n, P), np.int64)  # scratch of the compiled acceptance
    if not all(names):
        return x_edge, te_edge, label
    _, k1, K, _, _ = _setup(prob)  # boundaries of the pinion, of both members
    from .contact_surface import surface_contains, surface_on_sheet
    from .generated_surface import EDGE_TOL

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
        k = len(ii)
        corner, good, ok, new, win = (np.empty(k, bool) for _ in range(5))
        ma, ea, mb, eb = (np.empty(k, np.int64) for _ in range(4))
        mem, ee = np.ascontiguousarray(mem, np.int64), np.ascontiguousarray(ee, np.int64)
        ii, jj = np.ascontiguousarray(ii, np.int64), np.ascontiguousarray(jj, np.int64)
        xs, conv, ndot = solve_edge_contacts(prob, phi_eff, x0, mem, ee, tol=tol)
        gg = [np.ascontiguousarray(margins_of(prob, m, xs[:, 2 * m:2 * m + 2]), float) for m in (0, 1)]
        with np.errstate(invalid="ignore"):
            te = np.ascontiguousarray(te_of(xs[:, 4], ii, jj), float)
        # which boundaries each system holds its points on (a corner: two), whether each point lies on the rest
        # of its boundaries (margins >= -1e-9 but the held ones; NaN fails) or, held on none, on the real flank,
        # and whether the solution is a contact (converged, opposed normals, |TE| below half a gear pitch); then
        # the solutions that lead their pair's best contact so far: compiled (spiralbevel._core.tca_edge_screen)
        conv = np.array(conv, bool)
        ic = np.flatnonzero(conv)
        if ic.size:
            # a solution whose point (held on a boundary or not) lies on a part of a flank cut away past a limit
            # line of generation (the surfaces' ``on_sheet``) is no contact of the real teeth
            conv[ic] = surface_on_sheet(surfs[0], xs[ic, 0:2]) & surface_on_sheet(surfs[1], xs[ic, 2:4])
        C = [np.zeros(k, bool), np.zeros(k, bool)]
        ic = np.flatnonzero(conv)
        if ic.size:
            for m in (0, 1):
                if hasattr(surfs[m], "on_sheet"):    # contains: the margins and on_sheet, which conv holds already
                    with np.errstate(invalid="ignore"):
                        C[m][ic] = np.all(gg[m][ic] >= -EDGE_TOL, axis=1)
                else:
                    C[m][ic] = surface_contains(surfs[m], xs[ic, 2 * m:2 * m + 2])
        _ks.screen(gg[0], gg[1], mem, ee, k1, K, conv, np.ascontiguousarray(ndot, float), te, np.pi / prob.z2,
                   1e-9, C[0], C[1], ii, jj, np.ascontiguousarray(xs, float), floor, te_edge, x_edge, last, corner,
                   ma, ea, mb, eb, good, ok, new, win)

        def cons(a):
            """The boundaries (member, index) system a holds its points on."""
            if corner[a]:
                return (int(ma[a]), int(ea[a])), (int(mb[a]), int(eb[a]))
            return ((int(mem[a]), int(ee[a])),)

        for a in np.flatnonzero(win):  # the label of each pair's new contact
            i, j = int(ii[a]), int(jj[a])
            c = cons(a)
            if len(c) == 2:
                ms = {m for m, _ in c}
                who = "pinion/gear" if len(ms) == 2 else ("pinion", "gear")[c[0][0]]
                label[(i, j)] = (who, f"{names[c[0][0]][c[0][1]]}/{names[c[1][0]][c[1][1]]} corner", 0, int(ee[a]))
            else:
                label[(i, j)] = (("pinion", "gear")[mem[a]], names[mem[a]][ee[a]], int(mem[a]), int(ee[a]))
        if depth > 0:
            # a solution running past another boundary: the real teeth may first touch where its boundary meets
            # that one (two boundary curves meeting, or a flank's vertex against the mate), started from it
            # A corner is a point of an edge solution's boundary curve, met by the mate at a TE no larger than the
            # curve's stationary maximum: only edge solutions that could still lead their pair's other contacts seed
            # one (a corner bounds no vertex on its curve: corners seed theirs)
            with np.errstate(invalid="ignore"):
                bound = np.fmax(best_other[ii, jj] - te_tie, te_edge[ii, jj])
                lead = ~(te <= bound) | corner
            I, E = [], []
            for a in np.flatnonzero(good & ~ok & lead):
                c = cons(a)
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
    mate = _MATE
    if ii.size:
        kmax = max(len(names[0]), len(names[1]))
        # crossed[a, m, e]: candidate a's point of member m lies beyond boundary e of m (or off the surface: NaN)
        crossed = np.zeros((ii.size, 2, kmax), bool)
        for m in (0, 1):
            crossed[:, m, :len(names[m])] = ~(margins_of(prob, m, x[ii, jj, 2 * m:2 * m + 2]) >= 0)
        # link[m, e, m', e']: crossing boundary e of m asks for the edge system of e' of m': e itself (but the end of
        # the generated surface) and the boundary of the other member that meets it
        link = np.zeros((2, kmax, 2, kmax), bool)
        for m in (0, 1):
            for e, nm in enumerate(names[m]):
                if nm == "generated":
                    continue
                link[m, e, m, e] = True
                for other in mate.get(nm, ()):
                    if other in names[1 - m]:
                        link[m, e, 1 - m, names[1 - m].index(other)] = True
        want = (crossed.reshape(ii.size, -1).astype(np.int64) @ link.reshape(2 * kmax, -1).astype(np.int64)) > 0
        a, M, E = np.nonzero(want.reshape(ii.size, 2, kmax))  # in the order (candidate, member, boundary)
        if a.size:
            try_solve(ii[a], jj[a], M, E, x[ii[a], jj[a]])
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
            g_phys[m][near] = margins_of(prob, m, x[near][:, 2 * m:2 * m + 2])
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

    # 2. march over the cycle from every edge contact that leads, to its neighbours in the effective pinion rotation
    # (the next position of the same pair; at the ends of the cycle, the same and the next rotation of the adjacent
    # pair), from the neighbour's edge solution: where the pair's surface contact is lost altogether, and where the
    # pair still touches on the real flanks but a boundary of the same teeth may touch first (e.g. the gear's fillet
    # junction against the pinion flank ahead of a real surface contact: the edge then counts only if it leads that
    # contact, ``floor``). Into a real surface contact not on a boundary that the pair's contact of the extended
    # surfaces crossed at the edge contact marched from: started from that edge, near the crossing, the edge solve
    # finds the point of the boundary next to the surface contact just inside it, which trails that contact
    def leads(i, j):
        """Pair j's edge contact at position i leads the surface contacts of the other pairs there."""
        return te_edge[i, j] >= best_other[i, j]

    held_by = {}

    def held(m, e):
        """The boundaries (member, index) system (m, e) holds its points on (memoized)."""
        if (m, e) not in held_by:
            held_by[(m, e)] = constraints(np.array([m]), np.array([e]))[0]
        return held_by[(m, e)]

    def systems(m, e):
        """The systems tried at a neighbour of a contact on boundary e of member m: that one, and from a corner its
        two boundaries as edges too (past the corner one of the boundary curves runs against the mate's flank)."""
        c = held(m, e)
        return [(m, e)] + ([b for b in c if names[b[0]][b[1]] != "generated"] if len(c) == 2 else [])

    def crossed_at(i, j):
        """The boundaries (member, index) beyond which pair j's contact of the extended surfaces lies at position
        i (none where it is a real contact)."""
        if phys[i, j]:
            return set()
        return {(m, int(e)) for m in (0, 1)
                for e in np.flatnonzero(~(margins_of(prob, m, x[i, j, 2 * m:2 * m + 2][None])[0] >= 0))}

    # neighbours in the effective rotation phi1 + k T1: position i of pair k is step i + (n - 1) k when the positions
    # span one pitch T1 evenly (the last position of pair k is then the first of pair k + 1), else within a pair only
    span = n > 1 and bool(np.all(np.abs((phi1[1:] - phi1[:-1]) - T1 / (n - 1)) <= 1e-9 * (T1 / (n - 1))))  # allclose
    pl = [int(k) for k in pairs]

    def neighbours(i, j):
        """(position, pair index) of the same and the adjacent effective rotations of (i, j), but (i, j) itself."""
        out = [(k, j) for k in (i - 1, i + 1) if 0 <= k < n]
        if span and not 1 < i < n - 2:   # near an end of the cycle: positions of the other pairs too
            g = i + (n - 1) * pl[j]
            out += [(k, jk) for d in (-1, 0, 1) for jk in range(P) if jk != j
                    for k in (g + d - (n - 1) * pl[jk],) if 0 <= k < n]
        return out

    floor[:] = np.where(phys, te_surface + te_tie, -np.inf)
    front = {key for key in label if leads(*key)}
    while front:
        cand = {}
        for (i, j) in front:
            _, _, m, e = label[(i, j)]
            sy_, cr = systems(m, e), None
            for (k, jk) in neighbours(i, j):
                if (k, jk) not in label and (k, jk) not in cand:
                    sk = sy_
                    if phys[k, jk]:
                        cr = crossed_at(i, j) if cr is None else cr
                        sk = [b for b in sy_ if not cr.intersection(held(*b))]
                    if sk:
                        x0 = x_edge[i, j].copy()
                        x0[4] -= prob.ratio * (phi1[k] - phi1[i] + (pairs[jk] - pairs[j]) * T1)
                        cand[(k, jk)] = (sk, x0)
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
