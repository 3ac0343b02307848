import math

import pytest
from hypothesis import given, strategies as st

from spiralbevel.io.angles import format_dms, parse_angle_deg


@pytest.mark.parametrize(
    "text, expected",
    [
        (30, 30.0),
        ("22.5", 22.5),
        ("22°30'", 22.5),
        ("59°20'07\"", 59 + 20 / 60 + 7 / 3600),
        ("59°20′07″", 59 + 20 / 60 + 7 / 3600),
        ("59 20 7", 59 + 20 / 60 + 7 / 3600),  # seed 001 OCR style "59 20 7"
        ("22d30m", 22.5),
        ("-1°20'", -(1 + 20 / 60)),
        ("68 1 30", 68 + 1 / 60 + 30 / 3600),
    ],
)
def test_parse_forms(text, expected):
    assert parse_angle_deg(text) == pytest.approx(expected, abs=1e-12)


@pytest.mark.parametrize("bad", ["abc", "22°70'", "", "1 2 75", True, None, float("nan")])
def test_parse_rejects(bad):
    with pytest.raises(ValueError):
        parse_angle_deg(bad)


@given(st.integers(0, 179), st.integers(0, 59), st.integers(0, 59))
def test_dms_round_trip(d, m, s):
    text = format_dms(d + m / 60 + s / 3600)
    assert parse_angle_deg(text) == pytest.approx(d + m / 60 + s / 3600, abs=1e-9)
    assert text == f"{d}°{m:02d}'{s:02d}\""


def test_format_seed001_cradle_angle():
    # seed 001 Table 4: q2 = 59°20'07"
    assert format_dms(math.degrees(math.radians(59 + 20 / 60 + 7 / 3600))) == "59°20'07\""
