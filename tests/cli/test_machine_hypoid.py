"""`spiralbevel machine` on a hypoid design (ISO 23509 Sample 2): the four flanks' settings, the pinion by hypoid local
synthesis with a blank offset; the commands that do not build hypoid flanks still stop (tests/design)."""

import re

from typer.testing import CliRunner

from spiralbevel.cli import app

TOML = """title = "Sample 2 hypoid"
[gear_set]
pinion_teeth = 13
gear_teeth = 42
outer_pitch_diameter = 170.0
face_width = 30.0
mean_spiral_angle = 50
pinion_hand = "LH"
cutter_radius = 63.5
hypoid_offset = 15.0
limit_pressure_angle_factor = 1.0
[gear_set.depth]
taper = "given"
gear_addendum_dedendum_angles = [1.0, 4.0]
mean_addendum_factor = 0.35
thickness_factor = 0.1
[flank]
kind = "face-milled"
"""


def test_machine_prints_the_hypoid_settings(tmp_path):
    f = tmp_path / "hypoid.toml"
    f.write_text(TOML)
    res = CliRunner().invoke(app, ["machine", str(f)])
    assert res.exit_code == 0, res.output
    text = " ".join(res.output.split())
    assert text.count("hypoid local synthesis") == 2 and text.count("hypoid basic settings") == 2
    # the drive side's default path keeps the bearing inside the flanks (no note of positions off the flanks)
    drive = text[text.index("(drive side"):]
    assert "off the flanks" not in drive[:drive.index(")")]
    offsets = [float(v) for v in re.findall(r"Blank offset E_m │ (-?[0-9.]+)", text)]
    assert len(offsets) == 4 and sum(abs(v) > 1.0 for v in offsets) == 2    # the two synthesized pinion flanks
    assert "Traceback" not in res.output
