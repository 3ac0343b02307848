"""Seed 001 (Liu, Chen, Li, Machines 2024, 12, 34), Table 1 blank data, as decoded in docs/theory/example.md

Inputs: 23/65 teeth, Σ = 90°, outer transverse module 3.9 mm, b = 37 mm, β = 30°, α = 20°, cutter radius 114.3 mm
(Table 4), dedendum angles θf1 = 1°05′50″, θf2 = 2°29′20″ given (uniform clearance: θa1 = θf2, θa2 = θf1).
"""

import math

import pytest

from spiralbevel.conventions import Hand
from spiralbevel.design.blank import compute_blank
from spiralbevel.design.blank_input import BlankInput


def dms(d, m=0, s=0.0):
    return math.radians(d + m / 60 + s / 3600)


@pytest.fixture(scope="module")
def blank():
    inp = BlankInput(z1=23, z2=65, met=3.9, b=37.0, beta_m=math.radians(30), rc0=114.3, hand1=Hand.RIGHT,
                     alpha_dD=math.radians(20), alpha_dC=math.radians(20), taper="given",
                     theta_f1=dms(1, 5, 50), theta_f2=dms(2, 29, 20))
    return compute_blank(inp)


def test_pitch_angles_rounded_to_the_minute(blank):
    # Table 1: 19°29′ and 70°31′ (rounded to the minute) -> within half a minute
    assert abs(blank.delta1 - dms(19, 29)) <= dms(0, 0.5)
    assert abs(blank.delta2 - dms(70, 31)) <= dms(0, 0.5)
    # docs/theory/example.md: atan(23/65) = 19°29′10.1″
    assert abs(blank.delta1 - dms(19, 29, 10.1)) <= dms(0, 0, 0.05)


def test_mean_cone_distance(blank):
    # Table 1: A_m = 115.9511 mm (= m z2 / (2 sin γ2) − b/2, docs/theory/example.md), printed to 4 decimals
    assert blank.Rm == pytest.approx(115.9511, abs=5e-5)
    assert blank.Rm1 == blank.Rm2 == blank.Rm


def test_face_and_root_angles(blank):
    # Table 1, printed to the arcsecond -> within half an arcsecond
    half_sec = dms(0, 0, 0.5)
    assert abs(blank.delta_a1 - dms(21, 58, 30)) <= half_sec
    assert abs(blank.delta_a2 - dms(71, 36, 40)) <= half_sec
    assert abs(blank.delta_f1 - dms(18, 23, 20)) <= half_sec
    assert abs(blank.delta_f2 - dms(68, 1, 30)) <= half_sec


def test_face_width_ratios_and_hands(blank):
    # docs/theory/example.md: b/A_o = 0.275 <= 0.3 and b/m = 9.49 <= 10 -> no face width warning
    assert blank.b2 / blank.Re2 == pytest.approx(0.2752, abs=1e-4)
    assert not any("face width" in w for w in blank.warnings)
    assert blank.hand1 is Hand.RIGHT and blank.hand2 is Hand.LEFT


def test_uniform_clearance_given_as_addendum_angles_is_equivalent(blank):
    inp = BlankInput(z1=23, z2=65, met=3.9, b=37.0, beta_m=math.radians(30), rc0=114.3, hand1="RH", taper="given",
                     theta_a1=dms(2, 29, 20), theta_a2=dms(1, 5, 50))
    other = compute_blank(inp)
    assert other.delta_a1 == pytest.approx(blank.delta_a1, abs=1e-15)
    assert other.delta_f2 == pytest.approx(blank.delta_f2, abs=1e-15)
