"""Bad rating inputs give clear errors naming the design-file key, the value, the allowed range and the unit."""

import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.errors import DesignError
from spiralbevel.io.design_file import bundled_designs, parse_design
from spiralbevel.rating import RatingInput

SAMPLE = bundled_designs()["iso23509_sample1"].read_text(encoding="utf-8")


def _replace(text, key, line):
    out = []
    for ln in text.splitlines():
        out.append(line if ln.split("=")[0].strip() == key and line is not None else ln)
        if line is None and ln.split("=")[0].strip() == key:
            out.pop()
    return "\n".join(out) + "\n"


@pytest.mark.parametrize("key, line, field, words", [
    ("pinion_speed", "pinion_speed = 0", "rating.pinion_speed", ["> 0", "1/min"]),
    ("pinion_torque", "pinion_torque = -300", "rating.pinion_torque", ["> 0", "N m"]),
    ("sigma_Hlim", None, "rating.sigma_Hlim", ["required", "N/mm^2"]),
    ("sigma_Flim", None, "rating.sigma_Flim", ["required", "N/mm^2"]),
    ("oil_viscosity", None, "rating.oil_viscosity", ["required", "mm^2/s"]),
    ("mounting", 'mounting = "floating"', "rating.mounting", ["both-straddle"]),
    ("profile_crowning", 'profile_crowning = "medium"', "rating.profile_crowning", ["low", "high"]),
    ("pitch_deviation", "pitch_deviation = [12, -1]", "rating.pitch_deviation", ["> 0"]),
])
def test_schema_errors(key, line, field, words):
    with pytest.raises(DesignError) as err:
        parse_design(_replace(SAMPLE, key, line))
    text = str(err.value)
    assert field in text
    for w in words:
        assert w in text, text


def test_torque_or_power():
    both = SAMPLE.replace("pinion_torque = 300.0", "pinion_torque = 300.0\npower = 37.7")
    with pytest.raises(DesignError, match="exactly one of pinion_torque"):
        parse_design(both)
    with pytest.raises(DesignError, match="exactly one of pinion_torque"):
        parse_design(_replace(SAMPLE, "pinion_torque", None))


def test_cli_exit_code_and_message(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text(_replace(SAMPLE, "pinion_speed", "pinion_speed = 0"))
    res = CliRunner().invoke(app, ["rate", str(p)])
    assert res.exit_code == 2
    assert "rating.pinion_speed" in res.output and "Traceback" not in res.output


def test_design_without_rating_section():
    res = CliRunner().invoke(app, ["rate", "aviation_23x65_logspiral"])
    assert res.exit_code == 2
    assert "[rating]" in res.output


def test_rating_input_validates():
    ok = dict(T1=300.0, n1=1200.0, f_pt=(12.0, 26.0), rho_a0=(0.8, 1.2), sigma_Hlim=(1500.0, 1500.0),
              sigma_Flim=(480.0, 480.0), nu40=150.0)
    RatingInput(**ok)
    for key, bad in (("n1", 0.0), ("T1", -1.0), ("K_A", 0.9), ("f_pt", (12.0,)), ("nu40", float("nan")),
                     ("sigma_Hlim", (1500.0, 0.0)), ("mounting", "floating"),
                     ("profile_crowning", "medium")):
        with pytest.raises(DesignError, match=key):
            RatingInput(**{**ok, key: bad})
