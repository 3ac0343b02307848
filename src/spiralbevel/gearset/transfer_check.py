"""The default synthesis judges the contact between the TCA positions too: a short edge contact at a tooth-pair
transfer.

Where the contact passes from one tooth pair to the next, the incoming pair can touch first with an edge (the gear's
top edge on the coast side of many designs, the pinion's top on others) for about a percent of the mesh cycle, and a
TCA of 41 positions steps over it. Under load that edge carries load: the bearing is not inside the flanks, and the
default synthesis must not take such a pair as one whose bearing stays inside. The check solves the intervals where
a tooth pair's contact changes kind (surface, edge, none) near the leading contact eight times finer
(:func:`~spiralbevel.meshing.tca_events.events_between`, the detector the job's TCA report uses for its
``short_events``) and counts the finer positions at which an edge contact leads.

Why a transfer runs onto an edge: with a parabolic TE of level a over half a mesh cycle on each side of each pair's
mean contact, the two pairs' TE curves cross at half a cycle from the mean, where each has dropped by a. The
incoming pair's contact point at that rotation lies half a cycle's path length from its mean point along the path of
contact; when the path, measured along the profile, is longer than the room between the mean point and the edge it
runs toward, that point lies beyond the edge and the real contact there is the edge's (its TE rises above the
surface contact's, so the edge leads briefly before the surface contact takes over). The path advances per mesh
cycle by one transverse base pitch, projected on the path direction; turning the path toward the lengthwise
direction shortens its profile component, and the search's path directions do that (``DEFAULT_PATH_DIRECTIONS`` of
``gearset.facemilled``), as its depth candidates move the mean point away from the gear's top.
"""

from __future__ import annotations

import numpy as np

__all__ = ["short_edge_positions"]

#: finer positions per step of the checked TCA (as the job's report, ``gearset.tca.short_events``)
FACTOR = 8


def short_edge_positions(pair, res) -> int:
    """Number of finer positions (``FACTOR`` per step of ``res``) between the positions of a TCA at which an edge
    contact leads (:func:`~spiralbevel.meshing.tca_events.events_between`).

    Parameters
    ----------
    pair : MeshingPair
        The aligned pair ``res`` was solved on (its start; ``res`` centred on phi1 = its mean position).
    res : TCAResult
        The TCA to check.

    Returns
    -------
    int
        0 when no interval is flagged or no edge contact leads in one; the count of finer positions with a leading
        edge contact otherwise; ``len(res.phi1)`` when the finer TCA cannot be solved (the pair is not judged
        inside then).
    """
    from ..errors import ConvergenceError, NoContactError
    from ..meshing.tca import solve_tca
    from ..meshing.tca_events import events_between
    from ..meshing.tca_result import ContactStatus

    mean = 0.5 * float(res.phi1[0] + res.phi1[-1])

    def solve(n):
        return solve_tca(pair.pinion, pair.gear, pair.kinematics, n_positions=n, phi1_mean=mean, start=pair.start)

    try:
        ev = events_between(solve, res, factor=FACTOR)
    except (NoContactError, ConvergenceError, ValueError):
        return len(res.phi1)
    return int(np.sum([e.status == ContactStatus.EDGE for e in ev]))

