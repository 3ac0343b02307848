"""Misalignment sweeps of a hypoid pair (ISO 23509 Sample 2, drive pinion by hypoid local synthesis) through the
offset kinematics with the misalignments on top: the sweep's records equal the main job's TCA and misalignment study
of the same pair (``GearSet.tca``, ``GearSet.sensitivity``: another path through the pair, the phasing and the
contact-point coordinates), and with zero offset the hypoid kinematics reproduce the spiral bevel sweep."""

import json
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import spiralbevel as sb
from spiralbevel.cli import app
from spiralbevel.io.design_file import parse_design
from spiralbevel.job import sweep
from spiralbevel.job.sweep import misalignment_sweep

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _hypoid_sample2 import SAMPLE2_TOML, SEED001_SYNTHESIS  # noqa: E402

#: the synthesis is given (one path direction, drive side only) so that the test does not run the default search
DESIGN = SAMPLE2_TOML + '[synthesis]\nsides = ["drive"]\npath_direction = 40\n' + SEED001_SYNTHESIS
#: the same TCA solves reached through two paths to the same pair (sweep worker, GearSet): equal to round-off
TE_TOL, PT_TOL = 1e-6, 1e-9


@pytest.fixture(scope="module")
def design():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")      # Sample 2's own face width warning
        return parse_design(DESIGN, source="<hypoid sweep test>")


@pytest.fixture(scope="module")
def records(design):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        grid = {"pinion_axial": [0.0, 0.05], "offset": [0.0, 0.05]}
        return {(r["pinion_axial"], r["offset"]): r
                for r in misalignment_sweep(design, grid, side="drive", scheduler="sequential")}


def _ptp(tca):
    # the sweep's TE level: peak to peak over the solved positions (the report's TCA level also takes the exact
    # transfer points between tooth pairs, a few hundredths of an arcsec higher here)
    te = tca.result.te_arcsec
    return float(np.ptp(te[np.isfinite(te)]))


def test_sweep_equals_the_tca_and_the_misalignment_study(design, records):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        gs = sb.GearSet.from_dict(design.model_dump(mode="json"))
        sens = gs.sensitivity("drive", positions=41).to_dict()
        tcas = {key: gs.tca("drive", misalignment={"pinion_axial": key[0], "offset": key[1]}, positions=41)
                for key in records}
    assert all("error" not in r for r in records.values())
    # every grid point: the TCA of the hypoid pair with that misalignment on top of the offset
    for key, r in records.items():
        assert r["peak_to_peak_arcsec"] == pytest.approx(_ptp(tcas[key]), abs=TE_TOL), key
        assert r["edge_contact_positions"] == int(np.sum(tcas[key].result.edge_contact)), key
    base = records[(0.0, 0.0)]
    assert base["mean_contact_R_mm"] == pytest.approx(sens["aligned"]["contact_R_mm"], abs=PT_TOL)
    assert base["mean_contact_h_mm"] == pytest.approx(sens["aligned"]["contact_h_mm"], abs=PT_TOL)
    # one misalignment at a time: the study's contact shifts (its contact point read in the unrotated gear frame)
    for key, axis in (((0.05, 0.0), "pinion_axial"), ((0.0, 0.05), "offset")):
        r, s = records[key], sens[axis]
        assert r["mean_contact_R_mm"] - base["mean_contact_R_mm"] == pytest.approx(
            s["contact_shift_along_face_mm"], abs=PT_TOL), axis
        assert r["mean_contact_h_mm"] - base["mean_contact_h_mm"] == pytest.approx(
            s["contact_shift_along_profile_mm"], abs=PT_TOL), axis
    # the misalignments move the hypoid pair's contact (the sweep is not blind to them)
    assert abs(records[(0.05, 0.05)]["mean_contact_R_mm"] - base["mean_contact_R_mm"]) > 0.01


def test_sweep_of_an_unsynthesized_side_names_the_key(design):
    from spiralbevel.errors import DesignError

    with pytest.raises(DesignError, match="synthesis.sides"):
        misalignment_sweep(design, {"offset": [0.0]}, side="coast", scheduler="sequential")


def test_cli_sweep_on_a_hypoid(tmp_path):
    f = tmp_path / "hypoid.toml"
    f.write_text(DESIGN)
    out = tmp_path / "sweep.json"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = CliRunner().invoke(app, ["sweep", str(f), "--offset", "0,0.05", "--scheduler", "sequential",
                                       "--output", str(out)])
    assert res.exit_code == 0, res.output
    recs = json.loads(out.read_text())["records"]
    assert [r["offset"] for r in recs] == [0.0, 0.05] and all("error" not in r for r in recs)


def test_zero_offset_hypoid_kinematics_reproduce_the_spiral_bevel_sweep(monkeypatch):
    """The bundled face-milled spiral bevel pair swept through the hypoid kinematics with E = 0 (its flanks phased by
    the hypoid phasing) gives the spiral bevel sweep's records to round-off, misalignments included."""
    from spiralbevel.conventions import Member
    from spiralbevel.gearset.facemilled import PAIR_SIDES
    from spiralbevel.io.design_file import bundled_designs, load_design
    from spiralbevel.job.blank import blank_from_design
    from spiralbevel.job.facemilled import setup_flanks
    from spiralbevel.meshing.hypoid_kinematics import HypoidPairKinematics
    from spiralbevel.meshing.hypoid_pair import phased_for_hypoid_pair

    spec = load_design(str(bundled_designs()["aviation_23x65_facemilled"]))
    grid = {"pinion_axial": [0.03], "offset": [0.0, 0.05], "shaft_angle": [0.02]}
    ref = misalignment_sweep(spec, grid, side="drive", scheduler="sequential")
    blank = blank_from_design(spec)
    s1, s2 = PAIR_SIDES["drive"]
    setups = setup_flanks(spec, blank)
    kin = HypoidPairKinematics.from_blank(blank)
    assert kin.offset == 0.0
    gear = setups[(Member.GEAR, s2)].flank
    c1, c2 = phased_for_hypoid_pair(kin, blank, setups[(Member.PINION, s1)].flank, gear)
    hyp = (c1, c2, kin, gear.outline.Rh, {"start": np.r_[c1.reference_params, c2.reference_params, 0.0]})
    monkeypatch.setattr(sweep, "_pair", lambda spec_json, side: hyp)
    got = misalignment_sweep(spec, grid, side="drive", scheduler="sequential")
    assert len(got) == len(ref) == 2
    for a, b in zip(ref, got):
        # round-off: the two phasings turn the flanks by angles equal to ~1e-16 rad (tests/meshing, 1e-7 arcsec)
        assert b["peak_to_peak_arcsec"] == pytest.approx(a["peak_to_peak_arcsec"], abs=1e-7)
        assert b["mean_contact_R_mm"] == pytest.approx(a["mean_contact_R_mm"], abs=1e-9)
        assert b["mean_contact_h_mm"] == pytest.approx(a["mean_contact_h_mm"], abs=1e-9)
        assert b["edge_contact_positions"] == a["edge_contact_positions"]
