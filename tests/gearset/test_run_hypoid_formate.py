"""`spiralbevel run iso23509_sample2_hypoid_formate`: ISO 23509 Annex F Sample 2 with a Formate (non-generated) gear,
developed into a pair by the default synthesis, end to end through the CLI.

The gear flanks are the cutter surface (no roll) with the design mean-point angles; the pinion is generated and
fitted to them by the hypoid local synthesis (Formate defaults: modified roll, a shorter contact ellipse). The design
values are the ISO 23509 Method 1 dimension sheet; the TE level is a least-squares parabola fitted here to the report's
TE curve near the mean contact (the same definition as ``tca_checks.te_level``, recomputed from the report)."""

import json
import math
import warnings

import numpy as np
import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app

#: the acceptance bound of the hypoid issue on the achieved mean-point angles (the solves reach ~1e-9 deg)
ANGLE_TOL_DEG = 0.05
#: the acceptance bound on the TE level (the fitted parabola departs from the local synthesis' second-order
#: prediction by the higher-order terms: measured -3.5 % drive, -0.7 % coast)
TE_REL_TOL = 0.10
DESIGN_TE_ARCSEC = 8.0          # the default synthesis' te_magnitude


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("hypf") / "out"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = CliRunner().invoke(app, ["run", "iso23509_sample2_hypoid_formate", "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert "Traceback" not in res.output and (out / "report.html").is_file()
    return json.loads((out / "report.json").read_text())


def test_report_matches_the_schema(report):
    jsonschema = pytest.importorskip("jsonschema")
    from spiralbevel.io.report import report_schema

    jsonschema.validate(report, report_schema(), cls=jsonschema.Draft202012Validator)
    assert report["failed_analyses"] == []


def test_formate_gear_and_achieved_angles(report):
    b = report["blank"]
    beta = {"pinion": b["pinion"]["beta_m1_deg"], "gear": b["gear"]["beta_m2_deg"]}
    alpha = {("pinion", "concave"): b["pair"]["alpha_nD_deg"], ("gear", "convex"): b["pair"]["alpha_nD_deg"],
             ("pinion", "convex"): b["pair"]["alpha_nC_deg"], ("gear", "concave"): b["pair"]["alpha_nC_deg"]}
    for (m, s), a in alpha.items():
        f = report["flanks"][m][s]
        assert f["spiral_angle_deg"] == pytest.approx(beta[m], abs=ANGLE_TOL_DEG), (m, s)
        assert f["pressure_angle_deg"] == pytest.approx(a, abs=ANGLE_TOL_DEG), (m, s)
    for s in ("convex", "concave"):
        gear = report["machine_settings"]["gear"][s]
        assert gear["settings"]["generated"] is False and "Formate" in gear["source"]
        assert report["flanks"]["gear"][s]["k1_per_mm"] == 0.0     # straight blade: a straight profile, no roll
        assert ["Process", "Formate (non-generated)", ""] in gear["summary"]
        pin = report["machine_settings"]["pinion"][s]
        assert "hypoid local synthesis" in pin["source"] and "modified-roll" in pin["source"]


def _te_level(t, z1):
    """Least-squares parabola through the TE within 0.4 of half a mesh cycle of the mean contact, as its drop over
    half a mesh cycle (arcsec)."""
    phi = np.radians(np.asarray(t["pinion_rotation_deg"], float))
    te = np.asarray(t["transmission_error_arcsec"], float)
    phi = phi - phi[len(phi) // 2]
    half = math.pi / z1
    near = np.isfinite(te) & (np.abs(phi) <= 0.4 * half)
    return -np.polyfit(phi[near], te[near], 2)[0] * half ** 2


def test_tca_at_the_design_te_level_with_the_bearing_inside_the_flanks(report):
    z1 = report["blank"]["pinion"]["z1"]
    for side in ("drive", "coast"):
        t = report["tca"][side]
        assert t["status"] == "ok" and t["contact_positions"] == t["positions"], side   # no edge, no gap
        assert t["edge_contacts"] == [] and t["checks"] == [], side
        assert _te_level(t, z1) == pytest.approx(DESIGN_TE_ARCSEC, rel=TE_REL_TOL), side
        # peak to peak (measured 4.76 drive, 8.86 coast): the drive contact passes to the next pair before the
        # parabola has dropped by the full level, the coast parabola is not quite symmetric about the mean contact
        assert 0 < t["peak_to_peak_arcsec"] < 2 * DESIGN_TE_ARCSEC, side


def _design(**changes):
    from spiralbevel.io.design_file import bundled_designs

    text = bundled_designs()["iso23509_sample2_hypoid_formate"].read_text()
    for old, new in changes.items():
        assert old in text
        text = text.replace(old, new)
    return text


@pytest.mark.parametrize("old, new, key", [
    ("hypoid_offset = 15.0", "hypoid_offset = 0.0", "gear_set.gear_generation"),       # Formate needs an offset
    ('kind = "face-milled"', 'kind = "log-spiral"', "gear_set.gear_generation"),        # and face milling
    ('[flank]\nkind = "face-milled"', '[flank]\nkind = "face-milled"\n[face_milling.gear_convex.cutter]\n'
     'point_radius = 60.0\nblade_angle = 20.0\npoint_width = 1.5\nedge_radius = 0.5',
     "face_milling.gear_convex.cutter"),                                              # its cutter is solved
])
def test_invalid_formate_combinations_name_the_key(tmp_path, old, new, key):
    from spiralbevel.errors import DesignError
    from spiralbevel.gearset.gearset import GearSet

    path = tmp_path / "formate.toml"
    path.write_text(_design(**{old: new}))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(DesignError) as err:
            gs = GearSet.from_design(path)
            _ = gs.setups                  # the flanks are built on first use
    assert key in str(err.value) and "formate" in str(err.value).lower()


def test_blank_input_refuses_a_formate_gear_without_offset():
    from spiralbevel.design.blank_input import BlankInput
    from spiralbevel.errors import DesignError

    with pytest.raises(DesignError, match="gear_generated"):
        BlankInput(z1=13, z2=42, b=30.0, beta_m=math.radians(35.0), rc0=63.5, de2=170.0, gear_generated=False)
    with pytest.raises(DesignError, match="gear_generated"):
        BlankInput(z1=13, z2=42, b=30.0, beta_m=math.radians(35.0), rc0=63.5, de2=170.0, a=15.0,
                   gear_generated="formate")
