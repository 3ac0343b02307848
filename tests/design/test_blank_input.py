"""Validation of BlankInput: every bad field is named with its value, allowed range and unit, all at once."""

import math

import pytest

from spiralbevel.conventions import Hand
from spiralbevel.design.blank_input import BlankInput
from spiralbevel.errors import DesignError

R = math.radians
GOOD = dict(z1=14, z2=39, de2=176.893, b=25.4, beta_m=R(35.0), rc0=114.3)


def fields_of(err: DesignError) -> set[str]:
    return {p.field for p in err.problems}


def test_good_input_builds():
    inp = BlankInput(**GOOD)
    assert inp.u == pytest.approx(39 / 14) and inp.de2_value == 176.893
    assert inp.c_ham_value == pytest.approx(0.210 + 0.290 / (39 / 14) ** 2)


def test_offset_beyond_the_wheel_radius_is_rejected_with_a_clear_reason():
    BlankInput(**GOOD, a=5.0)  # a hypoid offset is accepted (ISO 23509 Method 1)
    for a in (1e4, float("nan")):
        with pytest.raises(DesignError) as ei:
            BlankInput(**GOOD, a=a)
        assert fields_of(ei.value) == {"a"}
        assert ei.value.problems[0].unit == "mm"
    with pytest.raises(DesignError, match="computes the pinion face width") as ei:
        BlankInput(**GOOD, a=5.0, b1=30.0)
    assert fields_of(ei.value) == {"b1"}


def test_all_problems_are_listed_at_once():
    with pytest.raises(DesignError) as ei:
        BlankInput(z1=3, z2=39, de2=-1.0, b=float("nan"), beta_m=R(80), rc0=0.0, alpha_dD=R(50), k_c=-0.1)
    assert fields_of(ei.value) == {"z1", "de2", "b", "beta_m", "rc0", "alpha_dD", "k_c"}
    text = str(ei.value)
    assert "7 problems" in text and "beta_m = 80.0 deg" in text and "0 <= beta_m < 75 deg" in text


@pytest.mark.parametrize("kw,field", [
    (dict(met=4.5), "de2/met"),  # both sizes
    (dict(de2=None), "de2/met"),  # none
    (dict(jen=0.1, jet=0.1), "jen/jet"),
    (dict(taper="spiral"), "taper"),
    (dict(theta_f1=0.01), "theta_f1"),  # theta with a computed taper
    (dict(taper="given", theta_f1=0.01), "theta_f2/theta_a1"),
    (dict(taper="given", theta_f1=0.01, theta_a2=0.02, theta_f2=0.1), "theta_a2"),  # not uniform clearance
    (dict(shaft_angle=R(150)), "shaft_angle"),  # internal wheel
    (dict(hand1="XX"), "hand1"),
    (dict(z1=40), "z1"),  # z1 > z2
    (dict(z2=39.0), "z2"),  # not an integer
    (dict(b=100.0), "b"),  # beyond the apex
    (dict(b1=200.0), "b1"),
    (dict(rc0=20.0), "rc0"),  # duplex needs rc0 > Rm sin(beta)
    (dict(c_ham=1.2), "c_ham"),
    (dict(f_alim=2.0), "f_alim"),
    (dict(k_t=0.9), "k_t"),
])
def test_each_bad_input_names_its_field(kw, field):
    with pytest.raises(DesignError) as ei:
        BlankInput(**{**GOOD, **kw})
    assert field in fields_of(ei.value)
    p = next(p for p in ei.value.problems if p.field == field)
    assert p.allowed  # an allowed range is always given


def test_hand_accepts_strings():
    assert BlankInput(**GOOD, hand1="rh").hand1 is Hand.RIGHT
    assert BlankInput(**GOOD, hand1="LH").hand1 is Hand.LEFT


NUMERIC = ["de2", "b", "beta_m", "rc0", "shaft_angle", "alpha_dD", "alpha_dC", "k_d", "k_c", "jen", "a"]
BAD = [float("nan"), float("inf"), -1.0, -1e-9, 1e9, "3", None]
VALID = {("jen", None), ("jen", 1e9), ("rc0", 1e9),  # no or huge backlash, huge cutter
         ("a", -1.0), ("a", -1e-9)}  # a hypoid offset of either sign (ISO 23509 Method 1)
# a huge wheel is valid by itself, but then the cutter is too small for the duplex taper -> rc0 is named
CULPRIT = {("de2", None): "de2/met", ("de2", 1e9): "rc0"}


@pytest.mark.parametrize("field", NUMERIC)
@pytest.mark.parametrize("value", BAD, ids=repr)
def test_bad_numeric_values_raise_design_error_naming_the_field(field, value):
    kw = {**GOOD, field: value}
    if (field, value) in VALID:
        BlankInput(**kw)
        return
    with pytest.raises(DesignError) as ei:
        BlankInput(**kw)
    expected = CULPRIT.get((field, value), field)
    assert expected in fields_of(ei.value)
