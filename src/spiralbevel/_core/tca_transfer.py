"""Compiled exact transfer points of TCA: the Illinois variant of regula falsi on all transfers of a cycle
(:mod:`spiralbevel.meshing.tca_transfer`).

Each bracket [lo, hi] holds a sign change of d = TE_b - TE_a with the values d_lo, d_hi; ``side`` is the end kept at
the last update (1: the root was in [p, hi], -1: in [lo, p], 0: none yet). Illinois: when the same end is kept twice
in a row, its stored value is halved, which restores superlinear convergence where plain regula falsi stalls.

Two entry points share the rules of one bracket (:func:`_propose`, :func:`_accept`):

* :func:`transfer_points` -- the whole iteration in one call for surfaces with compiled jets: each trial rotation's
  two contacts are solved inside the kernel, a surface contact by the Newton of :mod:`spiralbevel._core.tca_newton`
  (:func:`newton_one`, the same iteration as ``newton_batch`` on one system), an edge or corner contact by
  :func:`spiralbevel._core.tca_edge.edge_newton_jets` (as :func:`spiralbevel.meshing.tca_edge.solve_edge_contacts`
  runs it). Brackets are independent, so solving them one after the other gives the results of the batched
  iteration;
* :func:`illinois_propose`, :func:`illinois_accept` -- the bookkeeping alone, for surfaces evaluated by numpy (the
  function values come from the caller).
"""

from __future__ import annotations

import math

import numpy as np

from .jit import kernel
from .tca_edge import edge_newton_jets
from .tca_edge_screen import decode_systems
from .tca_newton import newton_one

__all__ = ["illinois_propose", "illinois_accept", "transfer_points"]

#: |d| below which a crossing is found (rad): 5e-11 rad = 1e-5 arcsec; with TE slopes of the order of 100 arcsec/rad
#: the crossing's TE is then within 1e-5 arcsec too. A bracket narrower than _WIDTH (rad) also ends.
_D_TOL = 5e-11
_WIDTH = 1e-12


@kernel(inline="always")   # a few statements
def _propose(lo, hi, d_lo, d_hi):
    """The regula falsi point of the bracket, or its midpoint where that is not strictly inside."""
    q = hi - d_hi * (hi - lo) / (d_hi - d_lo)
    return q if (math.isfinite(q) and lo < q < hi) else 0.5 * (lo + hi)


@kernel(inline="always")   # a few statements
def _accept(i, p, ta, tb, lo, hi, d_lo, d_hi, side, phi_t, te_t, cross):
    """Apply the TE values ``ta``, ``tb`` of both pairs at the trial rotation ``p`` of bracket ``i``: record the
    estimate (rotation, larger TE), update the bracket (Illinois), end it where it converged or lost a contact
    (``cross[i]`` False); returns whether the trial had both contacts."""
    d = tb - ta
    good = math.isfinite(d)
    phi_t[i] = p
    if not good:
        te_t[i] = math.nan
        cross[i] = False  # lost a contact inside the interval: stop at the best estimate
        return good
    te_t[i] = max(ta, tb)
    done = abs(d) < _D_TOL or (hi[i] - lo[i]) < _WIDTH
    if (d > 0) == (d_lo[i] > 0) and (d < 0) == (d_lo[i] < 0):  # same sign as at lo: root in [p, hi]
        lo[i], d_lo[i] = p, d
        if side[i] == 1:
            d_hi[i] *= 0.5
        side[i] = 1
    else:
        hi[i], d_hi[i] = p, d
        if side[i] == -1:
            d_lo[i] *= 0.5
        side[i] = -1
    if done:
        cross[i] = False
    return good


@kernel
def illinois_propose(lo, hi, d_lo, d_hi, c):
    """Trial rotations ``p (len(c),)`` of the active brackets ``c``: the regula falsi point, or the midpoint where it
    is not strictly inside the bracket."""
    p = np.empty(c.shape[0])
    for k in range(c.shape[0]):
        i = c[k]
        p[k] = _propose(lo[i], hi[i], d_lo[i], d_hi[i])
    return p


