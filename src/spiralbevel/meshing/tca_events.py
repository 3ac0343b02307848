"""Short contact events between the positions of a TCA: where a tooth pair's contact changes kind (surface, edge, none)
between two positions, a pair can lead for a fraction of a step -- an incoming pair's tip edge touching first for a
percent of the mesh cycle, say -- and the positions step over it.

Measured on the coast pair of the developed 13/20 sample design of the robustness bench (tests/meshing/
test_tca_events.py): the incoming pinion's top edge leads for 1.5 % of the cycle with a TE bump to +0.58 arcsec; over
five phases of the position grid, 21 positions showed that edge contact once and under-read the peak-to-peak TE by up
to 0.6 arcsec (11 %), 41 positions three times (up to 0.48 arcsec).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .tca_result import ARCSEC, ContactStatus

__all__ = ["ContactEvent", "events_between", "flagged_intervals"]

#: rad: a pair whose TE at both ends of an interval trails the contact there by more than this is not refined (its
#: TE would have to rise by that much within one step to lead; the edge bumps seen rose 0.6-2 arcsec per step of 81)
EVENT_MARGIN = 2.0 * ARCSEC


@dataclass(frozen=True)
class ContactEvent:
    """A contact between two positions of a TCA that leads where the positions do not show it.

    phi1 : float, rad
        Pinion rotation.
    te : float, rad
        Its transmission error.
    pair : int
        Tooth pair k.
    status : int
        :class:`~spiralbevel.meshing.tca_result.ContactStatus` (EDGE: an edge or corner contact).
    edge : tuple of str
        (member, boundary) of an edge contact, () for a surface contact.
    interval : int
        The coarse positions i, i + 1 it lies between.
    """

    phi1: float
    te: float
    pair: int
    status: int
    edge: tuple
    interval: int


def _kind(status):
    """0 surface (OK, LINE), 1 edge, 2 none."""
    s = np.asarray(status)
    return np.where(s == ContactStatus.EDGE, 1, np.where(s == ContactStatus.NO_CONTACT, 2, 0))


def flagged_intervals(res, margin: float = EVENT_MARGIN) -> np.ndarray:
    """Indices i of the intervals (positions i, i + 1) of ``res`` where some tooth pair's contact changes kind
    (surface, edge, none) and that pair's TE at an end of the interval is within ``margin`` (rad) of the contact
    there (the lower of the two ends' TE): where a short event could hide."""
    k = _kind(res.status_pairs)
    change = k[1:] != k[:-1]                                  # (n - 1, P)
    te = np.where(np.isfinite(res.te_pairs), res.te_pairs, -np.inf)
    near = np.maximum(te[1:], te[:-1]) >= (np.minimum(res.te[1:], res.te[:-1]) - margin)[:, None]
    return np.flatnonzero(np.any(change & near, axis=1))


def events_between(solve, res, factor: int = 8, margin: float = EVENT_MARGIN) -> list[ContactEvent]:
    """Contacts that lead between the positions of a TCA, found by solving the flagged intervals
    (:func:`flagged_intervals`) ``factor`` times finer.

    Parameters
    ----------
    solve : callable
        ``solve(n_positions) -> TCAResult``: the same TCA (surfaces, kinematics, misalignment, mean position, start,
        pairs) with another number of positions, e.g. ``lambda n: solve_tca(pinion, gear, kin, n_positions=n,
        start=start)``.
    res : TCAResult
        The TCA to check (``solve(len(res.phi1))``).
    factor : int
        Sub-steps per step; the finer TCA has ``factor (n - 1) + 1`` positions, which include those of ``res``.
    margin : float, rad

    Returns
    -------
    list of ContactEvent
        At the finer positions inside flagged intervals: every edge contact that leads, and every contact whose TE
        lies above the TE at both ends of its interval (a peak the positions miss). Empty where nothing is flagged
        (no finer TCA is solved then).
    """
    if int(factor) != factor or factor < 2:
        from ..errors import DesignError

        raise DesignError.single("factor", factor, "integer >= 2", "-")
    flag = flagged_intervals(res, margin)
    if not flag.size:
        return []
    n = len(res.phi1)
    fine = solve(int(factor) * (n - 1) + 1)
    if not np.allclose(fine.phi1[::factor], res.phi1, rtol=0, atol=1e-12):
        raise ValueError("solve(n) must give the TCA of res with n positions over the same cycle")
    edges = {e[0]: e[2:] for e in fine.edges}
    out = []
    for i in flag:
        top = max(res.te[i], res.te[i + 1])
        for f in range(i * factor + 1, (i + 1) * factor):
            st = int(fine.status[f])
            if st == ContactStatus.NO_CONTACT:
                continue
            if st == ContactStatus.EDGE or fine.te[f] > top + 1e-3 * ARCSEC:
                out.append(ContactEvent(float(fine.phi1[f]), float(fine.te[f]), int(fine.pairs[fine.pair[f]]), st,
                                        tuple(edges.get(f, ())), int(i)))
    return out
