"""The documentation site builds with warnings as errors (extra 'docs'), and the docs cite no developer-only file."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_docs_build_strict(tmp_path):
    pytest.importorskip("mkdocs")
    pytest.importorskip("mkdocstrings_handlers.python")
    pytest.importorskip("material")
    proc = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-4000:]
    html = (tmp_path / "site" / "reference" / "design-file" / "index.html").read_text(encoding="utf-8")
    from spiralbevel.io.design_schema import BaseModel, DesignFile

    # the design-file reference is generated from the schema: every table and every key of the schema is on the page
    def walk(model, path):
        for key, info in model.model_fields.items():
            sub = next((a for a in (info.annotation, *getattr(info.annotation, "__args__", ()))
                        if isinstance(a, type) and issubclass(a, BaseModel)), None)
            if sub is None:
                assert f"<code>{key}</code>" in html, f"{path}.{key}"
            else:
                name = f"{path}.{key}" if path else key
                assert f"<code>[{name}]</code>" in html, name
                walk(sub, name)

    walk(DesignFile, "")
    api = (tmp_path / "site" / "api" / "index.html").read_text(encoding="utf-8")
    import spiralbevel

    for name in spiralbevel.__all__:
        if not name.startswith("__"):
            assert f"<code>{name}</code>" in api, name


def test_docs_and_readme_cite_no_developer_file():
    pattern = re.compile(r"ERRATA|shared/|reference/(?:ERRATA|iso|what-users)", re.I)
    files = [ROOT / "README.md", ROOT / "mkdocs.yml", *sorted((ROOT / "docs").rglob("*.md")),
             *sorted((ROOT / "docs").rglob("*.py"))]
    # the code, the bundled design files, the tests, examples and benchmarks cite the theory pages instead
    files += [f for d in ("src", "tests", "examples", "bench") for ext in ("*.py", "*.toml", "*.md")
              for f in sorted((ROOT / d).rglob(ext)) if f != Path(__file__).resolve() and ".egg-info" not in str(f)]
    bad = [f"{f.relative_to(ROOT)}:{i}" for f in files
           for i, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1) if pattern.search(line)]
    assert not bad, bad


def test_getting_started_has_the_readme_commands():
    def block(text, after):
        return re.findall(r"```bash\n(.*?)```", text.split(after, 1)[1], re.S)[0]

    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    page = (ROOT / "docs" / "getting-started.md").read_text(encoding="utf-8")
    assert block(page, "# Getting started") == block(readme, "## Quick start")
