"""A measured CSV must belong to the nominal grid: header, coordinates and normals, not only the labels.

Reproducer: the pinion-concave grid given as gear-convex data was accepted (labels match) and 'corrected'
(rms 1.00 -> 0.00 um)."""

import numpy as np
import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.conventions import Member, Side
from spiralbevel.errors import DesignError
from spiralbevel.io.design_file import bundled_designs, load_design
from spiralbevel.io.measurement_csv import (NORMAL_TOL_DEG, POINT_TOL, measurement_grid_csv, read_measured_deviation)
from spiralbevel.job.blank import blank_from_design
from spiralbevel.job.facemilled import setup_flanks
from spiralbevel.manufacturing.measurement import measurement_grid


@pytest.fixture(scope="module")
def grids():
    spec = load_design(bundled_designs()["aviation_23x65_facemilled"])
    setups = setup_flanks(spec, blank_from_design(spec))
    return {k: measurement_grid(setups[k].flank) for k in ((Member.GEAR, Side.CONVEX), (Member.PINION, Side.CONCAVE))}


def _strip_comments(text):
    return "\n".join(ln for ln in text.splitlines() if not ln.startswith("#")) + "\n"


def test_grid_of_another_flank_is_refused_by_the_cli(tmp_path, grids):
    pc = grids[(Member.PINION, Side.CONCAVE)]
    csv = tmp_path / "m.csv"
    csv.write_text(measurement_grid_csv(pc, np.full(pc.shape, 0.001)))
    res = CliRunner().invoke(app, ["correct", "aviation_23x65_facemilled", "--measured", str(csv), "--member", "gear",
                                   "--side", "convex"])
    assert res.exit_code == 2, res.output
    assert "pinion concave flank" in res.output and "Traceback" not in res.output


def test_coordinates_checked_without_the_header(tmp_path, grids):
    gc, pc = grids[(Member.GEAR, Side.CONVEX)], grids[(Member.PINION, Side.CONCAVE)]
    csv = tmp_path / "m.csv"
    csv.write_text(_strip_comments(measurement_grid_csv(pc, np.zeros(pc.shape))))
    with pytest.raises(DesignError, match="x_mm, y_mm, z_mm of F1P1"):
        read_measured_deviation(csv, gc)


def test_normals_and_small_offsets(tmp_path, grids):
    gc = grids[(Member.GEAR, Side.CONVEX)]
    dev = np.random.default_rng(1).normal(scale=0.01, size=gc.shape)
    text = measurement_grid_csv(gc, dev)
    csv = tmp_path / "m.csv"
    csv.write_text(text)
    assert np.allclose(read_measured_deviation(csv, gc), dev, atol=1e-9)
    # a probed point that lies off the nominal point by the deviation (well inside the tolerance) is the same point
    moved = type(gc)(**{**gc.__dict__, "points": gc.points + 0.5 * POINT_TOL * gc.normals})
    csv.write_text(measurement_grid_csv(moved, dev))
    assert np.allclose(read_measured_deviation(csv, gc), dev, atol=1e-9)
    # flipped normals (the mating flank's convention) are not this grid's
    flipped = type(gc)(**{**gc.__dict__, "normals": -gc.normals})
    csv.write_text(_strip_comments(measurement_grid_csv(flipped, dev)))
    with pytest.raises(DesignError, match=f"within {NORMAL_TOL_DEG} deg"):
        read_measured_deviation(csv, gc)


@pytest.mark.parametrize("payload", ["label,deviation_mm\n" + "x" * 200_000 + ",1\n",
                                     "label,deviation_mm\nF1P1,1\n".encode("utf-16"), b"\x00\x01\x02"])
def test_malformed_files_are_clean_errors(tmp_path, grids, payload):
    csv = tmp_path / "m.csv"
    (csv.write_bytes if isinstance(payload, bytes) else csv.write_text)(payload)
    with pytest.raises(DesignError):
        read_measured_deviation(csv, grids[(Member.GEAR, Side.CONVEX)])
