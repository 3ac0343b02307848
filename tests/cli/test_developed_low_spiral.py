"""A low-spiral-angle design (beta 8.1 deg) from basic data is developed: its gear convex flank folds in the (u, psi_c)
chart inside the face (tests/generation/test_fold.py), which stopped the flank grid before the (phi, psi_c) chart of
the blade; now all four flanks hit the design, the default pinion bearing stays inside both flanks on both sides and
the TE has the default parabolic level."""

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.job.facemilled import DEFAULT_SYNTHESIS

runner = CliRunner()

# the design of tests/generation/test_fold.py (a design of the robustness bench, seed 1), with report options
DESIGN = """
title = "11/41 beta 8.1 deg"
[gear_set]
pinion_teeth = 11
gear_teeth = 41
shaft_angle = 76.6
module = 11.67
face_width = 61.2
normal_pressure_angle = 20
mean_spiral_angle = 8.1
pinion_hand = "RH"
cutter_radius = 235
[flank]
kind = "face-milled"
[output]
grid = [9, 5]
plots = false
stl = false
"""


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    d = tmp_path_factory.mktemp("low")
    f = d / "d.toml"
    f.write_text(DESIGN)
    result = runner.invoke(app, ["run", str(f), "-o", str(d / "out"), "-q"])
    assert result.exit_code == 0, result.output
    return json.loads((d / "out" / "report.json").read_text())


def test_all_four_flanks_hit_the_design(report):
    for m in ("pinion", "gear"):
        for s in ("convex", "concave"):
            d = report["flanks"][m][s]
            assert d["pressure_angle_deg"] == pytest.approx(20.0, abs=0.05), (m, s)   # acceptance of issue 11
            assert d["spiral_angle_deg"] == pytest.approx(8.1, abs=0.05), (m, s)
    assert set(report["synthesis"]) == {"drive", "coast"}


def test_bearing_inside_the_flank_at_the_design_te_level(report):
    half = math.pi / 11
    for name in ("drive", "coast"):
        t = report["tca"][name]
        assert t["status"] == "ok", (name, t["edge_contacts"])
        assert t["contact_positions"] == t["positions"], (name, t["no_contact_positions_deg"])
        assert not t["edge_contact_positions_deg"], name
        # least-squares parabola through the TE within 0.4 of half a mesh cycle, at half a mesh cycle (as
        # tests/cli/test_developed_pair.py): the synthesis fixes the second derivative at the mean point, +-10 %
        phi, te = np.radians(t["pinion_rotation_deg"]), np.array(t["transmission_error_arcsec"])
        near = np.abs(phi) <= 0.4 * half
        level = -np.polyfit(phi[near], te[near], 2)[0] * half**2
        assert level == pytest.approx(DEFAULT_SYNTHESIS["te_magnitude"], rel=0.10), (name, level)
