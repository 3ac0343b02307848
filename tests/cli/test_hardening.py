"""The reproducers of the input-hardening campaign, through the CLI: each gives a clean error (exit 2, no traceback,
the design-file key or option named) or a correct result, and never touches a file it does not own."""

import os
import time

import pytest
from typer.testing import CliRunner

from spiralbevel.cli import app
from spiralbevel.io.design_file import default_design_text

runner = CliRunner()


def _clean(result, code=2):
    assert result.exit_code == code, result.output
    assert "Traceback" not in result.output and result.exception is None or isinstance(result.exception, SystemExit)
    return result.output


def test_nonexistent_path_is_an_error_not_the_bundled_example(tmp_path):
    out = _clean(runner.invoke(app, ["check", "/nonexistent/aviation_23x65_logspiral.toml"]))
    assert "file not found" in out
    out = _clean(runner.invoke(app, ["check", str(tmp_path / "aviation_23x65_logspiral")]))
    assert "file not found" in out


def test_bare_name_selects_the_bundled_example():
    assert "ok" in _clean(runner.invoke(app, ["check", "aviation_23x65_logspiral"]), 0)
    assert "ok" in _clean(runner.invoke(app, ["check", "aviation_23x65_logspiral.toml"]), 0)


@pytest.mark.parametrize("value, fragment", [('"' + "1" * 1500 + 'x"', "longer than 64"),
                                             ('"22.5.5"', "cannot read"), ('"20.5 30"', "only the last component")])
def test_malformed_angle_is_rejected_fast_naming_the_key(tmp_path, value, fragment):
    f = tmp_path / "d.toml"
    text = default_design_text()
    assert "normal_pressure_angle = 20" in text
    f.write_text(text.replace("normal_pressure_angle = 20", f"normal_pressure_angle = {value}", 1))
    t0 = time.perf_counter()
    out = _clean(runner.invoke(app, ["check", str(f)]))
    assert time.perf_counter() - t0 < 5.0           # was 124 s for 1,500 digits
    assert "gear_set.normal_pressure_angle" in out and fragment in out


@pytest.mark.parametrize("payload", [default_design_text().encode("latin-1", "replace") + "# Zahnräder\n".encode(
    "latin-1"), default_design_text().encode("utf-16"), bytes(range(256))])
def test_undecodable_design_file(tmp_path, payload):
    f = tmp_path / "d.toml"
    f.write_bytes(payload)
    assert "UTF" in _clean(runner.invoke(app, ["check", str(f)]))


def test_deeply_nested_design_file(tmp_path):
    f = tmp_path / "d.toml"
    f.write_text("x = " + "[" * 5000 + "]" * 5000 + "\n")
    assert "nested" in _clean(runner.invoke(app, ["check", str(f)]))


@pytest.mark.parametrize("args, fragment", [
    (["--offset", "nan"], "--offset"), (["--offset", "inf"], "--offset"), (["--gear-axial", "1e300"], "--gear-axial"),
    (["--shaft-angle", "90"], "--shaft-angle"), (["--pinion-axial", "0:1:100000000"], "count"),
    (["--pinion-axial", "0:1:1000", "--offset", "0:1:1000"], "at most 10000 runs"),
    (["--scheduler", "bogus"], "--scheduler"), (["--scheduler", "tcp://localhost"], "port"),
    (["--scheduler", "tcp://localhost:99999"], "port"), (["--side", "sideways"], "--side"),
])
def test_sweep_inputs_checked_before_any_work(args, fragment):
    t0 = time.perf_counter()
    out = _clean(runner.invoke(app, ["sweep", "aviation_23x65_synthesized", *args]))
    assert fragment in out
    assert time.perf_counter() - t0 < 10.0


