"""Tooth contact analysis (TCA) of a bevel pair: seed 001 §4 (Eq. (16), docs/theory/tca.md, Eq. (T5)) on any two
:class:`~spiralbevel.meshing.contact_surface.ContactSurface` flanks.

For each pinion rotation phi1 the contact system (coincident points, opposite outward normals; 5 equations in the
two surface parameters of each flank and the gear rotation phi2) is solved for every tooth pair. Only solutions
with both points on the real flanks (the surfaces' ``contains``) are contacts; the pair in contact is the one of
them that leads the gear furthest in its driven direction, i.e. the largest TE in the sign convention of
:class:`~spiralbevel.meshing.tca_result.TCAResult` (seed 001 §5 calls it the pair with the "least transmission
error": with TE curves <= 0 that is the least in magnitude; docs/conventions.md "Misalignments" and "TCA").

Algorithm (all numpy, batched):

1. mean contact point of pair 0 at phi1 = phi10 (Newton with minimum-norm steps);
2. continuation outward in steps of half an angular pitch from the mean point with a second-order predictor and
   the path tangent dx/dphi1 = -J^+ dF/dphi1 (tooth pairs differ only by the pitch, so one path serves all pairs,
   see :mod:`spiralbevel.meshing.contact_problem`);
3. all positions x pairs at once, started from cubic Hermite interpolation of the continuation nodes;
4. domains, TE, the pair in contact, transfer points, contact ellipses.

Speed (bench/bench_tca.py): the Newton iterations are compiled (:mod:`spiralbevel._core.tca_newton`: LU steps where the
system is provably regular, the minimum-norm SVD step only on a contact line; flanks with a compiled jet, the log-spiral
flank, the face-milled generated flank and the log-spiral flank crowned by a quadratic normal deviation, are evaluated
inside the compiled loop), the path tangents come from the Jacobians of the last Newton iterations, one continuation
level (+-T/2) feeds a quintic predictor for the outer positions, positions beyond a node the continuation could not
reach are not solved, and systems that stop converging are dropped at the first iteration that does not halve their
residual (continuation nodes after two); the generated flanks give analytic derivatives
(:mod:`spiralbevel._core.generation_blade_jet`). The edge contacts (:mod:`.tca_edge`: compiled margins and Newton,
:mod:`spiralbevel._core.tca_edge`; the screen and acceptance of their solutions,
:mod:`spiralbevel._core.tca_edge_screen`, which solves and screens each batch in one call), the path predictor
(:mod:`spiralbevel._core.tca_predict`), the line-contact test and the transfer iteration
(:mod:`spiralbevel._core.tca_transfer`: regula falsi with each trial's surface and edge Newton in one call) are
compiled as well, and so is the continuation for flanks with compiled jets (its levels, predictors, Newton solves and
tangents in one call, :func:`spiralbevel._core.tca_solve.continuation_jets`); what remains in Python is the
orchestration below.
"""

from __future__ import annotations

import numbers

import numpy as np

from .._core import tca as _k
from .._core import tca_batch as _b
from .._core import tca_ellipse as _e
from .._core import tca_predict as _p
from .._core import tca_solve as _n
from ..errors import DesignError, NoContactError, Problem
from .contact_problem import _HALVINGS, _RCOND, ContactProblem
from .contact_surface import surface_derivatives
from .tca_edge import edge_stage
from .tca_edge_solve import flank_contains
from .tca_transfer import exact_transfers
from .ellipse import GLEASON_APPROACH
from .misalignment import Misalignment
from .tca_result import ContactStatus, TCAResult

__all__ = ["solve_tca", "ContactProblem", "TCAResult", "ContactStatus", "Misalignment"]

#: the statuses as plain ints (an array compared with an IntEnum member converts it on every call)
_OK, _LINE, _EDGE, _NONE = (int(ContactStatus.OK), int(ContactStatus.LINE), int(ContactStatus.EDGE),
                            int(ContactStatus.NO_CONTACT))


