"""CLI polish (issue 12 item 6): version, ``python -m``, markup-safe messages, plain output off a terminal, the
machine default, one round of validation, the cache directory option, setting names that round-trip."""

import os
import subprocess
import sys

from typer.testing import CliRunner

from spiralbevel import __version__
from spiralbevel.cli import app

runner = CliRunner()


def test_version():
    result = runner.invoke(app, ["--version"])
    assert result.exit_code == 0 and result.output.strip() == f"spiralbevel {__version__}"


def test_python_dash_m():
    """``python -m spiralbevel`` runs the same app (a real subprocess: stdout is a pipe, not a terminal)."""
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    out = subprocess.run([sys.executable, "-m", "spiralbevel", "--version"], capture_output=True, text=True,
                         env=env, timeout=120)
    assert out.returncode == 0 and out.stdout.strip() == f"spiralbevel {__version__}"


def test_user_text_is_not_markup():
    """``:a:`` is an emoji code and ``[red]`` a style for rich: both must come back verbatim."""
    result = runner.invoke(app, ["sweep", "aviation_23x65_facemilled", "--pinion-axial", "0.1:a:3"])
    assert result.exit_code == 2
    assert "'0.1:a:3'" in result.output
    result = runner.invoke(app, ["check", "[red]no_such[/red].toml"])
    assert result.exit_code == 2 and "[red]no_such[/red].toml" in result.output


def test_plain_unwrapped_output_when_piped(tmp_path):
    """Off a terminal a long message stays on one line and carries no escape codes."""
    from spiralbevel.io.design_file import bundled_designs

    text = bundled_designs()["aviation_23x65_logspiral"].read_text(encoding="utf-8")
    f = tmp_path / "long.toml"
    f.write_text(text.replace(text.splitlines()[5], 'title = "' + "a long title " * 12 + '"'), encoding="utf-8")
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "COLUMNS": "40"}
    out = subprocess.run([sys.executable, "-m", "spiralbevel", "check", str(f)], capture_output=True, text=True,
                         env=env, timeout=300)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert len(lines) == 1 and lines[0].rstrip() == ("ok " + "a long title " * 12).rstrip()
    assert "\x1b[" not in out.stdout + out.stderr


def test_machine_without_argument_uses_face_milled_default():
    result = runner.invoke(app, ["machine"])
    assert result.exit_code == 0, result.output
    assert "Radial setting" in result.output and "pinion convex" in result.output


def test_check_lists_schema_and_blank_problems_in_one_round(tmp_path):
    from spiralbevel.io.design_file import bundled_designs

    text = bundled_designs()["aviation_23x65_logspiral"].read_text(encoding="utf-8")
    text = text.replace("face_width = 37.0", "face_width = 150.0").replace("module = 3.9", "module = 3.9\nbogus = 1")
    f = tmp_path / "two.toml"
    f.write_text(text, encoding="utf-8")
    result = runner.invoke(app, ["check", str(f)])
    assert result.exit_code == 2
    assert "2 problem(s)" in result.output
    assert "gear_set.bogus" in result.output                       # schema
    assert "gear_set.face_width = 150.0 mm" in result.output        # blank, found in the same round


def test_cache_dir_option(tmp_path, monkeypatch):
    monkeypatch.setenv("SPIRALBEVEL_CACHE", str(tmp_path / "elsewhere"))
    target = tmp_path / "my cache"
    result = runner.invoke(app, ["cache", "info", "--cache-dir", str(target)])
    assert result.exit_code == 0, result.output
    assert f"cache: {target}" in result.output and "0 entries" in result.output
    not_dir = tmp_path / "file"
    not_dir.write_text("x")
    result = runner.invoke(app, ["cache", "clear", "--cache-dir", str(not_dir)])
    assert result.exit_code == 2 and "--cache-dir" in result.output


def test_run_help_documents_cache_dir():
    result = runner.invoke(app, ["run", "--help"], env={"COLUMNS": "200"})
    assert "--cache-dir" in result.output and "SPIRALBEVEL_CACHE" in result.output


def test_help_keeps_bracketed_section_names():
    """Rich reads ``[rating]`` in a command's docstring as a style tag and drops it; every command's first help line
    must come through whole (a bracketed section name is written ``\\[rating]`` in the docstring)."""
    import inspect
    import re

    for cmd in app.registered_commands:
        name = cmd.name or cmd.callback.__name__
        first = inspect.getdoc(cmd.callback).split("\n\n")[0].replace("\\[", "[")
        result = runner.invoke(app, [name, "--help"], env={"COLUMNS": "300"})
        assert result.exit_code == 0, (name, result.output)
        assert " ".join(first.split()) in " ".join(re.sub(r"[│╭╮╰╯─]", " ", result.output).split()), name