def test_machine_root_angle_is_named_as_the_culprit(tmp_path):
    # once blamed on radial_setting = 115.078 mm
    text = default_design_text("aviation_23x65_facemilled.toml")
    f = tmp_path / "d.toml"
    f.write_text(text.replace("machine_root_angle = \"68°01'30\\\"\"", "machine_root_angle = 0.001"))
    assert f.read_text() != text
    out = _clean(runner.invoke(app, ["check", str(f)]))
    assert "face_milling.gear_convex.machine.machine_root_angle = 0.001 deg" in out
    assert "radial_setting" not in out


def test_foreign_output_directory_is_refused_untouched(tmp_path):
    out = tmp_path / "projects"
    out.mkdir()
    (out / "thesis.tex").write_text("years of work")
    msg = _clean(runner.invoke(app, ["run", "-o", str(out), "-q"]))
    assert "not a spiralbevel output" in msg
    assert [p.name for p in out.iterdir()] == ["thesis.tex"] and (out / "thesis.tex").read_text() == "years of work"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["projects"]


def test_output_dot_in_a_foreign_directory_is_refused(tmp_path, monkeypatch):
    (tmp_path / "notes.txt").write_text("keep")
    monkeypatch.chdir(tmp_path)
    assert "not a spiralbevel output" in _clean(runner.invoke(app, ["run", "-o", ".", "-q"]))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.txt"]


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="POSIX FIFOs")
@pytest.mark.parametrize("kind", ["fifo", "symlink", "directory"])
def test_single_file_output_replaces_only_regular_files(tmp_path, kind):
    target = tmp_path / "b.json"
    victim = tmp_path / "victim.txt"
    victim.write_text("precious")
    if kind == "fifo":
        os.mkfifo(target)
    elif kind == "symlink":
        target.symlink_to(victim)
    else:
        target.mkdir()
    for cmd in (["blank", "--json", "--output", str(target)],
                ["sweep", "aviation_23x65_synthesized", "--scheduler", "sequential", "--output", str(target)]):
        out = _clean(runner.invoke(app, cmd))
        assert "only a regular file is replaced" in out or "not a regular file" in out or "is a" in out
    assert victim.read_text() == "precious"
    assert {"fifo": target.is_fifo(), "symlink": target.is_symlink(), "directory": target.is_dir()}[kind]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["b.json", "victim.txt"]


def test_restated_ranges_keep_words_that_contain_pi():
    # once "allowed 0 < value < 180tch angle": the "pi" inside "pitch" was read as the number pi
    import math

    from spiralbevel.errors import DesignError
    from spiralbevel.job.problems import _deg_text, restated

    assert _deg_text("0 < value < pitch angle = 0.5") == f"0 < value < pitch angle = {math.degrees(0.5):.6g}"
    assert _deg_text("pitch angle = 0.5 < value < pi/2") == f"pitch angle = {math.degrees(0.5):.6g} < value < 90"
    assert _deg_text("k1 < pi") == "k1 < 180"
    err = restated(DesignError.single("boundaries[pinion].root_angle", 0.6, "0 < value < pitch angle = 0.5", "rad"),
                   {"boundaries[pinion].": "gear_set.depth -> pinion blank"})
    text = str(err)
    assert "gear_set.depth -> pinion blank" in text and "pitch angle = 28.6479" in text and "tch" not in text.replace(
        "pitch", "")


def test_every_problem_names_a_design_file_key():
    # computational names ("grid(face station)", "locate(axial, radius)") are shown under the section that controls
    # them; design-file paths and options are left as they are
    from spiralbevel.errors import DesignError, Problem
    from spiralbevel.job.problems import with_design_keys

    err = DesignError([Problem("grid(face station)", "15 of 31 points", "", "mm"),
                       Problem("gear_set.module", -1, "> 0", "mm"), Problem("--offset", "x")])
    fields = [p.field for p in with_design_keys(err, "face_milling", "in the step 'plots'").problems]
    assert fields == ["face_milling (grid(face station), in the step 'plots')", "gear_set.module", "--offset"]