@kernel
def illinois_accept(c, p, ta, tb, lo, hi, d_lo, d_hi, side, phi_t, te_t, cross, good):
    """:func:`_accept` for the brackets ``c`` at the trial rotations ``p``; ``good (len(c),)`` receives which trials
    had both contacts (their solutions are kept by the caller)."""
    for k in range(c.shape[0]):
        good[k] = _accept(c[k], p[k], ta[k], tb[k], lo, hi, d_lo, d_hi, side, phi_t, te_t, cross)


# entries of the integer vector iv of transfer_points
(KIND1, MK1, SHARE1, KIND2, MK2, SHARE2, MAX_ITER, PATIENCE, HALVINGS, EDGE_MAX_ITER, ITERATIONS) = range(11)
# entries of its float vector fv
(SCALE, TOL, RCOND, EDGE_RCOND, H_TAU, DRIVE, PHI2_MEAN, RATIO, PHI1_MEAN, Z1, Z2) = range(11)


@kernel(inline="always")   # one call site: transfer_points
def _te_one(iv, fv, p1, p2, mp1, mp2, junction, d, M2, phi, k, kind, x, xo):
    """TE (rad, NaN where not converged) of pair ``k`` at pinion rotation ``phi`` and its solution ``xo (5,)`` from
    ``x (5,)``: a surface contact (``kind`` < 0, :func:`~spiralbevel._core.tca_newton.newton_one`) or the edge or
    corner contact coded ``kind = 2 edge + member`` (:func:`~spiralbevel._core.tca_edge.edge_newton_jets` with the
    corner proof, as ``tca_edge_screen.edge_try`` runs it), in the operation order of ``meshing.tca_transfer``."""
    phi_eff = phi + 2 * math.pi * k / fv[Z1]
    c1, s1 = math.cos(phi_eff), math.sin(phi_eff)
    for j in range(5):
        xo[j] = x[j]
    if kind < 0:
        F, J, S1f, E = np.empty(5), np.empty((5, 5)), np.empty((3, 6)), np.empty((2, 3))
        ok = newton_one(iv[KIND1], p1, iv[KIND2], p2, c1, s1, xo, d, M2, fv[SCALE], fv[TOL], iv[MAX_ITER],
                        fv[RCOND], iv[PATIENCE], iv[HALVINGS], F, J, S1f, E)
    else:
        cc, ss = np.empty(1), np.empty(1)
        cc[0], ss[0] = c1, s1
        xe = np.empty((1, 5))
        for j in range(5):
            xe[0, j] = x[j]
        member, edge = np.empty(1, np.int64), np.empty(1, np.int64)
        member[0], edge[0] = kind % 2, kind // 2
        ed, ed2, skip = decode_systems(member, edge, junction, iv[MK1], iv[MK2], cc, ss, d, M2, mp2)
        cv, _, _ = edge_newton_jets(iv[KIND1], p1, iv[MK1], mp1, iv[SHARE1] != 0, iv[KIND2], p2, iv[MK2], mp2,
                                    iv[SHARE2] != 0, cc, ss, xe, member, ed, ed2, d, M2, fv[H_TAU], fv[TOL],
                                    iv[EDGE_MAX_ITER], fv[EDGE_RCOND], skip)
        ok = cv[0]
        for j in range(5):
            xo[j] = xe[0, j]
    if not ok:
        return math.nan
    phi2 = xo[4] + 2 * math.pi * k / fv[Z2]
    return fv[DRIVE] * (-(phi2 - fv[PHI2_MEAN]) - fv[RATIO] * (phi - fv[PHI1_MEAN]))


