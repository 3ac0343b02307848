"""The default synthesis judges the contact between the TCA positions too: a short edge contact at a tooth-pair
transfer.

Where the contact passes from one tooth pair to the next, the incoming pair can touch first with an edge (the gear's
top edge on the 14/56 and 10/54 designs of bench/bench_robustness.py 40 1, the pinion's top on the 13/20 of
tests/meshing/test_tca_events.py) for about a percent of the mesh cycle, and a TCA of 41 positions steps over it.
Under load that edge carries load: the bearing is not inside the flanks, and the default synthesis must not take such
a pair as one whose bearing stays inside. The check solves the intervals where a tooth pair's contact changes kind
(surface, edge, none) near the leading contact eight times finer
(:func:`~spiralbevel.meshing.tca_events.events_between`, the detector the job's TCA report uses for its
``short_events``) and counts the finer positions at which an edge contact leads.

Why a transfer runs onto an edge: with a parabolic TE of level a over half a mesh cycle on each side of each pair's
mean contact, the two pairs' TE curves cross half a cycle from each one's mean, where each has dropped by a; there the
incoming pair's contact lies half a cycle's travel from M along the path of contact. When the path's profile component
over that half cycle is longer than the room between M and the edge it runs toward (a small gear addendum, a path
close to the profile direction), that contact of the extended flanks lies beyond the edge; the real flank ends there,
and the pair touches with its edge, which leads until the surface contact comes back onto the flank. Turning the path
toward the lengthwise direction shortens its profile component per cycle (the search's path directions,
``DEFAULT_PATH_DIRECTIONS`` and ``DEFAULT_LENGTHWISE_DIRECTIONS`` of ``gearset.facemilled``), and its depth candidates
move M away from the gear's top; the search already holds candidates that cure it and needed only to see it. Measured:
on the 14/56 coast pinion at beta 35.4 deg (bench/bench_robustness.py 40 1, gear addendum 1.29 mm) the path at -55 deg
keeps all 41 positions inside but runs to 1.24 mm above the pitch cone at the end of the cycle, and the incoming
pair's gear top edge leads at the transfer; at -70 deg the contact stays within 0.7 mm of the pitch cone and no edge
leads anywhere (tests/meshing/test_transfer_edge_default.py). The reading at the transfer point itself -- whether
either pair's surface contact at the exact transfer point (``TCAResult.transfer_phi1``) lies beyond a flank boundary,
one Newton solve per pair -- agrees: over the 360 candidates of the bench's 100-design sample whose 41 positions were
all inside, it flagged all 110 that this check finds and 8 of the 250 it clears (40-design sample: 43 of 43, 1 of 98).
It costs 0.5 ms against this check's 5-50 ms (one finer TCA, only where an interval is flagged); this check is kept as
the judge because it is the job report's own detector (``gearset.tca.short_events``) and names the edge, and it runs
only for a candidate whose positions are all inside.
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

