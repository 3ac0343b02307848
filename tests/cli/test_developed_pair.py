"""A face-milled design from basic data alone is developed: basic settings hit the design, the pinion is synthesized
against the gear on both sides by default, and the TCA shows the default parabolic TE level."""

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.job.facemilled import DEFAULT_SYNTHESIS
from _design_12x41 import design_12x41

runner = CliRunner()

OUTPUT = """[output]
grid = [9, 5]
plots = false
stl = false
"""


@pytest.fixture(scope="module", params=[(90, "RH"), (75, "LH")], ids=["S90-RH", "S75-LH"])
def report(request, tmp_path_factory):
    d = tmp_path_factory.mktemp("dev")
    f = d / "d.toml"
    f.write_text(design_12x41(shaft_angle=request.param[0], hand=request.param[1], title="12/41 basic data") + OUTPUT)
    result = runner.invoke(app, ["run", str(f), "-o", str(d / "out"), "-q"])
    assert result.exit_code == 0, result.output
    return json.loads((d / "out" / "report.json").read_text())


def test_all_four_flanks_hit_the_design(report):
    for m in ("pinion", "gear"):
        for s in ("convex", "concave"):
            d = report["flanks"][m][s]
            # the pinion flanks come from local synthesis; they keep the design angles at the mean point because the
            # synthesis prescribes the gear's point, normal and curvatures there (0.05 deg acceptance)
            assert d["pressure_angle_deg"] == pytest.approx(20.0, abs=0.05)
            assert d["spiral_angle_deg"] == pytest.approx(35.0, abs=0.05)
    assert set(report["synthesis"]) == {"drive", "coast"}
    for m in ("pinion", "gear"):
        for s in ("convex", "concave"):   # no developed-pair warning: angles, root, undercut at the achieved angles
            assert report["flanks"][m][s]["checks"] == [], (m, s)


def test_default_pair_te_level(report):
    """The parabolic TE level again, from the TCA alone: a least-squares parabola through the TE of the pair in
    contact within 0.4 of half a mesh cycle around the mean contact, evaluated at half a mesh cycle."""
    z1 = 12
    half = math.pi / z1
    for name in ("drive", "coast"):
        t = report["tca"][name]
        phi, te = np.radians(t["pinion_rotation_deg"]), np.array(t["transmission_error_arcsec"])
        near = np.abs(phi) <= 0.4 * half
        a2, a1, a0 = np.polyfit(phi[near], te[near], 2)
        level = -a2 * half**2
        # +-10 % acceptance: the synthesis fixes the second derivative at the mean point; third-order terms of the
        # real flanks bend the curve away from the parabola by a few percent over the fitted window
        assert level == pytest.approx(DEFAULT_SYNTHESIS["te_magnitude"], rel=0.10), (name, level)
        # the job's TE-level check fits the same parabola and stays silent within the 10 % acceptance
        assert not [c for c in t["checks"] if "TE level" in c], name


def test_bearing_check_agrees_with_the_contact_status(report):
    """The bearing check of the report warns exactly when the TCA status has a position off the flank (S90-RH: none;
    S75-LH: the known pinion-edge contact at the end of the drive cycle), and then names the synthesis keys."""
    for name in ("drive", "coast"):
        t = report["tca"][name]
        off = len(t["edge_contact_positions_deg"]) + (t["positions"] - t["contact_positions"])
        bearing = [c for c in t["checks"] if "bearing runs off the flank" in c]
        assert len(bearing) == (1 if off else 0), (name, t["checks"])
        if off:
            assert "synthesis.path_direction" in bearing[0]


def test_default_bearing_inside_the_flank(report):
    """The TCA's physical-contact status at every position of the mesh cycle: a real-flank contact (no position without
    contact) and no edge contact (the contact point inside the pinion and gear flank boundaries) on both sides."""
    for name in ("drive", "coast"):
        t = report["tca"][name]
        assert t["status"] == "ok", (name, t["edge_contacts"])
        assert t["contact_positions"] == t["positions"], (name, t["no_contact_positions_deg"])
        assert not t["edge_contact_positions_deg"], name
