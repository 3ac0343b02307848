"""The README's Python examples run, and its Quick start has exactly two commands."""

import re
from pathlib import Path

README = Path(__file__).resolve().parents[1] / "README.md"


def test_readme_python_examples_run(capsys):
    text = README.read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert blocks
    for code in blocks:
        exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    assert "26.24 81.273" in out  # ISO 23509 Annex F Sample 1: delta_a1 = 26.240 deg, Rm = 81.273 mm
    lines = out.splitlines()
    assert "30.0" in lines        # seed 001 gear (Tables 1, 4): mean spiral angle 30 deg (29.997)
    assert "3.7" in lines         # synthesized ellipse semi-major axis (Table 2)


def test_quick_start_has_two_commands():
    text = README.read_text(encoding="utf-8")
    section = text.split("## Quick start", 1)[1].split("##", 1)[0]
    block = re.findall(r"```bash\n(.*?)```", section, re.S)[0]
    commands = [line for line in block.splitlines() if line.strip()]
    assert len(commands) == 2
    assert "spiralbevel run" in commands[0] and "pytest" in commands[1]
    ci = (README.parent / ".ci" / "run").read_text()
    assert commands[1].strip() in ci
