"""Short contact events between TCA positions (spiralbevel.meshing.tca_events) on the coast pair of the developed
13/20 sample design (tests/meshing/_limit_line_pair.py): the incoming pinion's top edge leads for about 1.5 % of the
mesh cycle, a TE bump to +0.58 arcsec. With its position grid shifted by 0.2 of a step, the 21-position TCA shows no
edge contact and reads the TE's top as 0.00 arcsec; the events found in its flagged intervals are checked against the
independent gap oracle (tests/meshing/_gap_oracle.py) and against a dense TCA."""

import numpy as np
import pytest

from _gap_oracle import tca_deviation
from _limit_line_pair import coast_pair

from spiralbevel.errors import DesignError
from spiralbevel.meshing.tca import solve_tca
from spiralbevel.meshing.tca_events import events_between, flagged_intervals
from spiralbevel.meshing.tca_result import ARCSEC, ContactStatus

#: arcsec: TCA against the gap oracle, as in tests/meshing/test_tca_limit_line.py (measured there at most 2.9e-6)
TOL_ARCSEC = 1e-5


@pytest.fixture(scope="module")
def shifted():
    c1, c2, kin = coast_pair()
    T = 2 * np.pi / kin.z1
    sh = 0.2 * T / 20

    def solve(n):
        return solve_tca(c1, c2, kin, n_positions=n, phi1_mean=sh,
                         start=np.r_[c1.reference_params, c2.reference_params, -kin.z1 / kin.z2 * sh])

    return c1, c2, kin, solve


def test_events_the_positions_step_over_are_found_and_real(shifted):
    c1, c2, kin, solve = shifted
    res = solve(21)
    assert not res.edges and res.te.max() < 0.05 * ARCSEC      # the 21 positions step over the edge contact
    ev = events_between(solve, res, factor=8)
    assert ev and len(flagged_intervals(res)) <= 4
    edge = [e for e in ev if e.status == ContactStatus.EDGE]
    assert edge and all(e.edge == ("pinion", "top") and e.pair == -1 for e in edge)
    top = max(ev, key=lambda e: e.te)
    assert top.te > 0.4 * ARCSEC
    # the events are contacts of the finer TCA (161 positions, those of res among them), checked by the oracle
    fine = solve(161)
    idx = [int(np.argmin(np.abs(fine.phi1 - e.phi1))) for e in (top, edge[0])]
    assert np.allclose(fine.phi1[idx], [top.phi1, edge[0].phi1], rtol=0, atol=1e-12)
    d = tca_deviation(c1, c2, kin, fine, sorted(set(idx)))
    assert np.all(np.abs(d) <= TOL_ARCSEC), d
    # the dense TCA's top (641 positions, those of the finer one among them) is within 0.1 arcsec of the events' top:
    # the finer grid samples the bump every 1/160 of the cycle (measured: 0.583 against the events' top)
    dense = solve(641)
    assert 0.0 <= dense.te.max() - top.te < 0.1 * ARCSEC


def test_factor_is_checked(shifted):
    *_, solve = shifted
    with pytest.raises(DesignError, match="factor"):
        events_between(solve, solve(21), factor=1)


def test_job_section_lists_the_events_the_positions_step_over(shifted):
    """The job's TCA section (``gearset.tca.short_events``, solved again from the pair and the positions' mean) gives
    the events of :func:`events_between` on the same TCA, each in the report's units."""
    from spiralbevel.gearset.tca import short_events
    from spiralbevel.meshing.pair import MeshingPair

    c1, c2, kin, solve = shifted
    res = solve(21)
    sh = 0.5 * float(res.phi1[0] + res.phi1[-1])
    pair = MeshingPair(c1, c2, kin, np.r_[c1.reference_params, c2.reference_params, -kin.z1 / kin.z2 * sh])
    got = short_events(pair, res)
    want = events_between(solve, res, factor=8)
    assert len(got) == len(want) > 0
    for g, w in zip(got, want):
        assert g["pinion_rotation_deg"] == pytest.approx(np.degrees(w.phi1), abs=1e-9)
        assert g["transmission_error_arcsec"] == pytest.approx(w.te / ARCSEC, abs=1e-6)
        assert g["kind"] == ("edge" if w.status == ContactStatus.EDGE else "surface")
    assert any(g["kind"] == "edge" and (g["member"], g["edge"]) == ("pinion", "top") for g in got)
