"""The bundled example aviation_23x65_logspiral_forged: every flank (crowned and relieved) draws from the die with the
requested draft angle on 100 % of its area, and the relief's two parameters are the smallest that do."""

from __future__ import annotations

import math

import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.manufacturing.forging import ForgingRelief, RelievedFlank, relieved_draft_map


@pytest.fixture(scope="module")
def forged():
    from spiralbevel.io.design_file import bundled_designs, load_design
    from spiralbevel.job import logspiral_production as lp
    from spiralbevel.job.blank import blank_from_design
    from spiralbevel.job.logspiral import design_pair

    spec = load_design(bundled_designs()["aviation_23x65_logspiral_forged"])
    pair = design_pair(spec, blank_from_design(spec))
    crowning = lp.design_crowning(spec, pair)
    return spec, pair, crowning, lp.design_reliefs(spec, pair, crowning)


def test_every_flank_passes_the_draft_everywhere(forged):
    spec, pair, _, reliefs = forged
    theta = math.radians(spec.manufacturing.draft_angle)
    assert theta > 0
    for key, rd in reliefs.items():
        res = relieved_draft_map(rd.relieved, spec.manufacturing.die_direction, theta)
        assert res.passes and res.failing_area_fraction == 0.0, key
    assert reliefs[(Member.PINION, Side.CONVEX)].relief is not None  # the crowned pinion convex flank needed one
    assert reliefs[(Member.PINION, Side.CONVEX)].theoretical_failing_fraction > 0


def test_less_relief_fails(forged):
    spec, pair, crowning, reliefs = forged
    f = pair.flank(Member.PINION, Side.CONVEX)
    rd = reliefs[(Member.PINION, Side.CONVEX)]
    r = rd.relief
    theta = math.radians(spec.manufacturing.draft_angle)
    step = (f.domain.psi_max - f.domain.psi_min) / 100  # one column of the 101 x 101 check grid
    for less in (ForgingRelief(r.start_psi - step, r.rate), ForgingRelief(r.start_psi, r.rate * (1 - 1e-4))):
        g = RelievedFlank(f.surface, f.domain, less, crowning.deviation())
        assert not relieved_draft_map(g, spec.manufacturing.die_direction, theta).passes


def test_report_section_of_the_forging_relief(forged, tmp_path):
    from spiralbevel.job import logspiral_production as lp

    spec, pair, crowning, reliefs = forged

    class Summary:
        files = []

    section = lp.forging_section(spec, pair, reliefs, crowning, tmp_path, Summary, plots=False)
    assert section["draft_angle_deg"] == spec.manufacturing.draft_angle
    flanks = section["flanks"]
    assert set(flanks) == {"pinion_convex", "pinion_concave", "gear_convex", "gear_concave"}
    assert all(f["passes"] and f["failing_area_fraction_after"] == 0.0 for f in flanks.values())
    pc = flanks["pinion_convex"]
    r = reliefs[(Member.PINION, Side.CONVEX)].relief
    assert pc["start_psi_deg"] == pytest.approx(math.degrees(r.start_psi)) and pc["rate"] == r.rate
    assert 0 < pc["max_deviation_um"] < 50 and pc["failing_area_fraction_before"] > 0
