"""'spiralbevel correct': a simulated CMM measurement of a flank cut with a radial-setting error is corrected, and
``--write`` gives the corrected design file."""

import re

import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.conventions import Member, Side
from spiralbevel.generation import generate_flank
from spiralbevel.io.design_file import load_design
from spiralbevel.io.measurement_csv import write_measurement_grid
from spiralbevel.job.blank import blank_from_design
from spiralbevel.job.facemilled import setup_flanks
from spiralbevel.manufacturing.measurement import measure_deviation, measurement_grid

runner = CliRunner()


def test_correct_rejects_logspiral(tmp_path):
    result = runner.invoke(app, ["correct", "aviation_23x65_logspiral", "--measured", str(tmp_path / "x.csv"),
                                 "--member", "gear", "--side", "convex"])
    assert result.exit_code == 2 and "face-milled" in result.output


def _example():
    from spiralbevel.io.design_file import bundled_designs

    return bundled_designs()["aviation_23x65_facemilled"]


def test_correct_recovers_a_radial_setting_error_and_writes_the_design(tmp_path):
    """``--write`` gives a design file that cuts the corrected flank with the corrected settings (read back through
    the ordinary design-file path) and the other flanks as before; a foreign file is never replaced."""
    from spiralbevel.manufacturing.correction import PARAMETERS

    spec = load_design(str(_example()))
    blank = blank_from_design(spec)
    setups = setup_flanks(spec, blank)
    st = setups[(Member.GEAR, Side.CONVEX)]
    grid = measurement_grid(st.flank)
    cut = generate_flank(st.cutter, st.settings.replace(radial_setting=st.settings.radial_setting + 0.05), blank,
                         Member.GEAR, Side.CONVEX)
    csv = tmp_path / "measured.csv"
    write_measurement_grid(csv, grid, measure_deviation(cut, grid))
    foreign = tmp_path / "mine.toml"
    foreign.write_text("# my notes\n")
    args = ["correct", str(_example()), "--measured", str(csv), "--member", "gear", "--side", "convex",
            "--parameters", "radial_setting,cradle_angle,machine_root_angle"]
    result = runner.invoke(app, [*args, "--write", str(foreign)])
    assert result.exit_code == 2 and "--write" in result.output
    assert foreign.read_text() == "# my notes\n"
    new = tmp_path / "corrected.toml"
    result = runner.invoke(app, [*args, "--write", str(new)])
    assert result.exit_code == 0, result.output
    line = next(ln for ln in result.output.splitlines() if "radial_setting" in ln)
    change = float(re.findall(r"[-+]\d+\.\d+", line)[-1])
    assert change == pytest.approx(-0.05, rel=0.02)        # corrected = nominal - identified error
    # every setting name the table prints is one --parameters accepts
    names = [ln.split("│")[1].strip() for ln in result.output.splitlines() if ln.count("│") >= 5]
    names = [n for n in names if n and n != "setting"]
    assert names and set(names) <= set(PARAMETERS), names
    spec2 = load_design(str(new))
    setups2 = setup_flanks(spec2, blank_from_design(spec2))
    got = setups2[(Member.GEAR, Side.CONVEX)].settings.radial_setting
    assert got - st.settings.radial_setting == pytest.approx(-0.05, rel=0.02)
    for key in setups:
        if key != (Member.GEAR, Side.CONVEX):
            assert setups2[key].settings.radial_setting == pytest.approx(setups[key].settings.radial_setting,
                                                                         rel=1e-12)
    again = runner.invoke(app, [*args, "--write", str(new)])        # a file correct --write wrote may be replaced
    assert again.exit_code == 0, again.output
