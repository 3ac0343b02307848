"""Measurement grid and corrective settings on a hypoid pinion flank (ISO 23509 Sample 2, pinion by hypoid local
synthesis, generated with a blank offset; the member's view of the blank): known setting errors are recovered."""

import math

import numpy as np
import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.design.hypoid_member import member_blank
from spiralbevel.generation import generate_flank
from spiralbevel.manufacturing.correction import apply_changes, correct_settings
from spiralbevel.manufacturing.measurement import measure_deviation, measurement_grid
from spiralbevel.meshing.hypoid_pair import hypoid_basic_flanks
from _hypoid_sample2 import sample2_blank, sample2_concave_pinion

R = math.radians
TRUE = {"radial_setting": 0.05, "cradle_angle": R(0.01), "blank_offset": -0.03}


def test_round_trip_recovers_known_setting_errors():
    blank = sample2_blank()
    flanks = hypoid_basic_flanks(blank)
    syn = sample2_concave_pinion(blank, flanks, R(6.0), 3.7, 6.0 * math.pi / 648000.0)
    view = member_blank(blank, Member.PINION)
    key = (Member.PINION, Side.CONCAVE)
    cutter, settings = syn.pinion_cutter, syn.pinion_settings
    grid = measurement_grid(syn.pinion_flank)
    measured = measure_deviation(generate_flank(*apply_changes(cutter, settings, TRUE), view, *key), grid)
    assert np.max(np.abs(measured)) > 0.01
    res = correct_settings(cutter, settings, view, *key, grid, measured, parameters=tuple(TRUE), iterations=2)
    assert res.rank == 3 and not res.not_identifiable
    for name, value in TRUE.items():     # one chord Gauss-Newton step after the linear one, as for spiral bevels
        assert res.identified[name] / value == pytest.approx(1.0, abs=1e-4), name
    assert res.rms_after < 1e-4 * res.rms_before
