"""The bearing warning names the key the user can change: given pinion settings, a synthesized side, or a side that a
``[synthesis]`` section leaves out (its pinion flank then has the basic settings from the blank, which the design file
does not give: the warning once told the user to remove settings they never wrote)."""

from types import SimpleNamespace

import numpy as np

from spiralbevel.gearset.run_facemilled import pinion_settings_given
from spiralbevel.io.design_file import parse_design
from spiralbevel.meshing.tca_checks import bearing_warnings

BASE = """
[gear_set]
pinion_teeth = 12
gear_teeth = 41
module = 5
face_width = 30
mean_spiral_angle = 35
[flank]
kind = "face-milled"
"""
PARTIAL = BASE + "[synthesis]\nte_magnitude = 12\n"
GIVEN = BASE + """[face_milling.pinion_convex.machine]
radial_setting = 90.0
cradle_angle = 60.0
machine_root_angle = 15.0
ratio_of_roll = 3.5
"""


def _res_with_one_edge_contact():
    te = np.zeros(41)
    edge = np.zeros(41, bool)
    edge[3] = True
    return SimpleNamespace(te=te, edge_contact=edge, edges=[(3, 0, "gear", "top")])


def test_settings_given_is_read_from_the_design_file():
    assert not pinion_settings_given(parse_design(PARTIAL), "coast")
    assert not pinion_settings_given(parse_design(PARTIAL), "drive")
    assert pinion_settings_given(parse_design(GIVEN), "coast")
    assert not pinion_settings_given(parse_design(GIVEN), "drive")


def test_warning_names_the_key_of_each_case():
    res = _res_with_one_edge_contact()
    (given,) = bearing_warnings(res, "coast", synthesized=False, given=True)
    assert "face_milling.pinion_convex.machine" in given and "at 1 of 41" in given
    (left_out,) = bearing_warnings(res, "coast", synthesized=False, given=False)
    assert "synthesis.sides" in left_out and '"coast"' in left_out
    assert "face_milling" not in left_out and "given settings" not in left_out
    (synth,) = bearing_warnings(res, "coast", synthesized=True)
    assert "synthesis.path_direction" in synth


def test_default_search_warning_says_to_give_both_sides():
    """A default-synthesized side that keeps an edge contact: a [synthesis] section with only path_direction would
    synthesize the drive side alone (its ``sides`` default), so the message names sides with both."""
    res = _res_with_one_edge_contact()
    (text,) = bearing_warnings(res, "drive", synthesized=True, default=True)
    assert 'sides = ["drive", "coast"]' in text and "synthesis.path_direction" in text
    assert "default synthesis" in text
