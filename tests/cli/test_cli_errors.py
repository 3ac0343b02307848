"""CLI: bad input exits with code 2 and lists every problem without a traceback."""

from typer.testing import CliRunner

from spiralbevel.cli import app

runner = CliRunner()


def test_check_default_ok():
    result = runner.invoke(app, ["check"])
    assert result.exit_code == 0, result.output
    assert "ok" in result.output


def test_bad_design_exit_2_lists_problems(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text("[gear_set]\npinion_teeth = -4\ngear_teeth = 65\nmodule = 3.9\nface_width = 37\n"
                 "mean_spiral_angle = 90\nunknown = 1\n")
    result = runner.invoke(app, ["check", str(f)])
    assert result.exit_code == 2
    out = result.output
    assert "gear_set.pinion_teeth = -4" in out
    assert "gear_set.mean_spiral_angle = 90.0 deg" in out and "< 60.0 deg" in out
    assert "gear_set.unknown" in out
    assert "Traceback" not in out


def test_malformed_toml_exit_2(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text("[gear_set\n")
    result = runner.invoke(app, ["check", str(f)])
    assert result.exit_code == 2 and "malformed TOML" in result.output


def test_missing_file_exit_2(tmp_path):
    result = runner.invoke(app, ["run", str(tmp_path / "missing.toml"), "-o", str(tmp_path / "o")])
    assert result.exit_code == 2 and "file not found" in result.output
    assert not (tmp_path / "o").exists()


def test_run_into_missing_parent_names_the_output_path(tmp_path):
    out = tmp_path / "no" / "such" / "out"
    result = runner.invoke(app, ["run", "-q", "-o", str(out)])
    assert result.exit_code == 2, result.output
    assert str(out) in result.output and "parent directory" in result.output
    assert ".tmp" not in result.output
    assert list(tmp_path.iterdir()) == []


def test_log_spiral_hypoid_names_the_keys_to_change(tmp_path):
    """A log-spiral design with a hypoid offset: the allowed value reads "0 mm" (not "a = 0 (...) mm") and the hint
    names the keys to change, not the commands that develop a face-milled hypoid pair."""
    f = tmp_path / "d.toml"
    f.write_text("[gear_set]\npinion_teeth = 12\ngear_teeth = 41\nmodule = 5\nface_width = 30\n"
                 "mean_spiral_angle = 35\nhypoid_offset = 10\n[flank]\nkind = \"log-spiral\"\n")
    for cmd in (["check", str(f)], ["run", str(f), "-q", "-o", str(tmp_path / "out")]):
        result = runner.invoke(app, cmd)
        assert result.exit_code == 2, result.output
        text = " ".join(result.output.split())
        assert "gear_set.hypoid_offset = 10.0 mm: allowed 0 mm (" in text, text
        assert "flank.kind = 'face-milled'" in text and "this command does not take the offset" not in text
    assert not (tmp_path / "out").exists()
