"""End to end: the main job on the bundled default design, and its failure modes."""

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.io.design_file import default_design_text

runner = CliRunner()
_CONSOLE: dict = {}


@pytest.fixture(scope="module")
def default_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("run") / "out"
    result = runner.invoke(app, ["run", "-o", str(out), "-q"])
    assert result.exit_code == 0, result.output
    _CONSOLE["output"] = result.output
    return out, json.loads((out / "report.json").read_text())


def test_summary_names_a_failing_draft(default_run):
    """The default log-spiral pair's pinion convex flank cannot leave an axial die: the console summary says so and
    names every failing flank of report.json's draft section."""
    _, report = default_run
    failing = [k for k, v in report["draft"]["flanks"].items() if not v["passes"]]
    assert "pinion_convex" in failing
    line = next(ln for ln in _CONSOLE["output"].splitlines() if "forging draft" in ln)
    assert "FAILS" in line and all(k.replace("_", " ") in line for k in failing)


def test_default_run_writes_everything(default_run):
    out, report = default_run
    names = set(report["files"])
    assert {"report.json", "curvature_maps.png", "curvature_domain.png", "pitch_traces.png", "meshing_pair_3d.png",
            "transverse_section.png", "draft_map.png",
            "pinion_tooth.stl", "gear_tooth.stl", "pinion.stl", "gear.stl"} <= names
    assert sum(n.startswith("toolpath_") and n.endswith(".csv") for n in names) == 4
    for n in names:
        assert (out / n).stat().st_size > 0


def test_report_blank_matches_seed001(default_run):
    _, report = default_run
    blank = report["blank"]
    # seed 001 Table 1 (docs/theory/example.md): pitch angles 19°29'10.1", mean cone distance 115.9511 mm
    assert blank["pinion"]["delta1_deg"] == pytest.approx(19 + 29 / 60 + 10.1 / 3600, abs=1e-4)
    assert blank["pair"]["Rm_mm"] == pytest.approx(115.9511, abs=1e-4)


def test_report_logspiral_recipe_independent_check(default_run):
    _, report = default_run
    ls = report["logspiral"]
    # docs/theory/logspiral.md, Eq. (S12), recomputed here: tan a_t = tan a_n / cos b_m, sin d_i = sin g_i cos a_t
    a_n, b_m = math.radians(20), math.radians(30)
    a_t = math.atan(math.tan(a_n) / math.cos(b_m))
    g1 = math.atan2(23, 65)
    assert ls["transverse_pressure_angle_deg"] == pytest.approx(math.degrees(a_t), abs=1e-9)
    assert ls["members"]["pinion"]["base_cone_angle_deg"] == pytest.approx(
        math.degrees(math.asin(math.sin(g1) * math.cos(a_t))), abs=1e-9)
    assert ls["plane_spiral_angle_deg"] == pytest.approx(math.degrees(math.asin(math.cos(a_n) * math.sin(b_m))),
                                                          abs=1e-9)
    # convex flanks have positive curvatures (docs/conventions.md)
    for m in ("pinion", "gear"):
        conv = ls["members"][m]["flanks"]["convex"]
        assert conv["k1_range_per_mm"][0] > 0 and conv["k2_range_per_mm"][0] > 0
        n = np.array(conv["mean_point"]["normal"])
        assert np.linalg.norm(n) == pytest.approx(1.0, abs=1e-12)


def test_logspiral_pair_tca_line_contact_zero_te(default_run):
    # issue 2/5: the same TCA engine on the exact log-spiral pair shows line contact and zero TE
    _, report = default_run
    for side in ("convex-concave", "concave-convex"):
        t = report["logspiral"]["tca"][side]
        assert t["line_contact_positions"] == t["positions"]
        assert t["max_abs_transmission_error_arcsec"] < 1e-6
        assert report["logspiral"]["conjugacy"][side.split("-")[0]]["max_distance_mm"] < 1e-9


def test_stl_is_readable_and_closed(default_run):
    from spiralbevel.io.stl import read_stl

    out, _ = default_run
    mesh = read_stl(out / "pinion_tooth.stl")
    assert mesh.volume() > 0


def test_failed_run_leaves_previous_output_untouched(tmp_path):
    # a pinion dedendum angle of 3 deg puts its root cone (16.5 deg) inside its base cone (17.9 deg): the log-spiral
    # flank would cross the singular edge psi = 0, which must be reported, with no output written
    bad = default_design_text().replace('dedendum_angles = ["1°05\'50\\"", "2°29\'20\\""]',
                                        'dedendum_angles = ["3°", "2°29\'20\\""]')
    assert bad != default_design_text()
    f = tmp_path / "d.toml"
    f.write_text(bad)
    out = tmp_path / "out"
    out.mkdir()
    (out / "marker.txt").write_text("previous run")
    # a previous spiralbevel output (its manifest lists the files it wrote)
    (out / ".spiralbevel-output.json").write_text('{"files": ["marker.txt"]}')
    result = runner.invoke(app, ["run", str(f), "-o", str(out), "-q"])
    assert result.exit_code == 2, result.output
    assert "base cone" in result.output and "Traceback" not in result.output
    assert sorted(p.name for p in out.iterdir()) == [".spiralbevel-output.json", "marker.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.toml", "out"]


def test_blank_command_table_and_json(tmp_path):
    result = runner.invoke(app, ["blank"])
    assert result.exit_code == 0 and "pitch angle" in result.output
    result = runner.invoke(app, ["blank", "--json", "--output", str(tmp_path / "b.json")])
    assert result.exit_code == 0
    data = json.loads((tmp_path / "b.json").read_text())
    assert data["gear"]["delta2"] == pytest.approx(70 + 30 / 60 + 49.9 / 3600, abs=1e-4)
