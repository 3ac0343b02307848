"""'spiralbevel correct': a simulated CMM measurement of a flank cut with a radial-setting error is corrected."""

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


def test_correct_recovers_a_radial_setting_error(tmp_path):
    spec = load_design(str(_example()))
    blank = blank_from_design(spec)
    st = setup_flanks(spec, blank)[(Member.GEAR, Side.CONVEX)]
    grid = measurement_grid(st.flank)
    # the "machine" cut the gear with S_r + 0.05 mm: an independent flank, measured on the nominal grid
    cut = generate_flank(st.cutter, st.settings.replace(radial_setting=st.settings.radial_setting + 0.05), blank,
                         Member.GEAR, Side.CONVEX)
    dev = measure_deviation(cut, grid)
    assert abs(dev).max() > 1e-3
    csv = tmp_path / "measured.csv"
    write_measurement_grid(csv, grid, dev)
    result = runner.invoke(app, ["correct", str(_example()), "--measured", str(csv), "--member", "gear",
                                 "--side", "convex", "--parameters", "radial_setting,cradle_angle,machine_root_angle"])
    assert result.exit_code == 0, result.output
    line = next(ln for ln in result.output.splitlines() if "radial_setting" in ln)
    change = float(re.findall(r"[-+]\d+\.\d+", line)[-1])
    assert change == pytest.approx(-0.05, rel=0.02)        # corrected = nominal - identified error


def test_correct_rejects_logspiral(tmp_path):
    result = runner.invoke(app, ["correct", "aviation_23x65_logspiral", "--measured", str(tmp_path / "x.csv"),
                                 "--member", "gear", "--side", "convex"])
    assert result.exit_code == 2 and "face-milled" in result.output


def _example():
    from spiralbevel.io.design_file import bundled_designs

    return bundled_designs()["aviation_23x65_facemilled"]