def _validate(n_positions, pairs, approach, tol, phi1_mean):
    problems = []
    if isinstance(n_positions, bool) or not isinstance(n_positions, numbers.Integral) or n_positions < 2:
        problems.append(Problem("n_positions", n_positions, "integer >= 2", "-"))
    try:
        p = [int(k) for k in pairs]
        if len(set(p)) != len(p) or not p or any(k != q for k, q in zip(p, pairs)):
            raise ValueError
    except (TypeError, ValueError):
        problems.append(Problem("pairs", pairs, "distinct integers, e.g. (-1, 0, 1)", "-"))
    if not (isinstance(approach, numbers.Real) and np.isfinite(approach) and approach > 0):
        problems.append(Problem("approach", approach, "> 0", "mm"))
    if not (isinstance(tol, numbers.Real) and 0 < tol < 1e-3):
        problems.append(Problem("tol", tol, "0 < value < 1e-3", "mm"))
    if not (isinstance(phi1_mean, numbers.Real) and np.isfinite(phi1_mean)):
        problems.append(Problem("phi1_mean", phi1_mean, "a finite number", "rad"))
    if problems:
        raise DesignError(problems)


def _predict(o, nodes, X, Xp):
    """Predictor of the path at offsets ``o (m,)`` from sorted nodes with values ``X (n, 5)`` and slopes ``Xp``: cubic
    Hermite between the nodes; beyond the outer nodes, the quintic through the three nodes nearest that end (values and
    slopes) when there are three, else Hermite extrapolation (compiled: :mod:`spiralbevel._core.tca_predict`)."""
    out = np.empty((len(o), X.shape[1]))
    _p.predict(np.ascontiguousarray(o, float), np.ascontiguousarray(nodes, float), np.ascontiguousarray(X, float),
               np.ascontiguousarray(Xp, float), out)
    return out


#: Newton iterations at most of a continuation node (ContactProblem.newton's default)
_MAX_ITER = 30


def _continuation(prob, x_mean, xp0, phi1_mean, o_lo, o_hi, step, tol):
    """Nodes (sorted offsets, X, X') of the solution path from the mean point out to [o_lo, o_hi], and the offsets
    (lo, hi) of the first node that could not be reached on each side (-inf, inf when none failed).

    Level 1 solves the nodes +-step from the tangent predictor; each further level advances every side by up to two
    steps at once, predicted by the quintic Hermite polynomial through that side's last three nodes. The path
    tangent at a node comes from the Jacobian of its last Newton iteration. For surfaces with compiled jets the
    same rules run in one compiled call (:func:`spiralbevel._core.tca_solve.continuation_jets`).
    """
    need = {1: int(np.ceil(o_hi / step - 1e-9)), -1: int(np.ceil(-o_lo / step - 1e-9))}
    if prob._jets is not None:   # the same rules in one compiled call
        (k1, p1), (k2, p2) = prob._jets
        d, M2, L = prob._const
        return _n.continuation_jets(k1, p1, k2, p2, x_mean, xp0, d, M2, L, phi1_mean, step, need[-1], need[1], tol,
                                    _MAX_ITER, _RCOND, 2, _HALVINGS)
    nodes = {0: (x_mean, xp0)}  # integer step index -> (x, x')
    last = {1: 0, -1: 0}
    alive = {d: need[d] > 0 for d in (1, -1)}
    fail = {1: np.inf, -1: -np.inf}
    while any(alive.values()):
        idx, guesses = [], []
        for d in (1, -1):
            if not alive[d]:
                continue
            j0 = last[d]
            if abs(j0) == 0:
                new = [d]
                guesses.append(x_mean + d * step * xp0)
            else:
                new = [j0 + d * m for m in (1, 2) if abs(j0) + m <= need[d]]
                known = sorted([j0 - 2 * d, j0 - d, j0] if (j0 - 2 * d) in nodes else [j0 - d, j0])
                if len(known) == 3:  # the quintic through the three nodes of this side
                    guesses.extend(_predict(np.array(new, float) * step, np.array(known, float) * step,
                                            np.array([nodes[j][0] for j in known]),
                                            np.array([nodes[j][1] for j in known])))
                else:
                    xa, pa = nodes[j0]
                    guesses.extend(xa + (np.array(new)[:, None] - j0) * step * pa)
            idx.extend(new)
        idx = np.array(idx)
        phi = phi1_mean + idx * step
        # a node within reach converges quadratically from its predictor; two iterations without halving the residual
        # mean the path has ended there
        x, conv, _, J, data, _, E = prob.newton(phi, np.array(guesses), tol=tol, patience=2)
        tang = prob.path_tangent(J, data[2], E)
        good = (conv & np.isfinite(tang).all(axis=1)).tolist()
        for d in (1, -1):
            if not alive[d]:
                continue
            for m in np.nonzero(np.sign(idx) == d)[0][np.argsort(np.abs(idx[np.sign(idx) == d]))]:
                if not good[m]:
                    alive[d] = False
                    fail[d] = float(idx[m] * step)
                    break
                nodes[int(idx[m])] = (x[m], tang[m])
                last[d] = int(idx[m])
            if abs(last[d]) >= need[d]:
                alive[d] = False
    keys = sorted(nodes)
    return (np.array(keys, float) * step, np.array([nodes[k][0] for k in keys]),
            np.array([nodes[k][1] for k in keys]), (fail[-1], fail[1]))


