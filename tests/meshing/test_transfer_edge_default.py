"""The default synthesis judges the contact between the TCA positions (gearset/transfer_check.py), on the coast side of
the 14/56 design of the robustness bench (bench/bench_robustness.py 40 1, design 24: beta 35.4 deg, a gear addendum of
1.29 mm against the pinion's 4.35 mm).

The search used to take the first path direction whose 41-position TCA keeps the bearing inside: -55 deg, where the
incoming pair touches with the gear's top edge for about a percent of the cycle at its transfer point, between two
positions. Both picks are checked by means independent of the detector the search uses (which refines flagged
intervals of the 41-position TCA eight times): a dense TCA of 401 positions (ten per step, not the detector's grid
between the positions) and the brute-force gap oracle (tests/meshing/_gap_oracle.py: the first touch of the real
flanks, surface, edge or corner alike, from sampled flanks and no contact equations) at the positions about the
transfer.
"""

import math
import warnings

import numpy as np
import pytest

from _designs import basic_design, basic_setups
from _gap_oracle import tca_deviation

from spiralbevel.conventions import Member
from spiralbevel.gearset import facemilled as gfm
from spiralbevel.meshing import synthesis as syn
from spiralbevel.meshing.pair import meshing_pair
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_result import ARCSEC, ContactStatus

#: bench_robustness.py 40 1, design 24, as the bench writes it
DESIGN = basic_design(14, 56, shaft_angle="77.257", module="3.764", face_width="18.872", mean_spiral_angle="35.441",
                      hand="LH", cutter_radius="103.49", title="bench design")

#: the dense TCA's positions: ten per step of the 41-position TCA (the detector refines by eight)
DENSE = 401

#: arcsec: TCA against the gap oracle, as in tests/meshing/test_tca_events.py (measured there at most 2.9e-6)
TOL_ARCSEC = 1e-5


@pytest.fixture(scope="module")
def coast():
    spec, blank, setups = basic_setups(DESIGN)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sy = gfm.effective_synthesis(spec, blank)
        new, _ = gfm.synthesize_sides(spec, blank, setups, sy.model_copy(update={"sides": ("coast",)}))
    s1, s2 = gfm.PAIR_SIDES["coast"]
    return blank, setups, sy, s1, setups[(Member.GEAR, s2)], new[(Member.PINION, s1)]


def _dense(blank, pinion_flank, gear_flank):
    pair = meshing_pair(pinion_flank, gear_flank, blank)
    return pair, solve_tca(pair.pinion, pair.gear, pair.kinematics, n_positions=DENSE, start=pair.start)


def _near_transfers(res, width=3):
    """Dense positions within ``width`` of each transfer point."""
    out = set()
    for t in np.atleast_1d(res.transfer_phi1):
        i = int(np.argmin(np.abs(res.phi1 - t)))
        out.update(range(max(i - width, 0), min(i + width + 1, len(res.phi1))))
    return sorted(out)


def test_old_pick_touches_the_gear_top_between_positions(coast):
    """The path at -55 deg (the old pick) keeps the contact on the real flanks at all 41 positions, but the dense
    TCA shows the incoming pair's contact on the gear's top edge leading near the transfer, which the oracle confirms;
    the search's judge counts it."""
    blank, setups, sy, s1, gear, _ = coast
    pin = setups[(Member.PINION, s1)]
    res = syn.synthesize_pinion(gear.cutter, gear.settings, blank, side=s1, eta=math.radians(-55.0),
                                semi_major_axis=sy.semi_major_axis, te_magnitude=sy.te_magnitude * ARCSEC,
                                approach=sy.approach, free=syn.FREE_OFFSET, pinion_cutter_hint=pin.cutter,
                                pinion_settings_hint=pin.settings)
    pair = meshing_pair(res.pinion_flank, gear.flank, blank)
    coarse = solve_tca(pair.pinion, pair.gear, pair.kinematics, n_positions=41, start=pair.start)
    assert np.all(coarse.status != ContactStatus.EDGE) and np.all(np.isfinite(coarse.te))
    _, dense = _dense(blank, res.pinion_flank, gear.flank)
    edge = [e for e in dense.edges if e[2:] == ("gear", "top")]
    assert edge
    d = tca_deviation(pair.pinion, pair.gear, pair.kinematics, dense, [edge[0][0]])
    assert np.all(np.abs(d) <= TOL_ARCSEC), d
    assert gfm.bearing_off_flank(blank, res.pinion_flank, gear.flank) > 0


def test_default_pick_has_no_edge_contact_between_positions(coast):
    """The default coast pinion: the dense TCA has real-flank surface contact at every position, and the oracle's
    first touch at the positions about each transfer is the TCA's (no edge leads there that the TCA misses)."""
    blank, _, _, _, gear, pinion = coast
    pair, dense = _dense(blank, pinion.flank, gear.flank)
    assert np.all(np.isin(dense.status, (ContactStatus.OK, ContactStatus.LINE))), dense.edges
    idx = _near_transfers(dense)[::2]
    d = tca_deviation(pair.pinion, pair.gear, pair.kinematics, dense, idx)
    assert np.all(np.abs(d) <= TOL_ARCSEC), d
