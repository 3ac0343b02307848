"""LTCA peak pressure against the Method B1 contact stress: the re-rating at the LTCA's torque, checked against the
Hertzian square-root law and the sheet at the rated torque; the pressure read from the LTCA result object."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from spiralbevel.errors import DesignError
from spiralbevel.io.design_file import bundled_designs, load_design
from spiralbevel.job.blank import blank_from_design
from spiralbevel.job.rating import rating_from_design, rating_input_from_design, rating_ltca_report
from spiralbevel.rating import compare_with_ltca


@pytest.fixture(scope="module")
def sample():
    spec = load_design(bundled_designs()["iso23509_sample1"])
    blank = blank_from_design(spec)
    return spec, blank, rating_input_from_design(spec, blank)


def _ltca(T2_Nmm, pressure):
    # the attributes of LTCAResult that the comparison reads (gear torque N mm, per-position peak pressure ...)
    n = len(pressure)
    share = np.zeros((n, 3))
    share[:, 1] = 1.0
    share[2, :2] = 0.5  # two pairs share the load at position 2
    share[2, 2] = 0.0
    return SimpleNamespace(torque=T2_Nmm, max_pressure=np.asarray(pressure, float),
                           pinion_angles=np.radians(np.linspace(-5.0, 5.0, n)), load_share=share)


def test_rated_torque_gives_the_rating_sheet(sample):
    spec, blank, inp = sample
    u = blank.z2 / blank.z1
    cmp = compare_with_ltca(blank, inp, _ltca(300.0 * u * 1000.0, [900.0, np.nan, 1500.0, 1200.0, 800.0]))
    sheet = rating_from_design(spec)
    assert cmp["T1_ltca"] == pytest.approx(300.0, rel=1e-12)
    assert cmp["sigma_H0"] == pytest.approx(sheet["sigma_H0"], rel=1e-12)
    assert cmp["sigma_H"] == pytest.approx(sheet["sigma_H"], rel=1e-12)
    # the peak over the cycle, NaN (unloaded position) skipped; its position and the pairs in contact there
    assert cmp["p_max_ltca"] == 1500.0
    assert cmp["phi1_at_p_max"] == pytest.approx(0.0, abs=1e-12)
    assert cmp["pairs_at_p_max"] == 2
    assert cmp["p_max/sigma_H0"] == pytest.approx(1500.0 / sheet["sigma_H0"], rel=1e-12)


def test_nominal_stress_follows_the_hertz_square_root(sample):
    # sigma_H0 has no load-dependent factor: four times the torque doubles it (line contact p ~ sqrt(F))
    _, blank, inp = sample
    u = blank.z2 / blank.z1
    a = compare_with_ltca(blank, inp, _ltca(100.0 * u * 1000.0, [1000.0] * 5))
    b = compare_with_ltca(blank, inp, _ltca(400.0 * u * 1000.0, [1000.0] * 5))
    assert b["sigma_H0"] == pytest.approx(2.0 * a["sigma_H0"], rel=1e-12)
    # sigma_H carries K_v and K_Halpha, whose deviation terms weigh less under a larger load
    assert b["sigma_H"] / b["sigma_H0"] < a["sigma_H"] / a["sigma_H0"]


def test_ltca_without_pressure_is_a_clear_error(sample):
    _, blank, inp = sample
    with pytest.raises(DesignError, match="ltca"):
        compare_with_ltca(blank, inp, _ltca(1e6, [math.nan] * 5))


def test_report_section(sample):
    spec, blank, _ = sample
    u = blank.z2 / blank.z1
    res = _ltca(300.0 * u * 1000.0, [900.0, 1500.0, 1200.0, 800.0, 700.0])
    summary = SimpleNamespace(highlights=[])
    ltca_spec = SimpleNamespace(side="drive")
    report = {"rating": {}}
    rating_ltca_report(spec.model_copy(update={"ltca": ltca_spec}), blank, report, summary, res)
    section = report["rating"]["ltca_comparison"]
    assert section["status"] == "ok" and section["p_max_ltca_N_per_mm2"] == 1500.0 and "units" not in section
    assert section["sigma_H_N_per_mm2"] > 0 and section["phi1_at_p_max_deg"] is not None
    assert "LTCA peak pressure" in summary.highlights[-1]
    report = {"rating": {}}
    rating_ltca_report(spec.model_copy(update={"ltca": SimpleNamespace(side="coast")}), blank, report, summary, res)
    assert report["rating"]["ltca_comparison"]["status"].startswith("not compared")
