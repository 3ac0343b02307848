"""End to end: seed 001 gear (Table 4) with the pinion drive side by local synthesis (Table 2 design data)."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.io.design_file import default_design_text

runner = CliRunner()


@pytest.fixture(scope="module")
def syn_run(tmp_path_factory):
    d = tmp_path_factory.mktemp("syn")
    f = d / "syn.toml"
    f.write_text(default_design_text("aviation_23x65_synthesized.toml").replace("grid = [31, 15]", "grid = [15, 9]"))
    out = d / "out"
    result = runner.invoke(app, ["run", str(f), "-o", str(out), "-q"])
    assert result.exit_code == 0, result.output
    return out, json.loads((out / "report.json").read_text())


def test_synthesis_reported_with_design_values(syn_run):
    _, report = syn_run
    s = report["synthesis"]["drive"]
    assert s["eta_deg"] == pytest.approx(6.0, abs=1e-6)
    assert s["semi_axes_mm"][0] == pytest.approx(3.7, rel=1e-6)
    assert s["te_magnitude_arcsec"] == pytest.approx(3.0, rel=1e-6)
    assert report["machine_settings"]["pinion"]["concave"]["source"].startswith("local synthesis")


def test_tca_of_synthesized_pair(syn_run):
    _, report = syn_run
    t = report["tca"]["drive"]
    te = np.array(t["transmission_error_arcsec"])
    phi = np.radians(t["pinion_rotation_deg"])
    assert t["max_transmission_error_arcsec"] == pytest.approx(0.0, abs=1e-6)   # the mean contact point
    # near the mean point the TE is the designed parabola: 3" over one mesh cycle 2 pi / 23 (Table 2)
    near = np.abs(phi) < 0.05
    x = phi[near]
    a2 = np.polyfit(x, te[near], 2)[0]
    assert a2 == pytest.approx(-3.0 / (np.pi / 23) ** 2, rel=0.05)


def test_contact_ratio_from_tca_is_the_iso_transverse_ratio(syn_run):
    """The pair's path leaves the profile direction by 6 deg only: one pair's contact runs from root to top about as
    the transverse path of contact of ISO 10300-1 (eps_valpha of the virtual cylindrical gears, from the blank
    alone; meshing/tca_checks.contact_ratio).

    Tolerance: half a grid step at each end (1/40 of the pitch at the 41 TCA positions) plus 2 % of eps_valpha for
    the virtual cylindrical gears (involutes on the back cone of the mean section, where the real bevel path leaves
    the mean section and the depth tapers; 0.3-2 % observed on both sides at 41 and 81 positions)."""
    _, report = syn_run
    for name in ("drive", "coast"):
        t = report["tca"][name]
        assert t["positions"] == 41 and not t["contact_ratio_from_tca_is_lower_bound"]
        eps_a = t["contact_ratio_iso10300_transverse"]
        assert t["contact_ratio_from_tca"] == pytest.approx(eps_a, abs=1 / 40 + 0.02 * eps_a), name
        assert eps_a < t["contact_ratio_iso10300_total"]


def test_easeoff_is_clearance_and_measurement_grids(syn_run):
    out, report = syn_run
    e = report["easeoff"]["drive"]
    assert e["min_mm"] > -1e-6 and e["max_mm"] > 0.01   # crowned: clearance everywhere but the mean point
    for name in report["measurement"].values():
        if isinstance(name, str) and name.endswith(".csv"):
            lines = (out / name).read_text().strip().splitlines()
            assert len([ln for ln in lines if not ln.startswith("#")]) == 1 + 45


def test_ltca_of_synthesized_pair(syn_run):
    out, report = syn_run
    lt = report["ltca"]
    # seed 001 §4.3.2: at the torque of a 0.00635 mm approach the loaded TE grows well beyond the unloaded one
    # (paper: -3.15" unloaded, -22.08" loaded)
    assert lt["torque_N_m"] == pytest.approx(lt["torque_for_approach_N_m"])
    assert lt["torque_for_approach_N_m"] > 1.0
    assert lt["loaded_transmission_error_largest_magnitude_arcsec"] < 0
    assert abs(lt["loaded_transmission_error_largest_magnitude_arcsec"]) > 3 * abs(
        lt["unloaded_transmission_error_largest_magnitude_arcsec"])
    share = np.array(lt["load_share"])
    assert np.allclose(share.sum(axis=1), 1.0, atol=1e-9)   # load sharing adds up at every position
    assert lt["positions_with_two_pairs_loaded"] >= 1
    assert (out / "ltca.png").stat().st_size > 0


def test_both_sides_synthesized_give_localized_contact(syn_run):
    _, report = syn_run
    for side in ("drive", "coast"):
        t = report["tca"][side]
        assert t["max_transmission_error_arcsec"] == pytest.approx(0.0, abs=1e-6)
        assert t["peak_to_peak_arcsec"] < 10.0          # a few arcsec, not the hundreds of unsynthesized settings
    assert report["machine_settings"]["pinion"]["convex"]["source"].startswith("local synthesis")
