"""A ``[synthesis]`` section overrides the developed-pair defaults key by key (issue 11 item 3): a key it leaves out
keeps the default (both sides, semi-major axis 0.15 b, approach b/5827, 8 arcsec), and without ``path_direction`` the
default search over path directions runs. A section with only ``te_magnitude = 12`` once synthesized the drive side
alone at the schema's seed 001 path direction (6 deg) and left the coast unsynthesized.

The expected values come from the design file's face width (b = 30 mm) and the documented defaults, not from the
function under test."""

import warnings

import pytest

from spiralbevel.gearset.default_synthesis import effective_synthesis
from spiralbevel.io.design_file import parse_design
from spiralbevel.job.blank import blank_from_design
from _design_12x41 import design_12x41

B = 30.0   # face width of design_12x41, mm


def _sy(extra=""):
    spec = parse_design(design_12x41() + extra)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # the blank's design warnings are not under test here
        blank = blank_from_design(spec)
    return effective_synthesis(spec, blank)


def _is_default_search(sy) -> bool:
    return getattr(sy, "_default", False)


def test_no_section_is_the_developed_default():
    sy = _sy()
    assert _is_default_search(sy) and sy.sides == ("drive", "coast")
    assert sy.semi_major_axis == pytest.approx(0.15 * B, rel=1e-12)
    assert sy.approach == pytest.approx(0.00635 / 37.0 * B, rel=1e-12)
    assert sy.te_magnitude == 8.0


def test_partial_section_keeps_the_other_defaults():
    sy = _sy("\n[synthesis]\nte_magnitude = 12\n")
    assert _is_default_search(sy)                 # no path_direction given: the search over path directions
    assert sy.sides == ("drive", "coast") and sy.te_magnitude == 12.0
    assert sy.semi_major_axis == pytest.approx(0.15 * B, rel=1e-12)
    assert sy.approach == pytest.approx(0.00635 / 37.0 * B, rel=1e-12)
    assert sy.free == "offset"
    sy = _sy('\n[synthesis]\nfree = "fixed-blade"\nsemi_major_axis = 4\n')
    assert _is_default_search(sy) and sy.free == "fixed-blade" and sy.semi_major_axis == 4.0
    assert sy.te_magnitude == 8.0 and sy.sides == ("drive", "coast")


def test_given_path_direction_is_used_as_given():
    sy = _sy("\n[synthesis]\npath_direction = 30\n")
    assert not _is_default_search(sy) and sy.path_direction == 30.0
    assert sy.sides == ("drive", "coast") and sy.te_magnitude == 8.0
    assert sy.semi_major_axis == pytest.approx(0.15 * B, rel=1e-12)
    sy = _sy('\n[synthesis]\nsides = ["drive"]\npath_direction = 6\nsemi_major_axis = 3.7\nte_magnitude = 3\n')
    assert not _is_default_search(sy) and sy.sides == ("drive",)
    assert (sy.path_direction, sy.semi_major_axis, sy.te_magnitude) == (6.0, 3.7, 3.0)


def test_side_with_given_pinion_settings_is_left_alone():
    given = """
[face_milling.pinion_convex.machine]
radial_setting = 90.0
cradle_angle = 60.0
machine_root_angle = 15.0
ratio_of_roll = 3.5
"""
    sy = _sy(given + "\n[synthesis]\nte_magnitude = 12\n")
    assert sy.sides == ("drive",) and sy.te_magnitude == 12.0
