"""'spiralbevel correct' on a hypoid design (ISO 23509 Sample 2, drive pinion by hypoid local synthesis with a
blank offset): a simulated CMM measurement of the synthesized pinion flank cut with known setting errors is
corrected through the universal generator's settings, and ``--write`` gives a design file that cuts the corrected
flank (read back through the ordinary hypoid design-file path)."""

import math
import re
import sys
import warnings
from pathlib import Path

import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.conventions import Member, Side
from spiralbevel.design.hypoid_member import member_blank
from spiralbevel.generation import generate_flank
from spiralbevel.io.design_file import load_design
from spiralbevel.io.measurement_csv import write_measurement_grid
from spiralbevel.job.blank import blank_from_design
from spiralbevel.job.correction import flank_setups
from spiralbevel.manufacturing.correction import apply_changes
from spiralbevel.manufacturing.measurement import measure_deviation, measurement_grid

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _hypoid_sample2 import SAMPLE2_TOML, SEED001_SYNTHESIS  # noqa: E402

#: the synthesis is given (one path direction, drive side only) so that the test does not run the default search
DESIGN = SAMPLE2_TOML + '[synthesis]\nsides = ["drive"]\npath_direction = 40\n' + SEED001_SYNTHESIS
TRUE = {"radial_setting": 0.05, "cradle_angle": math.radians(0.01), "blank_offset": -0.03}
KEY = (Member.PINION, Side.CONCAVE)


def test_correct_recovers_hypoid_pinion_setting_errors_and_writes_the_design(tmp_path):
    design = tmp_path / "hypoid.toml"
    design.write_text(DESIGN)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")      # Sample 2's own face width warning
        spec = load_design(str(design))
        blank = blank_from_design(spec)
        setups, _ = flank_setups(spec, blank)
    st = setups[KEY]
    assert st.settings.blank_offset != 0.0 and "hypoid local synthesis" in st.source
    grid = measurement_grid(st.flank)
    cut = generate_flank(*apply_changes(st.cutter, st.settings, TRUE), member_blank(blank, Member.PINION), *KEY)
    csv = tmp_path / "measured.csv"
    write_measurement_grid(csv, grid, measure_deviation(cut, grid))
    new = tmp_path / "corrected.toml"
    res = CliRunner().invoke(app, ["correct", str(design), "--measured", str(csv), "--member", "pinion", "--side",
                                   "concave", "--parameters", ",".join(TRUE), "--write", str(new)])
    assert res.exit_code == 0, res.output
    changes = {}
    for line in res.output.splitlines():
        for name in TRUE:
            if f" {name} " in line:
                changes[name] = float(re.findall(r"[-+]\d+\.\d+", line)[-1])
    # corrected = nominal - identified error, recovered to the table's six printed decimals (the measured rms falls
    # from 6.62 um to 0.00 um: the Gauss-Newton steps after the linear one converge on this exact measurement)
    printed = 1e-6
    assert changes["radial_setting"] == pytest.approx(-TRUE["radial_setting"], abs=printed)
    assert changes["cradle_angle"] == pytest.approx(-math.degrees(TRUE["cradle_angle"]), abs=printed)
    assert changes["blank_offset"] == pytest.approx(-TRUE["blank_offset"], abs=printed)
    # the written design cuts the corrected pinion flank, and every other flank as before
    spec2 = load_design(str(new))
    setups2, _ = flank_setups(spec2, blank_from_design(spec2))
    got = setups2[KEY].settings
    assert got.blank_offset - st.settings.blank_offset == pytest.approx(-TRUE["blank_offset"], abs=printed)
    assert got.radial_setting - st.settings.radial_setting == pytest.approx(-TRUE["radial_setting"], abs=printed)
    for key in setups:
        if key != KEY:
            assert setups2[key].settings.radial_setting == pytest.approx(setups[key].settings.radial_setting,
                                                                         rel=1e-12)
