"""``rating.fe_root_stress`` of the job report: the FE figures against Method B1 re-rated at the LTCA torque, the
plot, and the cases that skip it. The FE model is a small block segment (the bundled pair's FE build takes ~45 s,
its figures are quoted in docs/rating.md)."""

import json
from types import SimpleNamespace

import numpy as np
import pytest

pytest.importorskip("skfem")

from spiralbevel.io.design_file import bundled_designs, load_design  # noqa: E402
from spiralbevel.io.design_schema import LTCASpec  # noqa: E402
from spiralbevel.job import rating as job_rating  # noqa: E402
from spiralbevel.job.blank import blank_from_design  # noqa: E402
from spiralbevel.rating.fe_root_stress import member_root_stress  # noqa: E402


def _block_stress(member):
    Z, X = np.meshgrid(np.linspace(0.0, 6.0, 3), 100.0 + np.linspace(0.0, 4.0, 9), indexing="ij")
    lo = np.stack([X, np.full_like(X, -1.0), Z], -1)
    hi = lo.copy()
    hi[..., 1] = 1.0
    return member_root_stress(member, lo, hi, 40, "convex", 2, [np.array([[103.5, -1.0, 3.0]])], [np.array([0])],
                              [np.array([500.0])], [0], np.array([0.01]), fe_options=dict(thickness_divisions=2))


@pytest.fixture(scope="module")
def sample():
    spec = load_design(bundled_designs()["iso23509_sample1"])
    spec = spec.model_copy(update={"ltca": LTCASpec()})
    return spec, blank_from_design(spec)


def test_report_entry_compares_with_the_rerated_sheet(sample, monkeypatch, tmp_path):
    spec, blank = sample
    stresses = {"pinion": _block_stress("pinion"), "gear": _block_stress("gear")}
    monkeypatch.setattr(job_rating, "fe_root_stress_from_job", lambda *a, **k: stresses)
    u = blank.z2 / blank.z1
    ltca = SimpleNamespace(torque=150.0 * u * 1000.0)  # gear torque N mm of T1 = 150 N m
    report = {"rating": {}}
    summary = SimpleNamespace(highlights=[], files=[])
    job_rating.rating_fe_root_report(spec, blank, report, summary, ltca, setups={}, out=tmp_path, plots=True)
    entry = report["rating"]["fe_root_stress"]
    assert entry["status"] == "ok" and entry["T1_ltca_N_m"] == pytest.approx(150.0, rel=1e-12)
    # independent: the rating sheet of the design with its torque set to 150 N m
    sheet = job_rating.rating_from_design(spec.model_copy(update={"rating": spec.rating.model_copy(
        update={"pinion_torque": 150.0})}), blank)
    for member, sfx in (("pinion", "1"), ("gear", "2")):
        e = entry[member]
        assert e["sigma_F0_N_per_mm2"] == pytest.approx(sheet[f"sigma_F0{sfx}"], rel=1e-12)
        assert e["sigma_F_N_per_mm2"] == pytest.approx(sheet[f"sigma_F{sfx}"], rel=1e-12)
        assert e["sigma1_max_N_per_mm2"] == stresses[member].sigma1_max
        assert e["sigma1/sigma_F0"] == pytest.approx(e["sigma1_max_N_per_mm2"] / e["sigma_F0_N_per_mm2"], rel=1e-12)
        assert e["max_equilibrium_error_N"] < 1e-8
    json.dumps(entry)  # JSON-ready
    assert summary.files == ["root_stress.png"] and (tmp_path / "root_stress.png").stat().st_size > 0
    assert any("FE root stress" in h for h in summary.highlights)


def test_skipped_without_rating_ltca_or_on_the_coast_side(sample, monkeypatch):
    spec, blank = sample
    monkeypatch.setattr(job_rating, "fe_root_stress_from_job", lambda *a, **k: pytest.fail("must not run"))
    ltca = SimpleNamespace(torque=1.0e5)
    for s, lt in ((spec.model_copy(update={"rating": None}), ltca),
                  (spec.model_copy(update={"ltca": None}), ltca),
                  (spec.model_copy(update={"ltca": LTCASpec(side="coast")}), ltca),
                  (spec, None)):
        report = {"rating": {}}
        job_rating.rating_fe_root_report(s, blank, report, SimpleNamespace(highlights=[], files=[]), lt, setups={})
        assert "fe_root_stress" not in report["rating"]


def test_a_failed_fe_model_is_reported_not_raised(sample, monkeypatch):
    from spiralbevel.errors import DesignError

    spec, blank = sample

    def boom(*a, **k):
        raise DesignError.single("ltca points", "3.0 mm from the convex flank grid", "<= 0.5 mm", "mm")

    monkeypatch.setattr(job_rating, "fe_root_stress_from_job", boom)
    report, summary = {"rating": {}}, SimpleNamespace(highlights=[], files=[])
    job_rating.rating_fe_root_report(spec, blank, report, summary, SimpleNamespace(torque=1.0e5), setups={})
    assert report["rating"]["fe_root_stress"]["status"].startswith("not computed: ltca points")
