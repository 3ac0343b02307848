"""Partial results are results: a failing secondary analysis becomes a report entry with its reason and a warning,
the rest of the output is written, and the exit code is 3 ("completed with warnings")."""

import json

import pytest
from typer.testing import CliRunner

from spiralbevel.cli import EXIT_WARNINGS, app
from spiralbevel.errors import ConvergenceError, NoContactError
from spiralbevel.io.design_file import default_design_text

runner = CliRunner()


def _raise(exc):
    def fail(*args, **kwargs):
        raise exc

    return fail


def test_logspiral_conjugacy_and_tca_failures_are_report_entries(tmp_path, monkeypatch):
    import spiralbevel.job.conjugacy as cj
    import spiralbevel.job.logspiral_tca as lt

    monkeypatch.setattr(cj, "conjugacy_report", _raise(ConvergenceError("envelope Newton failed", 50, 1e-3)))
    monkeypatch.setattr(lt, "logspiral_tca", _raise(NoContactError("no contact at the mean position")))
    f = tmp_path / "d.toml"
    text = default_design_text()
    for key in ("plots", "stl", "toolpaths", "draft"):
        text = text.replace(f"{key} = true", f"{key} = false")
    f.write_text(text)
    res = runner.invoke(app, ["run", str(f), "-o", str(tmp_path / "out"), "-q"])
    assert res.exit_code == EXIT_WARNINGS, res.output
    assert "completed with warnings" in res.output and "Traceback" not in res.output
    assert "conjugacy check (envelope solver) failed (envelope Newton failed" in res.output
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    assert report["logspiral"]["conjugacy"]["status"] == "failed"
    assert "envelope Newton failed" in report["logspiral"]["conjugacy"]["reason"]
    assert report["logspiral"]["tca"] == {"status": "failed", "analysis": "log-spiral tooth contact analysis",
                                          "reason": "no contact at the mean position"}
    assert [a["analysis"] for a in report["failed_analyses"]] == ["conjugacy check (envelope solver)",
                                                                  "log-spiral tooth contact analysis"]
    assert "members" in report["logspiral"] and report["blank"]     # the rest is there


def test_facemilled_ltca_and_one_sensitivity_case_fail(tmp_path, monkeypatch):
    import spiralbevel.job.ltca as jl
    import spiralbevel.job.tca as jt

    monkeypatch.setattr(jl, "run_ltca_job", _raise(NoContactError("loaded TCA: no contact")))
    real = jt.solve_tca

    def no_contact_when_tilted(*args, misalignment=None, **kwargs):
        if misalignment is not None and misalignment.shaft_angle != 0.0:
            raise NoContactError("tilted: no contact")
        return real(*args, misalignment=misalignment, **kwargs)

    monkeypatch.setattr(jt, "solve_tca", no_contact_when_tilted)
    text = default_design_text("aviation_23x65_facemilled.toml")
    text = text.replace("grid = [31, 15]\nstep = true", "grid = [9, 5]\nstep = false\nplots = false\nstl = false")
    text = text.replace("[output]", '[ltca]\nside = "drive"\ntorque = "approach"\n\n[output]')
    f = tmp_path / "d.toml"
    f.write_text(text)
    res = runner.invoke(app, ["run", str(f), "-o", str(tmp_path / "out"), "-q"])
    assert res.exit_code == EXIT_WARNINGS, res.output
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    assert report["ltca"]["status"] == "failed" and report["ltca"]["reason"] == "loaded TCA: no contact"
    sens = report["tca"]["misalignment_sensitivity"]
    assert sens["shaft_angle"]["status"] == "failed" and sens["shaft_angle"]["value_deg"] == 0.05
    assert "peak_to_peak_arcsec" in sens["offset"]                  # the other cases are results
    assert {a["analysis"] for a in report["failed_analyses"]} == {
        "loaded TCA, drive side", "misalignment sensitivity, shaft_angle case"}
    assert "max_transmission_error_arcsec" in report["tca"]["drive"]


def test_attempt_lets_bad_input_through():
    from spiralbevel.errors import DesignError
    from spiralbevel.job.partial import PartialLog, attempt

    log = PartialLog()
    with pytest.raises(DesignError):
        attempt(log, "x", _raise(DesignError.single("ltca.side", "up", "'drive' or 'coast'", "-")))
    assert log.failed == []
