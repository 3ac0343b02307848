"""The documented example scripts run and produce what the README says."""

import json
import runpy
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def test_seed001_cmc_example(tmp_path, monkeypatch):
    monkeypatch.setattr(sys, "argv", ["seed001_cmc.py", str(tmp_path)])
    runpy.run_path(str(EXAMPLES / "seed001_cmc.py"), run_name="__main__")
    data = json.loads((tmp_path / "seed001_cmc.json").read_text())
    assert max(data["tca"]["control_point_errors_rad"]) <= 1e-9
    assert data["tca"]["max_transmission_error_arcsec"] == pytest.approx(-3.0, rel=0.05)  # paper model vs 3"
    for name in ("seed001_te.png", "seed001_blank_offset.png", "seed001_cmc.png", "seed001_contact.png"):
        assert (tmp_path / name).stat().st_size > 0
