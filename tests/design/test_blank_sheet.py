"""Dimension sheet (io/dimension_sheet.py), metadata and glossary coverage of the blank quantities."""

import json
import math
import pathlib
import re

import pytest

from spiralbevel.design.blank import compute_blank
from spiralbevel.design.blank_input import BlankInput
from spiralbevel.design.blank_meta import QUANTITIES, attribute_names
from spiralbevel.io.dimension_sheet import dimension_sheet_json, dimension_sheet_rows, format_dimension_sheet

R = math.radians
GLOSSARY = pathlib.Path(__file__).resolve().parents[2] / "docs" / "glossary.md"


@pytest.fixture(scope="module")
def blank():
    return compute_blank(BlankInput(z1=14, z2=39, de2=176.893, b=25.4, beta_m=R(35.0), rc0=114.3, c_ham=0.24737,
                                    k_t=0.0915, jen=0.127))


def test_every_attribute_in_the_table_exists_and_names_are_unique(blank):
    names = attribute_names()
    assert len(names) == len(set(names))
    for n in names:
        assert hasattr(blank, n), n
    required = ("z1 z2 u Sigma hand1 hand2 delta1 delta2 Re1 Re2 Rm1 Rm2 Rm Ri1 Ri2 b1 b2 de1 de2 dm1 dm2 di1 di2 met "
                "mmn mmt beta_m1 beta_m2 beta_e1 beta_e2 beta_i1 beta_i2 alpha_nD alpha_nC alpha_e hmw ham1 ham2 hfm1 "
                "hfm2 c hm theta_a1 theta_a2 theta_f1 theta_f2 delta_a1 delta_a2 delta_f1 delta_f2 hae1 hae2 hfe1 "
                "hfe2 he1 he2 hai1 hai2 hfi1 hfi2 dae1 dae2 dai1 dai2 rc0 smn1 smn2 smt1 txo1 txo2 tzF1 tzF2 tzR1 "
                "tzR2 smnc1 smnc2 hamc1 hamc2 dfe1 dfe2 dfi1 dfi2 ht1 ht2 tzm1 tzm2 tz1 tz2 be1 be2 bi1 bi2 x_smn "
                "x_sm1 x_sm2 sai1 sai2 sam1 sam2 sae1 sae2").split()
    assert set(required) <= set(names)


def test_rows_are_in_display_units(blank):
    rows = dimension_sheet_rows(blank)
    by_sym = {r[0]: r for r in rows}
    sym, desc, unit, p, g = by_sym["delta"]
    assert unit == "deg" and p == pytest.approx(math.degrees(blank.delta1)) and g == math.degrees(blank.delta2)
    assert by_sym["Re"][2] == "mm" and by_sym["Re"][4] == blank.Re2
    assert by_sym["hand"][3:] == ("LH", "RH")
    assert by_sym["Sigma"][3] == by_sym["Sigma"][4] == pytest.approx(90.0)
    # one row per table entry; the pair row Rm is left out because the member row shows Rm1 = Rm2 = Rm
    assert [r[0] for r in rows] == [b for b, _d, _k, scope in QUANTITIES if not (b == "Rm" and scope == "pair")]
    assert by_sym["Rm"][3:] == (blank.Rm1, blank.Rm2)


def test_json_is_serializable_and_complete(blank):
    j = dimension_sheet_json(blank)
    text = json.dumps(j, allow_nan=False)
    back = json.loads(text)
    keys = set(back["pair"]) | set(back["pinion"]) | set(back["gear"])
    assert keys == set(attribute_names()) == set(back["units"]) == set(back["descriptions"])
    assert all(k.endswith("1") for k in back["pinion"]) and all(k.endswith("2") for k in back["gear"])
    assert back["pinion"]["delta_a1"] == pytest.approx(math.degrees(blank.delta_a1), rel=1e-15)
    assert back["units"]["delta_a1"] == "deg" and back["units"]["Re2"] == "mm"
    assert back["warnings"] == []


def test_json_writes_null_for_the_crown_gear_virtual_diameter():
    bl = compute_blank(BlankInput(z1=20, z2=40, met=3.0, b=15.0, beta_m=R(30), rc0=60.0, shaft_angle=math.acos(-0.5)))
    j = dimension_sheet_json(bl)
    assert j["gear"]["dvn2"] is None
    json.dumps(j, allow_nan=False)


def test_text_sheet(blank):
    text = format_dimension_sheet(blank)
    line = next(li for li in text.splitlines() if li.startswith("delta_a "))
    assert "26.2403" in line and "72.3874" in line  # Sample 1 face angles 26.240 / 72.387 deg


def test_glossary_lists_every_quantity():
    text = GLOSSARY.read_text(encoding="utf-8")
    listed = set(re.findall(r"`([A-Za-z_0-9]+)`", text))
    missing = [n for n in attribute_names() if n not in listed]
    assert not missing, f"docs/glossary.md lacks {missing}"


def test_cli_blank_json_shows_the_iso_quantities(tmp_path):
    """`spiralbevel blank --json` carries the root diameters, h_t, t_zm, t_z and the thickness coefficients; the
    values equal the blank's (tzm = Rm·cos δ: crossing point to mean point, not the pitch apex)."""
    from typer.testing import CliRunner

    from spiralbevel.cli import app

    result = CliRunner().invoke(app, ["blank", "--json", "--output", str(tmp_path / "b.json")])
    assert result.exit_code == 0, result.output
    data = json.loads((tmp_path / "b.json").read_text())
    for key in ("dfe1", "dfi1", "ht1", "tzm1", "tz1", "be1", "bi1", "x_sm1"):
        assert key in data["pinion"] and key.replace("1", "2") in data["gear"], key
    assert "x_smn" in data["pair"]
    cos_d1 = math.cos(math.radians(data["pinion"]["delta1"]))
    assert data["pinion"]["tzm1"] == pytest.approx(data["pair"]["Rm"] * cos_d1, rel=1e-12)
    assert data["pinion"]["tz1"] == 0.0
    assert data["units"]["dfe1"] == "mm" and data["units"]["x_sm1"] == "-"
