"""Transfer points of TCA found exactly: where the TE curves of the two pairs that hand over the contact cross.

Between two positions where the pair in contact changes from a to b, the transfer is the root of
d(phi1) = TE_b(phi1) - TE_a(phi1), each TE from its own contact solved at that phi1 (a surface contact by the
Newton solver of :class:`~spiralbevel.meshing.contact_problem.ContactProblem`, an edge contact by
:func:`~spiralbevel.meshing.tca_edge.solve_edge_contacts`), not interpolated between the positions. The root is
bracketed by the two positions and found by the Illinois variant of regula falsi, all transfers of a cycle at once
(compiled: :mod:`spiralbevel._core.tca_transfer`, the whole iteration with its contacts' Newton in one call
where the surfaces have compiled jets, else its bookkeeping between the solves).
The TE there is the envelope's local minimum (the kink where the curves cross), which a sampled envelope misses by
O(spacing): it is reported with the transfer and enters the extremes of the TE curve.
"""

from __future__ import annotations

import numpy as np

from .._core import tca_transfer as _kt
from .contact_problem import _HALVINGS, _RCOND
from .tca_edge import solve_edge_contacts
from .tca_edge_solve import _H_TAU, compiled_args, junction_samples
from .tca_edge_solve import _RCOND as _RCOND_EDGE

__all__ = ["exact_transfers"]

#: Newton iterations at most of a contact (the defaults of ContactProblem.newton and solve_edge_contacts) and of
#: regula falsi
_MAX_ITER = 30
_ITERATIONS = 40
_EMPTY = np.zeros(0)
_NO_JUNCTION = np.zeros((0, 3))


