"""Misalignment sweeps: sequential and dask give the same records; directions of the contact shift."""

import json

import numpy as np

import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.io.design_file import bundled_designs, load_design
from spiralbevel.job.sweep import misalignment_sweep

runner = CliRunner()


@pytest.fixture(scope="module")
def spec():
    return load_design(bundled_designs()["aviation_23x65_synthesized"])


def test_gear_axial_moves_the_pattern_along_the_face(spec):
    recs = misalignment_sweep(spec, {"gear_axial": [-0.05, 0.0, 0.05]}, scheduler="sequential")
    R = [r["mean_contact_R_mm"] for r in recs]
    # gear out of mesh along +a2 (docs/conventions.md, Misalignments): the contact moves monotonically along the face
    assert (R[0] - R[1]) * (R[2] - R[1]) < 0 and abs(R[2] - R[0]) > 0.05
    assert all(r["peak_to_peak_arcsec"] > 0 for r in recs)


def test_dask_matches_sequential(spec):
    pytest.importorskip("dask")
    grid = {"pinion_axial": [-0.03, 0.03], "shaft_angle": [0.0, 0.02]}
    assert misalignment_sweep(spec, grid) == misalignment_sweep(spec, grid, scheduler="sequential")


def test_distributed_client_matches_sequential(spec):
    distributed = pytest.importorskip("distributed")
    grid = {"offset": [-0.02, 0.02]}
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as c:
        recs = misalignment_sweep(spec, grid, scheduler=c.scheduler_address)
    assert recs == misalignment_sweep(spec, grid, scheduler="sequential")


def test_multiprocess_cluster_over_tcp_matches_sequential(spec):
    """A multi-machine run in miniature: a scheduler and two worker processes on the loopback interface, reached by
    its tcp:// address as ``--scheduler`` gives it; the batches come back in grid order."""
    distributed = pytest.importorskip("distributed")
    grid = {"pinion_axial": [-0.03, 0.0, 0.03], "offset": [0.0, 0.02]}
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as c:
        assert c.scheduler_address.startswith("tcp://127.0.0.1:")
        recs = misalignment_sweep(spec, grid, scheduler=c.scheduler_address)
    assert recs == misalignment_sweep(spec, grid, scheduler="sequential")


def test_batches_cover_the_grid_and_merge_back_in_order():
    from spiralbevel.job.sweep import BATCHES_PER_WORKER, MIN_BATCH, _batches, _merge

    for n_points in (1, 7, 23, 200, 1000):
        pts = list(range(n_points))
        for workers in (1, 2, 7, 50):
            b = _batches(pts, workers)
            assert sorted(p for part in b for p in part) == pts      # every point once
            assert _merge(b) == pts                                   # and back in grid order
            assert len(b) == max(1, min(n_points, BATCHES_PER_WORKER * workers, -(-n_points // MIN_BATCH)))
            assert max(map(len, b)) - min(map(len, b)) <= 1
            # interleaved: every batch of more than one case spans the grid, not a contiguous block
            assert all(part[-1] - part[0] >= (len(part) - 1) * len(b) for part in b)


def test_cli_sweep_writes_json(tmp_path):
    out = tmp_path / "sweep.json"
    result = runner.invoke(app, ["sweep", "aviation_23x65_synthesized", "--pinion-axial", "-0.05:0.05:3",
                                 "--scheduler", "sequential", "--output", str(out)])
    assert result.exit_code == 0, result.output
    data = json.loads(out.read_text())
    assert [r["pinion_axial"] for r in data["records"]] == [-0.05, 0.0, 0.05]


def test_cli_sweep_bad_values():
    result = runner.invoke(app, ["sweep", "aviation_23x65_synthesized", "--offset", "a,b"])
    assert result.exit_code == 2 and "sweep values" in result.output


def test_logspiral_sweep_on_the_crowned_side():
    """A crowned log-spiral design is swept on the side of its crowned pinion flank (the CLI's default there): at
    zero misalignment the contact sits at the gear's mean point (on the pitch cone at the mean cone distance, where the
    crowning was designed) and the TE level is the design's te_level; a gear axial shift moves the pattern along the
    face, as on the face-milled pair."""
    from spiralbevel.conventions import Member, Side
    from spiralbevel.job.blank import blank_from_design
    from spiralbevel.job.logspiral import design_pair

    spec = load_design(bundled_designs()["aviation_23x65_logspiral_forged"])
    pair = design_pair(spec, blank_from_design(spec))
    recs = misalignment_sweep(spec, {"gear_axial": [-0.05, 0.0, 0.05]}, side="coast", scheduler="sequential")
    aligned = recs[1]
    p = pair.mean_point(Member.GEAR, Side(spec.crowning.side).mate).point
    d2 = pair.gear.pitch_angle
    r, z = float(np.hypot(p[0], p[1])), float(p[2])
    # the mean point from the pair's own recipe, projected the same way: 1 um (TCA's contact point tolerance)
    assert aligned["mean_contact_R_mm"] == pytest.approx(r * np.sin(d2) + z * np.cos(d2), abs=1e-3)
    assert aligned["mean_contact_h_mm"] == pytest.approx(r * np.cos(d2) - z * np.sin(d2), abs=1e-3)
    # the crowning's TE target over one mesh cycle (te_level at the cycle ends): the mean-point synthesis meets it to
    # 2.6 % here (7.79 arcsec for 8), the same shortfall as the job's own TCA of the mismatched pair
    assert aligned["peak_to_peak_arcsec"] == pytest.approx(spec.crowning.te_level, rel=0.04)
    R = [r["mean_contact_R_mm"] for r in recs]
    assert (R[0] - R[1]) * (R[2] - R[1]) < 0 and abs(R[2] - R[0]) > 0.05


def test_logspiral_sweep_cli_default_side_and_refusals():
    result = runner.invoke(app, ["sweep", "aviation_23x65_logspiral_forged", "--gear-axial", "0", "--scheduler",
                                 "sequential"])
    assert result.exit_code == 0, result.output
    assert "coast side" in result.output
    result = runner.invoke(app, ["sweep", "aviation_23x65_logspiral_forged", "--gear-axial", "0", "--side", "drive"])
    assert result.exit_code == 2 and "crowning.side" in result.output
    result = runner.invoke(app, ["sweep", "aviation_23x65_logspiral", "--gear-axial", "0"])
    assert result.exit_code == 2 and "line contact" in result.output and "[crowning]" in result.output
