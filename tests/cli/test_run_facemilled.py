"""End to end: the bundled face-milled design of seed 001 (Tables 1, 4, 5)."""

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.io.design_file import default_design_text

runner = CliRunner()
DESIGN = "aviation_23x65_facemilled.toml"


@pytest.fixture(scope="module")
def fm_run(tmp_path_factory):
    d = tmp_path_factory.mktemp("fm")
    f = d / "fm.toml"
    f.write_text(default_design_text(DESIGN).replace("grid = [31, 15]", "grid = [15, 9]"))
    out = d / "out"
    result = runner.invoke(app, ["run", str(f), "-o", str(out), "-q"])
    assert result.exit_code == 0, result.output
    return out, json.loads((out / "report.json").read_text())


def test_files(fm_run):
    out, report = fm_run
    assert {"report.json", "axial_section.png", "curvature_maps.png", "pinion_tooth.stl", "gear.stl",
            "pinion_tooth.step", "gear_tooth.step"} <= set(report["files"])


def test_seed001_gear_mean_point(fm_run):
    _, report = fm_run
    gear = report["flanks"]["gear"]["convex"]
    # seed 001 Table 1: 30 deg mean spiral angle, left-hand gear; Table 4 settings give it within 0.05 deg
    assert gear["spiral_angle_deg"] == pytest.approx(30.0, abs=0.05)
    assert gear["hand"] == "LH" and report["flanks"]["pinion"]["concave"]["hand"] == "RH"
    # the mean point lies at the mean cone distance A_m = 115.9511 mm on the pitch cone (seed 003 /
    # docs/theory/generation.md, Eqs. (G7)-(G9))
    p = np.array(gear["mean_point_mm"])
    assert np.linalg.norm(p) == pytest.approx(115.9511, abs=1e-3)
    assert math.degrees(math.atan2(math.hypot(p[0], p[1]), p[2])) == pytest.approx(70 + 30 / 60 + 49.9 / 3600,
                                                                                   abs=1e-3)
    for m in ("pinion", "gear"):
        for s in ("convex", "concave"):
            assert report["flanks"][m][s]["meshing_residual"] < 1e-10


def test_machine_settings_in_report(fm_run):
    _, report = fm_run
    ms = report["machine_settings"]
    gear = ms["gear"]["convex"]
    assert gear["source"] == "given"
    assert gear["settings"]["radial_setting_mm"] == 115.078
    assert gear["settings"]["cradle_angle_deg"] == pytest.approx(59 + 20 / 60 + 7 / 3600)
    derived = ms["gear"]["concave"]
    assert derived["source"].startswith("basic settings solved")
    # the solved coast flanks hit the design; the paper's given drive flanks are reported as they come out
    fl = report["flanks"]
    for m, s in (("gear", "concave"), ("pinion", "convex")):
        d = fl[m][s]["design_vs_achieved"]
        assert d["pressure_angle_deg"] == pytest.approx(22.5, abs=1e-5)  # Newton tolerance 1e-7 rad = 6e-6 deg
        assert d["spiral_angle_deg"] == pytest.approx(30.0, abs=1e-5)
        # the pressure angle again from the reported mean point and normal: asin|n . N| with N the pitch-cone normal
        p, n = np.array(fl[m][s]["mean_point_mm"]), np.array(fl[m][s]["mean_normal"])
        delta = math.radians(70 + 30 / 60 + 49.9 / 3600) if m == "gear" else math.radians(90 - (70 + 30 / 60
                                                                                               + 49.9 / 3600))
        rho = np.array([p[0], p[1], 0.0]) / math.hypot(p[0], p[1])
        N = math.cos(delta) * rho - math.sin(delta) * np.array([0.0, 0.0, 1.0])
        assert math.degrees(math.asin(abs(n @ N))) == pytest.approx(22.5, abs=2e-3)  # delta printed to 0.1"
    # Table 5's 22 deg 30' blade with Table 5's settings: 22.75 deg, 0.12 deg from the given gear's 22.63 deg (the
    # mean-point tangency of a synthesized pair; tests/machine/test_seed001_reading.py)
    given = fl["pinion"]["concave"]["design_vs_achieved"]
    gear_given = fl["gear"]["convex"]["design_vs_achieved"]
    assert abs(given["pressure_angle_deg"] - gear_given["pressure_angle_deg"]) < 0.15


def test_machine_command_prints_summary():
    from importlib import resources

    path = resources.files("spiralbevel.data").joinpath(DESIGN)
    result = runner.invoke(app, ["machine", str(path)])
    assert result.exit_code == 0, result.output
    assert "Radial setting" in result.output and "91.1160" in result.output


def test_machine_command_rejects_logspiral():
    """A log-spiral design named explicitly is refused (it has no machine settings); with no design the command
    summarizes the face-milled example instead (tests/cli/test_cli_polish.py)."""
    result = runner.invoke(app, ["machine", "aviation_23x65_logspiral"])
    assert result.exit_code == 2 and "flank.kind" in result.output


def test_bad_given_settings_named_by_design_file_path(tmp_path):
    text = default_design_text(DESIGN).replace("radial_setting = 115.078", "radial_setting = 400.0")
    f = tmp_path / "bad.toml"
    f.write_text(text)
    result = runner.invoke(app, ["run", str(f), "-o", str(tmp_path / "out"), "-q"])
    assert result.exit_code == 2
    assert "face_milling.gear_convex.machine.radial_setting = 400.0 mm" in result.output
    assert "Traceback" not in result.output and not (tmp_path / "out").exists()


def test_tca_checks_flag_the_given_drive_pair(fm_run):
    """The given drive side (Tables 4 and 5) runs its bearing to the pinion's edge: the check says so at exactly the
    positions the TCA marks without a real-flank contact or in edge contact, and names the given settings."""
    _, report = fm_run
    for name in ("drive", "coast"):
        t = report["tca"][name]
        off = len(t["edge_contact_positions_deg"]) + len(t["no_contact_positions_deg"])
        bearing = [c for c in t["checks"] if "bearing runs off the flank" in c]
        assert len(bearing) == (1 if off else 0), name
        if off:
            assert f"at {off} of {t['positions']} TCA positions" in bearing[0]
    drive = [c for c in report["tca"]["drive"]["checks"] if "bearing" in c]
    assert drive and "face_milling.pinion_concave" in drive[0]
