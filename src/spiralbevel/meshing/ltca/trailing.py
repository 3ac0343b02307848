"""Trailing edge contacts: the real-flank contacts of tooth pairs that the unloaded TCA does not follow.

The unloaded TCA (:func:`~spiralbevel.meshing.tca.solve_tca`) solves a pair's edge contact (a boundary curve of one
flank against the other flank, :mod:`spiralbevel.meshing.tca_edge`) only where it can lead: an edge contact that
trails the surface contact of another pair does not decide the unloaded motion and is left as NO_CONTACT. Under load
it may still carry load: the teeth deflect, the loaded pair lags its unloaded position by tens of arcseconds, and any
pair whose real flanks are closer than that lag touches. Where a pair's surface contact runs off a flank boundary
while another pair leads (the exit of a hypoid drive flank is one), the lost positions would then miss a contact
that is there, and the loaded transmission error would jump as if one pair suddenly carried the whole load.

:func:`follow_trailing_edges` marches each such pair's edge contact from its last real contact into the positions
where the TCA lost it (every named boundary of both members is tried from the neighbour's solution, the leading valid
one is kept, with the checks of the TCA's own edge stage), as long as the contact trails the leading contact of the
position by at most ``window``. The loaded TCA then decides from the load whether these pairs touch.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..tca_edge import _all_margins, solve_edge_contacts
from ..tca_result import ContactStatus

__all__ = ["follow_trailing_edges", "TRAILING_WINDOW"]

#: default window of :func:`follow_trailing_edges`, as a fraction of the gear's angular pitch 2 pi / z2 (about 300
#: arcsec on ISO 23509 Sample 2, ten times the elastic lag of its loaded example)
TRAILING_WINDOW = 0.01


def follow_trailing_edges(prob, tca, window: float | None = None, tol: float = 1e-11):
    """The TCA with the trailing edge contacts of its lost positions added (see the module docstring).

    Parameters
    ----------
    prob : ContactProblem
        The assembled pair of the TCA.
    tca : TCAResult
    window : float, rad, optional
        Largest lag of a followed edge contact behind the leading contact of its position (TE difference); default
        :data:`TRAILING_WINDOW` x 2 pi / z2.
    tol : float, mm
        Tolerance of the edge solves.

    Returns
    -------
    tca : TCAResult
        ``status_pairs`` EDGE, ``te_pairs``, ``phi2_pairs``, ``params1``, ``params2``, ``point_fixed`` filled at the
        followed (position, pair) entries; everything else as given.
    followed : (n, P) bool
        The entries added.
    """
    if window is None:
        window = TRAILING_WINDOW * 2 * np.pi / prob.z2
    status = np.array(tca.status_pairs, int)
    te = np.array(tca.te_pairs, float)
    n, P = te.shape
    pairs = np.asarray(tca.pairs, int)
    phi1 = np.asarray(tca.phi1, float)
    surfs = (prob.pinion, prob.gear)
    names = [tuple(getattr(s, "boundary_names", ())) for s in surfs]
    followed = np.zeros((n, P), bool)
    if not all(names) or n < 2:
        return tca, followed
    valid = (status != ContactStatus.NO_CONTACT) & np.isfinite(te)
    lead = np.max(np.where(valid, te, -np.inf), axis=1)
    x = np.full((n, P, 5), np.nan)
    x[..., 0:2], x[..., 2:4] = tca.params1, tca.params2
    x[..., 4] = np.asarray(tca.phi2_pairs, float) - 2 * np.pi * pairs[None, :] / prob.z2
    cands = [(m, e) for m in (0, 1) for e, nm in enumerate(names[m]) if nm != "generated"]

    def te_of(p2e, i, j):
        return tca.drive_sign * (-(prob.gear_angle(p2e, pairs[j]) - tca.phi2_mean)
                                 - prob.ratio * (phi1[i] - tca.phi1_mean))

    # fronts: a real contact of pair j at position i next to a lost position k = i + d
    front = [(i + d, j, d, x[i, j]) for i in range(n) for j in range(P) for d in (-1, 1)
             if valid[i, j] and 0 <= i + d < n and not valid[i + d, j]]
    while front:
        m_all = len(cands)
        K = np.repeat(np.array([f[0] for f in front]), m_all)
        J = np.repeat(np.array([f[1] for f in front]), m_all)
        src = np.repeat(np.array([f[3] for f in front]), m_all, axis=0)
        src[:, 4] -= prob.ratio * (phi1[K] - phi1[K - np.repeat(np.array([f[2] for f in front]), m_all)])
        mem = np.tile(np.array([c[0] for c in cands]), len(front))
        edg = np.tile(np.array([c[1] for c in cands]), len(front))
        xs, conv, ndot = solve_edge_contacts(prob, phi1[K] + pairs[J] * 2 * np.pi / prob.z1, src, mem, edg, tol=tol)
        ok = _valid(prob, surfs, xs, conv, ndot, mem, edg)
        with np.errstate(invalid="ignore"):
            t = te_of(xs[:, 4], K, J)
            ok &= (np.abs(t) < np.pi / prob.z2) & (t >= lead[K] - window) & (t <= lead[K] + 1e-9)
        nxt = []
        for a, (k, j, d, _) in enumerate(front):
            sl = slice(a * m_all, (a + 1) * m_all)
            good = np.flatnonzero(ok[sl])
            if not good.size or valid[k, j]:
                continue
            b = sl.start + good[np.argmax(t[sl][good])]
            x[k, j], te[k, j], status[k, j] = xs[b], t[b], ContactStatus.EDGE
            valid[k, j] = followed[k, j] = True
            if 0 <= k + d < n and not valid[k + d, j]:
                nxt.append((k + d, j, d, xs[b]))
        front = nxt
    if not followed.any():
        return tca, followed
    ii, jj = np.nonzero(followed)
    xf = x[ii, jj]
    r1 = prob.state(xf)[0]
    R1, _, o1, _ = prob.pose(phi1[ii] + pairs[jj] * 2 * np.pi / prob.z1, xf[:, 4])
    pf = np.array(tca.point_fixed, float)
    pf[ii, jj] = o1 + np.einsum("mij,mj->mi", R1, r1)
    p1, p2, ph2 = (np.array(a, float) for a in (tca.params1, tca.params2, tca.phi2_pairs))
    p1[ii, jj], p2[ii, jj] = xf[:, 0:2], xf[:, 2:4]
    ph2[ii, jj] = prob.gear_angle(xf[:, 4], pairs[jj])
    out = dataclasses.replace(tca, status_pairs=status, te_pairs=te, phi2_pairs=ph2, params1=p1, params2=p2,
                              point_fixed=pf)
    return out, followed


def _valid(prob, surfs, xs, conv, ndot, mem, edg, tolm=1e-9):
    """The checks of the TCA's edge stage: converged, the edge point on the rest of its own flank's boundary, the
    touched point on the other member's real flank, opposed normals."""
    from ..contact_surface import surface_contains

    ok = conv.copy()
    for m in (0, 1):
        s = mem == m
        if not s.any():
            continue
        gg = _all_margins(surfs[m], xs[s, 2 * m:2 * m + 2])
        gg[np.arange(s.sum()), edg[s]] = np.inf
        with np.errstate(invalid="ignore"):
            ok[s] &= np.all(gg >= -tolm, axis=1)
    ok &= np.where(mem == 0, surface_contains(prob.gear, xs[:, 2:4]), surface_contains(prob.pinion, xs[:, 0:2]))
    with np.errstate(invalid="ignore"):
        ok &= ndot < -0.5
    return ok
