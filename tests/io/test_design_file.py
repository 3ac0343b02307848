import pytest

from spiralbevel.errors import DesignError
from spiralbevel.io.design_file import load_design, parse_design

MINIMAL = """
[gear_set]
pinion_teeth = 23
gear_teeth = 65
module = 3.9
face_width = 37
mean_spiral_angle = "30°00'"
"""


def test_default_design_is_seed001_table1():
    d = load_design()
    g = d.gear_set
    assert (g.pinion_teeth, g.gear_teeth) == (23, 65)
    assert (g.shaft_angle, g.module, g.face_width, g.mean_spiral_angle, g.normal_pressure_angle) == (
        90.0, 3.9, 37.0, 30.0, 20.0)
    assert d.flank.kind == "log-spiral"
    theta_f1, theta_f2 = g.depth.dedendum_angles
    assert theta_f1 == pytest.approx(1 + 5 / 60 + 50 / 3600)
    assert theta_f2 == pytest.approx(2 + 29 / 60 + 20 / 3600)


def test_minimal_design_defaults():
    d = parse_design(MINIMAL)
    assert d.gear_set.mean_spiral_angle == 30.0
    assert d.gear_set.pinion_hand == "RH"
    assert d.output.grid == (31, 15)


def _problems(text):
    with pytest.raises(DesignError) as info:
        parse_design(text)
    return {p.field: p for p in info.value.problems}, str(info.value)


def test_every_problem_listed_with_field_value_range_unit():
    text = MINIMAL.replace("pinion_teeth = 23", "pinion_teeth = -3").replace(
        "mean_spiral_angle = \"30°00'\"", "mean_spiral_angle = 95").replace(
        "face_width = 37", "face_width = 37\ncolour = 1")
    probs, message = _problems(text)
    assert set(probs) == {"gear_set.pinion_teeth", "gear_set.mean_spiral_angle", "gear_set.colour"}
    p = probs["gear_set.mean_spiral_angle"]
    assert p.value == 95.0 and p.unit == "deg" and "< 60" in p.allowed
    assert "gear_set.pinion_teeth = -3" in message and ">= 5" in message
    assert "unknown key" in str(probs["gear_set.colour"])


def test_malformed_toml():
    probs, message = _problems("[gear_set\npinion_teeth = 3")
    assert "malformed TOML" in message


def test_bad_angle_string():
    probs, _ = _problems(MINIMAL.replace("\"30°00'\"", "\"thirty\""))
    assert "cannot read" in probs["gear_set.mean_spiral_angle"].reason


def test_module_xor_diameter():
    _, message = _problems(MINIMAL.replace("module = 3.9", "outer_pitch_diameter = 253.5\nmodule = 3.9"))
    assert "exactly one of module" in message


def test_missing_required():
    probs, _ = _problems("[gear_set]\npinion_teeth = 23\n")
    assert {"gear_set.gear_teeth", "gear_set.face_width", "gear_set.mean_spiral_angle"} <= set(probs)
    assert probs["gear_set.face_width"].unit == "mm"


def test_missing_file(tmp_path):
    with pytest.raises(DesignError, match="file not found"):
        load_design(tmp_path / "nope.toml")


def test_tca_positions_key():
    """[tca] positions: default 41; out of range names the key, the value and the range."""
    from spiralbevel.errors import DesignError
    from spiralbevel.io.design_file import default_design_text, parse_design

    assert parse_design(default_design_text()).tca.positions == 41
    assert parse_design(default_design_text() + "\n[tca]\npositions = 241\n").tca.positions == 241
    with pytest.raises(DesignError) as e:
        parse_design(default_design_text() + "\n[tca]\npositions = 3\n")
    assert "tca.positions" in str(e.value) and "3" in str(e.value) and "11" in str(e.value)


def test_number_given_with_a_unit_says_to_write_a_bare_number():
    """"5 mm" or "30mm" for a length: the message says to write a bare number and which unit the key is in, and does not
    put the unit after the quoted value ('5 mm' mm)."""
    text = ("[gear_set]\npinion_teeth = 12\ngear_teeth = 41\nmodule = \"5 mm\"\nface_width = \"30mm\"\n"
            "mean_spiral_angle = 35\n")
    with pytest.raises(DesignError) as ei:
        parse_design(text)
    msgs = {p.field: str(p) for p in ei.value.problems}
    for key, given in (("gear_set.module", "'5 mm'"), ("gear_set.face_width", "'30mm'")):
        assert f"{key} = {given}:" in msgs[key], msgs[key]
        assert f"write a bare number without quotes or unit: {key} is in mm" in msgs[key]
        assert "<= " in msgs[key] and msgs[key].split("(")[0].rstrip().endswith("mm")   # the range keeps its unit
