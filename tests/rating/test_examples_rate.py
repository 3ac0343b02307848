"""The rating of every bundled example runs: designs without a [rating] section get a common one."""

import math

import pytest

from spiralbevel.io.design_file import bundled_designs, load_design
from spiralbevel.io.design_schema import RatingSpec
from spiralbevel.job.blank import blank_from_design
from spiralbevel.job.rating import rating_from_design, rating_report

COMMON = RatingSpec(pinion_torque=200.0, pinion_speed=3000.0, accuracy_grade=6, sigma_Hlim=1500.0,
                    sigma_Flim=480.0, oil_viscosity=100.0)


@pytest.mark.parametrize("name", sorted(bundled_designs()))
def test_rating_of_bundled_example_runs(name):
    spec = load_design(bundled_designs()[name])
    if spec.rating is None:
        # a hypoid needs its hypoid factor Z_Hyp given (not computed: docs/rating.md); ISO/TR 10300-30 Sample 2's
        common = COMMON.model_copy(update={"hypoid_factor": 0.952}) if spec.gear_set.hypoid_offset else COMMON
        spec = spec.model_copy(update={"rating": common})
    res = rating_from_design(spec)
    for key, v in res.values.items():
        assert math.isfinite(v), key
    for key in ("S_H", "S_F1", "S_F2", "sigma_H", "sigma_F1", "sigma_F2", "Y_Fa1", "Y_Sa2"):
        assert res[key] > 0, key
    # derived cutter edge radii are positive and below the cutter addendum
    assert 0 < res["rho_a01"] < res["h_a01"] and 0 < res["rho_a02"] < res["h_a02"]


def test_report_section_only_with_rating():
    spec = load_design(bundled_designs()["iso23509_sample1"])
    blank = blank_from_design(spec)

    class Summary:
        highlights = []

    report = {}
    rating_report(spec, blank, report, Summary)
    assert report["rating"]["standard"].startswith("ISO 10300")
    assert report["rating"]["S_H"] > 0 and "S_H" in Summary.highlights[-1]
    report = {}
    rating_report(spec.model_copy(update={"rating": None}), blank, report, Summary)
    assert "rating" not in report


def test_power_equals_torque():
    spec = load_design(bundled_designs()["iso23509_sample1"])
    P = 300.0 * 1200.0 * math.pi / 30000.0  # kW of 300 N m at 1200 1/min
    alt = spec.model_copy(update={"rating": spec.rating.model_copy(update={"pinion_torque": None, "power": P})})
    assert rating_from_design(alt)["sigma_H"] == pytest.approx(rating_from_design(spec)["sigma_H"], rel=1e-12)


def test_main_job_report_has_the_rating(tmp_path):
    from spiralbevel.job import run_design

    spec = load_design(bundled_designs()["iso23509_sample1"])
    spec = spec.model_copy(update={"output": spec.output.model_copy(
        update={"plots": False, "stl": False, "step": False, "toolpaths": False, "draft": False})})
    summary = run_design(spec, tmp_path / "out", progress=False)
    assert summary.report["rating"]["S_H"] == pytest.approx(rating_from_design(spec)["S_H"], rel=1e-12)
    assert any(line.startswith("rating (ISO 10300 B1)") for line in summary.highlights)