def _te_at(prob, phi, pair_k, kind, x0, te_of_phi, tol):
    """TE (m,) and solutions (m, 5) of pairs at pinion rotations phi (m,): kind (m,) -1 surface contact, else
    (member, edge) encoded as 2 * edge + member for an edge contact."""
    phi_eff = phi + 2 * np.pi * pair_k / prob.z1
    x = np.array(x0, float)
    s = kind < 0
    n_s = int(np.count_nonzero(s))
    if n_s == len(phi):  # surface contacts only (the common case: no edge contact at a transfer)
        x, ok, *_ = prob.newton(phi_eff, x, tol=tol)
    elif n_s == 0:
        x, ok, _ = solve_edge_contacts(prob, phi_eff, x, kind % 2, kind // 2, tol=tol)
    else:
        ok = np.zeros(len(phi), bool)
        xs, conv, *_ = prob.newton(phi_eff[s], x[s], tol=tol)
        x[s], ok[s] = xs, conv
        e = ~s
        xe, conv, _ = solve_edge_contacts(prob, phi_eff[e], x[e], kind[e] % 2, kind[e] // 2, tol=tol)
        x[e], ok[e] = xe, conv
    te = np.where(ok, te_of_phi(x[:, 4], pair_k, phi), np.nan)
    return te, x


def _compiled(prob, ka, kb, tol, te_frame, iterations):
    """Arguments of :func:`spiralbevel._core.tca_transfer.transfer_points` but the brackets' (iv, fv, p1, p2, mp1,
    mp2, junction, d, M2), or None where the contacts are not all solved in compiled code (a surface without a
    compiled jet; an edge contact of surfaces without compiled margins)."""
    if prob._jets is None:
        return None
    (k1, p1), (k2, p2) = prob._jets
    edge = np.concatenate([ka[ka >= 0], kb[kb >= 0]])
    kinds, mp1, mp2, junction = np.zeros(6, np.int64), _EMPTY, _EMPTY, _NO_JUNCTION
    if edge.size:
        args = compiled_args(prob)
        if args is None:
            return None
        kinds, _, mp1, _, mp2, _ = args
        junction = junction_samples(prob, edge % 2, edge // 2)
    iv = np.array([k1, kinds[1], kinds[2], k2, kinds[4], kinds[5], _MAX_ITER, _MAX_ITER, _HALVINGS, _MAX_ITER,
                   iterations], np.int64)
    drive, phi2_mean, phi1_mean = te_frame
    fv = np.array([prob._const[2], tol, _RCOND, _RCOND_EDGE, _H_TAU, drive, phi2_mean, prob.ratio, phi1_mean, prob.z1,
                   prob.z2], float)
    d, M2, _ = prob._const
    return iv, fv, p1, p2, mp1, mp2, junction, d, M2


def exact_transfers(prob, phi1, sel, te2, x2, kinds, pairs, te_of_phi, tol=1e-10, te_tie=1e-11, iterations=_ITERATIONS,
                    te_frame=None):
    """Transfer points (rotations and TE) of a TCA cycle.

    Parameters
    ----------
    prob : ContactProblem
    phi1 : (n,) float, rad
    sel : (n,) int
        Index of the pair in contact per position (-1: none).
    te2 : (n, P) float, rad
        TE of each pair's contact (NaN where none).
    x2 : (n, P, 5) float
        The contacts' solutions.
    kinds : (n, P) int
        -1 for a surface contact, 2 * edge + member for an edge contact.
    pairs : (P,) int
    te_of_phi : callable
        ``te_of_phi(phi2_eff, k, phi1) -> TE`` (rad) for pair k at pinion rotation phi1.
    te_frame : (drive, phi2_mean, phi1_mean), optional
        The TE of ``te_of_phi`` as numbers, TE = drive (-(phi2 - phi2_mean) - ratio (phi1 - phi1_mean)) with phi2 the
        gear rotation of the pair (rad): given, the whole iteration runs in one compiled call where every contact can
        be solved in compiled code (:func:`spiralbevel._core.tca_transfer.transfer_points`).

    Returns
    -------
    transfer_phi1 : (t,) float, rad
    transfer_te : (t,) float, rad
        TE at the crossing (NaN where the curves do not cross: the leading pair's contact ends there and the TE
        jumps; the rotation is then the middle of the interval).
    """
    sel = np.asarray(sel)
    a, b = sel[:-1], sel[1:]
    ic = ((a >= 0) & (b >= 0) & (a != b)).nonzero()[0]  # the pair in contact changes between i and i + 1
    ac, bc = a[ic], b[ic]
    d0 = te2[ic, bc] - te2[ic, ac]
    d1 = te2[ic + 1, bc] - te2[ic + 1, ac]
    tie = np.isfinite(d0) & np.isfinite(d1) & (np.maximum(np.abs(d0), np.abs(d1)) <= te_tie)  # shared contact
    I, A, B = ic[~tie], ac[~tie], bc[~tie]
    m = len(I)
    if not m:
        return np.zeros(0), np.zeros(0)
    # (an integer index array returns a new array: no copies beyond these)
    I1 = I + 1
    lo, hi = np.asarray(phi1[I], float), np.asarray(phi1[I1], float)
    # each pair's contact at the other end of the interval: solved from its own solution where it is missing
    ta_hi, tb_lo = te2[I1, A], te2[I, B]
    xa, xb = x2[I, A], x2[I1, B]
    ka, kb = kinds[I, A], kinds[I + 1, B]
    fast = None if te_frame is None else _compiled(prob, ka, kb, tol, te_frame, iterations)
    if fast is not None:   # the whole iteration in one compiled call
        phi_t, te_t = np.empty(m), np.empty(m)
        iv, fv, p1, p2, mp1, mp2, junction, d, M2 = fast
        _kt.transfer_points(iv, fv, p1, p2, mp1, mp2, junction, d, M2, lo, hi, np.asarray(te2[I, A], float),
                            np.asarray(te2[I1, B], float), np.asarray(ta_hi, float), np.asarray(tb_lo, float),
                            np.asarray(xa, float), np.asarray(xb, float), np.asarray(ka, np.int64),
                            np.asarray(kb, np.int64), np.asarray(pairs[A], np.int64), np.asarray(pairs[B], np.int64),
                            phi_t, te_t)
        return phi_t, te_t
    miss_a, miss_b = ~np.isfinite(ta_hi), ~np.isfinite(tb_lo)
    if miss_a.any() or miss_b.any():
        na = int(miss_a.sum())
        t, _ = _te_at(prob, np.concatenate([hi[miss_a], lo[miss_b]]),
                      np.concatenate([pairs[A[miss_a]], pairs[B[miss_b]]]), np.concatenate([ka[miss_a], kb[miss_b]]),
                      np.concatenate([xa[miss_a], xb[miss_b]]), te_of_phi, tol)
        ta_hi[miss_a], tb_lo[miss_b] = t[:na], t[na:]
    d_lo = tb_lo - te2[I, A]
    d_hi = te2[I + 1, B] - ta_hi
    cross = np.isfinite(d_lo) & np.isfinite(d_hi) & (np.sign(d_lo) != np.sign(d_hi))
    phi_t = 0.5 * (lo + hi)
    te_t = np.full(m, np.nan)
    side = np.zeros(m, np.int64)
    kk, kind2 = np.concatenate([pairs[A], pairs[B]]), np.concatenate([ka, kb])
    for _ in range(iterations):
        c = np.flatnonzero(cross)
        if not c.size:
            break
        p = _kt.illinois_propose(lo, hi, d_lo, d_hi, c)
        cc = np.concatenate([c, c + m])
        t, xn = _te_at(prob, np.concatenate([p, p]), kk[cc], kind2[cc], np.concatenate([xa[c], xb[c]]), te_of_phi, tol)
        good = np.empty(c.size, bool)
        _kt.illinois_accept(c, p, t[:c.size], t[c.size:], lo, hi, d_lo, d_hi, side, phi_t, te_t, cross, good)
        xa[c[good]], xb[c[good]] = xn[:c.size][good], xn[c.size:][good]
    return phi_t, te_t