#: all positions x pairs start from interpolated path points, where Newton halves the residual at every iteration;
#: a system that fails to do so has no solution near its start (beyond the end of the path)
_PATIENCE = 1


def _solve_reachable(prob, phi_eff, guess, reach, tol):
    """:meth:`ContactProblem.newton` on the systems ``reach``; the others keep the guess, NaN data, no convergence."""
    if reach.all():
        return prob.newton(phi_eff, guess, tol=tol, patience=_PATIENCE)
    m = len(guess)
    x, conv, res = guess.copy(), np.zeros(m, bool), np.full(m, np.inf)
    J = np.full((m, 5, 5), np.nan)
    data = (np.full((m, 3, 6), np.nan), np.full((m, 3, 6), np.nan), np.full((m, 3, 6), np.nan),
            np.full((m, 6, 6), np.nan))
    iters, E = 0, None
    if reach.any():
        xr, cr, rr, Jr, dr, iters, E = prob.newton(phi_eff[reach], guess[reach], tol=tol, patience=_PATIENCE)
        x[reach], conv[reach], res[reach], J[reach] = xr, cr, rr, Jr
        for a, b in zip(data, dr):
            a[reach] = b
    return x, conv, res, J, data, iters, E


def _on_blade(surface, params):
    """True where ``params`` (u, psi_c) of a generated surface lie on the blade (u at or above the blade tip) and on
    the generated root of the equation of meshing; all True for a surface without these boundaries (log spiral)."""
    names = tuple(getattr(surface, "boundary_names", ()))
    if "generated" not in names or "fillet" not in names:
        return np.ones(np.asarray(params).shape[:-1], bool)
    m = surface.boundary_margins(params)
    gen = getattr(getattr(surface, "flank", None), "generator", None)
    with np.errstate(invalid="ignore"):
        ok = m[..., names.index("generated")] >= 0.0
        if gen is not None:   # the fillet margin is u - u_j; the blade tip is at u_min
            ok &= m[..., names.index("fillet")] >= gen.cp["u_min"] - gen.cp["u_j"] - 1e-9
    return ok


_CYCLES: dict[tuple, np.ndarray] = {}


def _cycle(T, n):
    """``np.linspace(-T / 2, T / 2, n)``, kept for the last few (T, n) (read-only)."""
    key = (T, n)
    out = _CYCLES.get(key)
    if out is None:
        if len(_CYCLES) >= 16:
            _CYCLES.clear()
        out = _CYCLES[key] = np.linspace(-T / 2, T / 2, n)
        out.flags.writeable = False
    return out


