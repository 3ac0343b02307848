"""Checks on a developed pair: pinion undercut at the achieved pressure angles, design-vs-achieved per flank."""

import math
import warnings

import pytest

from spiralbevel.conventions import Member, Side
from spiralbevel.design.blank_checks import achieved_undercut, section_limit_depth
from spiralbevel.generation.basic_settings_solve import FlankFit
from spiralbevel.io.design_file import parse_design
from spiralbevel.job.blank import blank_from_design
from spiralbevel.job.facemilled import flank_checks

DESIGN = """
[gear_set]
pinion_teeth = {z1}
gear_teeth = 41
shaft_angle = 90
module = 5
face_width = 30
normal_pressure_angle = 20
mean_spiral_angle = 35
pinion_hand = "RH"
[flank]
kind = "face-milled"
"""


@pytest.mark.parametrize("z1", [9, 12])
def test_undercut_threshold_at_the_achieved_angle(z1):
    """The root-undercut warning switches on exactly where (dvn1/2) sin^2(alpha) = hfm1: the threshold angle by the
    closed-form inversion of the nominal limit depth, L(alpha) = L(alpha_n) sin^2(alpha) / sin^2(alpha_n)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        bl = blank_from_design(parse_design(DESIGN.format(z1=z1)))
    a0 = min(bl.alpha_nD, bl.alpha_nC)
    L0 = section_limit_depth(bl, 1, "m")
    a_root = math.asin(math.sqrt(bl.hfm1 / L0) * math.sin(a0))     # hfm1 = L(a_root)
    a_active = math.asin(math.sqrt(bl.ham2 / L0) * math.sin(a0))   # ham2 = L(a_active) < a_root
    d = math.radians(0.01)
    assert achieved_undercut(bl, a_root + d, math.radians(25.0)) == []
    below = achieved_undercut(bl, math.radians(25.0), a_root - d)   # the smaller of the two angles counts
    assert len(below) == 1 and "root undercut" in below[0] and "gear_set.normal_pressure_angle" in below[0]
    active = achieved_undercut(bl, a_active - d, a_active - d)
    assert len(active) == 1 and "gear_set.pinion_teeth" in active[0]


def test_flank_checks_name_the_key():
    a, b = math.radians(20.0), math.radians(35.0)
    ok = FlankFit(a, a + math.radians(0.04), b, b - math.radians(0.04), (0.0, -0.009, 0.002), 3)
    assert flank_checks(ok, Member.GEAR, Side.CONVEX) == []
    bad = FlankFit(a, a - math.radians(0.3), b, b + math.radians(0.1), (-0.02, None, 0.0), 3)
    msgs = flank_checks(bad, Member.PINION, Side.CONCAVE)
    assert len(msgs) == 3
    assert "face_milling.pinion_concave.cutter.blade_angle" in msgs[0] and "-0.300 deg" in msgs[0]
    assert "face_milling.pinion_concave.machine" in msgs[1]
    assert "below the blank's root cone at the toe" in msgs[2]