@kernel
def transfer_points(iv, fv, p1, p2, mp1, mp2, junction, d, M2, lo, hi, te_a_lo, te_b_hi, ta_hi, tb_lo, xa, xb, ka,
                    kb, pa, pb, phi_t, te_t):
    """The transfer points of all brackets in one call (module docstring).

    Parameters
    ----------
    iv : (11,) int64
        Jet kind, margin kind and "margins share the jet" flag of the pinion (``KIND1``, ``MK1``, ``SHARE1``) and the
        gear; the surface Newton's ``MAX_ITER``, ``PATIENCE``, ``HALVINGS``; the edge Newton's ``EDGE_MAX_ITER``;
        ``ITERATIONS`` of regula falsi at most.
    fv : (11,) float
        ``SCALE`` L (mm), ``TOL`` (mm), ``RCOND`` of the surface Newton, ``EDGE_RCOND`` and ``H_TAU`` of the edge
        Newton, the TE frame ``DRIVE``, ``PHI2_MEAN``, ``RATIO``, ``PHI1_MEAN`` and ``Z1``, ``Z2``:
        TE = drive (-(phi2_eff + 2 pi k / z2 - phi2_mean) - ratio (phi1 - phi1_mean)).
    p1, p2, mp1, mp2 : float arrays
        Jet and margin parameters of pinion and gear (margins: empty where no edge contact is solved).
    junction : (k, 3) float
        Samples of the pinion's fillet junction for the corner proof (``tca_edge_solve.junction_samples``), or k = 0.
    d, M2 :
        Assembly constants (:mod:`spiralbevel._core.tca_newton`).
    lo, hi : (m,) float, rad
        The brackets (positions where the pair in contact changes from a to b).
    te_a_lo, te_b_hi : (m,) float, rad
        TE of pair a at lo and of pair b at hi.
    ta_hi, tb_lo : (m,) float, rad
        TE of pair a at hi and of pair b at lo, NaN where missing (solved here from xa, xb).
    xa, xb : (m, 5) float
        Solutions of pair a at lo and of pair b at hi (updated with the accepted trials').
    ka, kb : (m,) int
        Their kinds: -1 surface contact, else 2 * edge + member.
    pa, pb : (m,) int
        The pairs' numbers k.
    phi_t, te_t : (m,) float, rad
        Output: the transfer rotations and the TE there (NaN where the curves do not cross: the middle of the
        interval).
    """
    m = lo.shape[0]
    xo = np.empty((2, 5))   # the trial solutions of pair a and pair b
    t = np.empty(2)
    use = np.empty(2, np.bool_)
    phis = np.empty(2)
    d_lo, d_hi, bl, bh, pt, tt = np.empty(1), np.empty(1), np.empty(1), np.empty(1), np.empty(1), np.empty(1)
    cross = np.empty(1, np.bool_)
    side = np.empty(1, np.int64)
    for i in range(m):
        # round 0: each pair's contact at the other end of the interval, solved from its own solution where it is
        # missing; then the trials of regula falsi, both pairs at one rotation (one call site of _te_one: inlined)
        t_ahi, t_blo = ta_hi[i], tb_lo[i]
        use[0], use[1] = not math.isfinite(t_ahi), not math.isfinite(t_blo)
        phis[0], phis[1] = hi[i], lo[i]
        p = 0.0
        for it in range(iv[ITERATIONS] + 1):
            if it > 0:
                if not cross[0]:
                    break
                p = _propose(bl[0], bh[0], d_lo[0], d_hi[0])
                phis[0], phis[1] = p, p
                use[0], use[1] = True, True
            for w in range(2):
                if use[w]:
                    t[w] = _te_one(iv, fv, p1, p2, mp1, mp2, junction, d, M2, phis[w], pa[i] if w == 0 else pb[i],
                                   ka[i] if w == 0 else kb[i], xa[i] if w == 0 else xb[i], xo[w])
            if it == 0:
                if use[0]:
                    t_ahi = t[0]
                if use[1]:
                    t_blo = t[1]
                d_lo[0] = t_blo - te_a_lo[i]
                d_hi[0] = te_b_hi[i] - t_ahi
                bl[0], bh[0] = lo[i], hi[i]
                s0 = 0 if d_lo[0] == 0.0 else (1 if d_lo[0] > 0.0 else -1)
                s1 = 0 if d_hi[0] == 0.0 else (1 if d_hi[0] > 0.0 else -1)
                cross[0] = math.isfinite(d_lo[0]) and math.isfinite(d_hi[0]) and s0 != s1
                side[0] = 0
                pt[0] = 0.5 * (lo[i] + hi[i])
                tt[0] = math.nan
            elif _accept(0, p, t[0], t[1], bl, bh, d_lo, d_hi, side, pt, tt, cross):
                for j in range(5):
                    xa[i, j] = xo[0, j]
                    xb[i, j] = xo[1, j]
        phi_t[i], te_t[i] = pt[0], tt[0]