def solve_tca(pinion, gear, kinematics, *, misalignment: Misalignment | None = None, phi1_mean: float = 0.0,
              n_positions: int = 41, pairs=(-1, 0, 1), start=None, approach: float = GLEASON_APPROACH,
              tol: float = 1e-10, line_tol: float = 1e-7, line_anchor: int | None = 1,
              te_tie: float = 1e-11, flank_bounds: bool = True) -> TCAResult:
    """Tooth contact analysis over one mesh cycle (2 pi / z1 of pinion rotation centred on the mean point).

    Parameters
    ----------
    pinion, gear : ContactSurface
        Pinion and gear flanks of the meshing side, member frames, outward normals.
    kinematics : object
        With ``z1``, ``z2``, ``shaft_angle`` (rad), e.g. ``BevelPairKinematics``.
    misalignment : Misalignment, optional
    phi1_mean : float, rad
        phi10, pinion rotation of the mean contact point (centre of the cycle).
    n_positions : int
        Pinion positions over the cycle [phi10 - pi/z1, phi10 + pi/z1].
    pairs : sequence of int
        Tooth pairs k (pinion tooth k meets gear tooth k; pair k's mean point is at phi10 - 2 pi k / z1).
    start : (5,) float, optional
        Starting guess (q1, q2, phi2) of the mean contact point; default: the surfaces' ``reference_params``
        and phi2 = -(z1/z2) phi10.
    approach : float, mm
        Elastic approach of the contact ellipses.
    tol : float, mm
        Newton tolerance on max|F|.
    line_tol : float
        s_min/s_max of the equilibrated Jacobian below which the contact is reported as line contact.
    line_anchor : int or None
        On line contact, the reported point of the contact line is the one where pinion parameter ``line_anchor``
        (0 or 1) equals its reference value (for the log-spiral flank, index 1 = phi: mid-face); None keeps the
        minimum-norm Newton point.
    te_tie : float, rad
        Pairs whose TE is within ``te_tie`` of the largest share the load (line contact of conjugate flanks); the
        first of them in ``pairs`` order is reported, a surface contact before an edge contact.
    flank_bounds : bool
        True (default): a contact counts only where both points lie on the real flanks (the surfaces' ``contains``:
        toe, heel, top and fillet junction); False: the analytically extended surfaces are the flanks (the idealized
        model of seed 001 Eq. (16), which has no edges).

    Returns
    -------
    TCAResult

    Raises
    ------
    NoContactError
        No contact at the mean position, or at none of the positions.
    DesignError
        Invalid arguments.
    """
    _validate(n_positions, pairs, approach, tol, phi1_mean)
    prob = ContactProblem(pinion, gear, kinematics, misalignment)
    z1, z2, ratio = prob.z1, prob.z2, prob.ratio
    pairs = np.array([int(k) for k in pairs])
    T = 2 * np.pi / z1
    # ---------------------------------------------------------------- 1. mean point
    if start is None:
        q1 = getattr(pinion, "reference_params", None)
        q2 = getattr(gear, "reference_params", None)
        if q1 is None or q2 is None:
            raise DesignError.single("start", None, "(q1, q2, phi2) or surfaces with reference_params", "-")
        start = np.concatenate([np.asarray(q1, float), np.asarray(q2, float), [-ratio * phi1_mean]])
    start = np.asarray(start, float).reshape(1, 5)
    xm, conv, res, Jm, dm, _, Em = prob.newton(np.array([phi1_mean]), start, tol=tol)
    xm = xm[0]
    n1f, n2f, r1f = dm[2][0, :, 1], dm[3][0, :3, 1], dm[2][0, :, 0]
    if not conv[0] or n1f @ n2f > -0.5:
        raise NoContactError(f"no contact at the mean position phi1 = {phi1_mean:.6g} rad "
                             f"(residual {res[0]:.3e} mm, n1.n2 = {n1f @ n2f:.3f})")
    phi2_mean = float(xm[4])
    (a0, a1, a2), (p0, p1, p2), (m0, m1, m2) = np.asarray(prob.axes[0], float).tolist(), r1f.tolist(), n1f.tolist()
    drive = 1 if (a1 * p2 - a2 * p1) * m0 + (a2 * p0 - a0 * p2) * m1 + (a0 * p1 - a1 * p0) * m2 > 0 else -1
    # ---------------------------------------------------------------- 2. continuation nodes
    phi1 = phi1_mean + _cycle(T, n_positions)
    off = (phi1 - phi1_mean)[:, None] + pairs[None, :] * T  # effective offsets (n, P)
    xp0 = prob.path_tangent(Jm, dm[2], Em)[0]
    half = T / 2
    nodes, X, Xp, (o_fail_lo, o_fail_hi) = _continuation(prob, xm, xp0, phi1_mean, off.min(),
                                                         off.max(), half, max(tol, 1e-8))
    # ---------------------------------------------------------------- 3. all positions x pairs
    # beyond a node the continuation could not reach, the path of contact has ended (the extended flanks end or
    # the normals turn away): those offsets are not solved and are reported as no contact
    offs = off.reshape(-1)
    guess = _predict(offs, nodes, X, Xp)
    phi_eff = phi1_mean + offs
    reach = (offs >= o_fail_lo - 1e-12) & (offs <= o_fail_hi + 1e-12)
    x, conv, res, J, data, iters, _ = _solve_reachable(prob, phi_eff, guess, reach, tol)
    line = conv & _b.is_singular(J, line_tol)
    if line.any() and line_anchor is not None:
        # contact line: pick the point of the line where pinion parameter `line_anchor` has its reference value
        ref = getattr(pinion, "reference_params", None)
        value = float(ref[line_anchor]) if ref is not None else float(xm[line_anchor])
        # systems already at the anchor leave that Newton at once, unchanged (residual max(|F|, |anchor|))
        ra = prob.scale * np.abs(x[:, line_anchor] - value)
        done = line & (ra < tol)
        res[done] = np.maximum(res[done], ra[done])
        ix = np.nonzero(line & ~done)[0]
        if ix.size:
            xl, cl, rl, _, dl, _, _ = prob.newton(phi_eff[ix], x[ix], tol=tol,
                                                  anchor=(line_anchor, np.full(ix.size, value)))
            x[ix], conv[ix], res[ix] = xl, cl, rl
            for a, b in zip(data, dl):
                a[ix] = b
    # ---------------------------------------------------------------- 4. evaluation
    n, P = off.shape
    S1, S2 = data[0], data[1]
    r1, n1, dr1, dn1 = S1[:, :, 0], S1[:, :, 1], S1[:, :, 2:4], S1[:, :, 4:6]
    r2, n2, dr2, dn2 = S2[:, :, 0], S2[:, :, 1], S2[:, :, 2:4], S2[:, :, 4:6]
    R1, R2, o1, o2 = prob.pose(phi_eff, x[:, 4])
    n1f = np.einsum("mij,mj->mi", R1, n1)
    n2f = np.einsum("mij,mj->mi", R2, n2)
    pf = o1 + np.einsum("mij,mj->mi", R1, r1)
    valid = conv & (np.einsum("mi,mi->m", n1f, n2f) < -0.5)
    kk = np.repeat(pairs[None, :], n, axis=0).reshape(-1)
    phi2 = prob.gear_angle(x[:, 4], kk)
    te = drive * (-(phi2 - phi2_mean) - ratio * (np.repeat(phi1, P) - phi1_mean))
    # a "contact" whose TE exceeds half an angular pitch of the gear belongs to no tooth pair of this mesh: Newton
    # converged to a spurious intersection of the analytically extended surfaces
    valid &= np.abs(te) < np.pi / z2
    # (only valid contacts need the test: the statuses below read it there alone)
    inside = np.zeros(n * P, bool)
    iv = valid.nonzero()[0]
    # surfaces without edges (flank_bounds False: toe, heel and top extended), but a contact must still be generated
    # by a blade: on its straight edge or fillet (not beyond the blade tip) where the equation of meshing of
    # generation has a root; past the tip Newton can converge to a spurious touch of the extended surfaces below the
    # root
    test = flank_contains if flank_bounds else _on_blade
    if iv.size:
        inside[iv] = test(pinion, x[iv, 0:2])
        iv = iv[inside[iv]]
    if iv.size:
        inside[iv] = test(gear, x[iv, 2:4])
    sp = np.full(n * P, _NONE)
    vi = valid & inside
    sp[vi & ~line] = _OK
    sp[vi & line] = _LINE
    sp[valid & ~inside] = _EDGE
    te = np.where(valid, te, np.nan)
    te2 = te.reshape(n, P)
    if not np.isfinite(te2).any():
        raise NoContactError(f"no contact at any of the {n} positions phi1 in [{phi1[0]:.6g}, {phi1[-1]:.6g}] rad")
    sp2 = sp.reshape(n, P)
    # edge contacts: where a pair's surface contact lies beyond a flank boundary (and next to such positions where it
    # is lost), the boundary curve of one member against the other's flank (meshing/tca_edge.py)
    x2 = x.reshape(n, P, 5)
    if flank_bounds:
        def te_of(p2, i, j):
            return drive * (-(prob.gear_angle(p2, pairs[j]) - phi2_mean) - ratio * (phi1[i] - phi1_mean))

        x_edge, te_edge, labels = edge_stage(prob, x2, sp2, te2, te_of, phi1, pairs, tol=min(tol, 1e-11),
                                              te_tie=te_tie, te_frame=(drive, phi2_mean, phi1_mean))
    else:
        x_edge, te_edge, labels = np.full((n, P, 5), np.nan), np.full((n, P), np.nan), {}
    has_edge = np.isfinite(te_edge)
    # a pair's status: OK/LINE (surface contact of the real flanks), EDGE (edge contact solved: its TE, points on the
    # boundary curve and the touched flank), NO_CONTACT
    sp2 = np.where(sp2 == _EDGE, _NONE, sp2)
    sp2[has_edge] = _EDGE
    te2 = np.where(has_edge, te_edge, np.where((sp2 == _OK) | (sp2 == _LINE), te2, np.nan))
    if has_edge.any():
        fe = has_edge.reshape(-1).nonzero()[0]
        x[fe] = x_edge.reshape(-1, 5)[fe]
        q1, q2 = x[fe, 0:2], x[fe, 2:4]
        e1 = surface_derivatives(pinion, q1)
        e2 = surface_derivatives(gear, q2)
        r1[fe], n1[fe], dr1[fe], dn1[fe] = e1
        r2[fe], n2[fe], dr2[fe], dn2[fe] = e2
        R1[fe], R2[fe] = prob.pose(phi_eff[fe], x[fe, 4])[:2]
        n1f[fe] = np.einsum("mij,mj->mi", R1[fe], n1[fe])
        pf[fe] = o1 + np.einsum("mij,mj->mi", R1[fe], r1[fe])
        phi2[fe] = prob.gear_angle(x[fe, 4], kk[fe])
        valid[fe] = True
        res[fe] = 0.0
    fin = np.isfinite(te2)
    if not fin.any():
        raise NoContactError(f"no contact of the real flanks at any of the {n} positions phi1 in "
                             f"[{phi1[0]:.6g}, {phi1[-1]:.6g}] rad")
    # pair in contact: the largest TE (it leads the gear) among the contacts of the real flanks, surface or edge
    score = np.where(fin, te2, -np.inf)
    anyv = fin.any(axis=1)
    # ties (several pairs within te_tie of the largest TE, e.g. line contact of conjugate flanks): a surface contact
    # before an edge contact of the same line, then the first pair in `pairs` order
    tmax = score.max(axis=1, keepdims=True)
    tie = score >= tmax - te_tie
    rank = np.where(tie, np.where(sp2 == _EDGE, 1, 2), 0)
    sel = np.where(anyv, rank.argmax(axis=1), -1)
    sel0 = np.maximum(sel, 0)
    status = np.where(anyv, sp2[np.arange(n), sel0], _NONE)
    edge_pos = status == _EDGE
    sl, pl = sel.tolist(), pairs.tolist()
    edges = [(i, pl[sl[i]]) + tuple(labels[(i, sl[i])][:2]) for i in edge_pos.nonzero()[0].tolist()]
    # ellipses at the selected contacts
    flat = np.arange(n) * P + sel0
    nocon_or_edge = ~anyv | edge_pos
    # (positions without contact may carry no surface data, NaN: their ellipses are NaN, set below anyway)
    lam, dirs, W1, W2 = np.empty((n, 2)), np.empty((n, 2, 3)), np.empty((n, 3, 3)), np.empty((n, 3, 3))
    R1s, R2s = np.ascontiguousarray(R1[flat]), np.ascontiguousarray(R2[flat])
    _e.weingarten_batch(np.ascontiguousarray(dr1[flat]), np.ascontiguousarray(dn1[flat]), R1s, True, W1)
    _e.weingarten_batch(np.ascontiguousarray(dr2[flat]), np.ascontiguousarray(dn2[flat]), R2s, True, W2)
    _e.relative_curvature_batch(W1, W2, np.ascontiguousarray(n1f[flat]), lam, dirs)
    axes_ = _k.ellipse_axes(lam, approach)
    axes_ = np.where((status == _LINE)[:, None], np.inf, axes_)
    dirs1 = np.einsum("mji,mkj->mki", R1s, dirs)
    dirs2 = np.einsum("mji,mkj->mki", R2s, dirs)
    if nocon_or_edge.any():
        for arr in (lam, axes_, dirs1, dirs2):
            arr[nocon_or_edge] = np.nan
    # transfer points: where the pair in contact changes, at the exact crossing of the two pairs' TE curves
    kinds = np.full((n, P), -1)
    for (i, j), lab in labels.items():
        kinds[i, j] = 2 * lab[3] + lab[2]

    def te_of_phi(p2, k, phi):
        return drive * (-(prob.gear_angle(p2, k) - phi2_mean) - ratio * (phi - phi1_mean))

    transfers, transfer_te = exact_transfers(prob, phi1, sel, te2, x.reshape(n, P, 5), kinds, pairs, te_of_phi,
                                             tol=tol, te_tie=te_tie, te_frame=(drive, phi2_mean, phi1_mean))

    def rs(a, k=None):
        return a.reshape((n, P) + a.shape[1:])

    return TCAResult(
        phi1=phi1, phi1_mean=float(phi1_mean), phi2_mean=phi2_mean, drive_sign=drive, pairs=pairs,
        te_pairs=te2, phi2_pairs=rs(np.where(valid, phi2, np.nan)), status_pairs=sp2,
        params1=rs(x[:, 0:2]), params2=rs(x[:, 2:4]), point1=rs(r1), normal1=rs(n1), point2=rs(r2), normal2=rs(n2),
        point_fixed=rs(pf), normal_fixed=rs(n1f), residual=rs(res), pair=sel, status=status,
        semi_axes=axes_, ellipse_dirs1=dirs1, ellipse_dirs2=dirs2, relative_curvatures=lam,
        approach=float(approach), transfer_phi1=np.asarray(transfers), transfer_te=np.asarray(transfer_te),
        z1=z1, z2=z2,
        shaft_angle=prob.shaft_angle, iterations=int(iters), edges=tuple(edges),
    )
