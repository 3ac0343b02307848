"""`spiralbevel machine` on a hypoid design (ISO 23509 Sample 2): the four flanks' settings, the pinion by hypoid local
synthesis with a blank offset; the commands that do not build hypoid flanks still stop (tests/design)."""

import re

from typer.testing import CliRunner

from spiralbevel.cli import app
from _hypoid_sample2 import SAMPLE2_TOML



def test_machine_prints_the_hypoid_settings(tmp_path):
    f = tmp_path / "hypoid.toml"
    f.write_text(SAMPLE2_TOML)
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
