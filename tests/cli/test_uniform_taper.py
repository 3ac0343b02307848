"""A log-spiral design with a parallel-depth blank (taper = "uniform") is refused with a readable message that names
the key to change (the allowed range once read "< 180tch angle": "pi" was replaced inside "pitch"; then it came as two
problems per member under an internal name, "gear_set.depth -> pinion blank.root_angle")."""

from typer.testing import CliRunner

from spiralbevel.cli import app

DESIGN = """
[gear_set]
pinion_teeth = 12
gear_teeth = 41
shaft_angle = 90
module = 5
face_width = 30
normal_pressure_angle = 22.5
mean_spiral_angle = 35
pinion_hand = "RH"
[gear_set.depth]
taper = "uniform"
[flank]
kind = "log-spiral"
"""


def test_uniform_taper_log_spiral_message(tmp_path):
    f = tmp_path / "d.toml"
    f.write_text(DESIGN)
    result = CliRunner().invoke(app, ["run", str(f), "-o", str(tmp_path / "out"), "-q"])
    assert result.exit_code != 0
    text = " ".join(result.output.split())
    assert "180tch" not in text
    # one problem, on the key to change (not one per cone of each member under an internal name)
    assert "1 problem(s) in the input" in text and "gear_set.depth.taper = 'uniform'" in text
    assert "blank." not in text and "->" not in text
    assert "gear_set.depth.taper = 'standard'" in text and "flank.kind = 'face-milled'" in text
    assert "Traceback" not in text
