"""MkDocs hook: pages generated at build time, so that they never go stale.

* ``reference/design-file.md`` from the pydantic schema ``spiralbevel.io.design_schema.DesignFile``;
* ``api/<group>.md`` from the curated public API ``spiralbevel.__all__`` (rendered by mkdocstrings from the
  numpydoc docstrings);
* the output blocks of the tutorials (``<!-- tutorial-output: NAME.py -->``), by running each tutorial script.

The navigation in ``mkdocs.yml`` names the generated pages; a page named there but not generated fails the strict
build, and so does a public name that no group takes.
"""

from __future__ import annotations

import functools
import inspect
import os
import re
import subprocess
import sys
import tempfile
import types
import typing
from pathlib import Path

from mkdocs.structure.files import File

import spiralbevel
from spiralbevel.io import design_schema

#: API groups: (page stem, title, subpackages of spiralbevel whose public names it lists, intro)
API_GROUPS = (
    ("gear-pair", "Gear pair", ("gearset",),
     "The user-facing object of a gear pair, when present in this version."),
    ("logspiral", "Log-spiral gears", ("geometry", "design.logspiral_pair"),
     "Closed-form log-spiral flanks, generic differential geometry and the log-spiral pair recipe "
     "([theory](../theory/logspiral.md))."),
    ("blank", "ISO 23509 blank", ("design",), "The blank dimensions (ISO 23509, Method 0)."),
    ("face-milling", "Face milling", ("machine", "generation"),
     "Head cutter, cradle-machine settings and generated flanks ([theory](../theory/generation.md))."),
    ("meshing", "Meshing and contact", ("meshing",),
     "Pair kinematics, envelope, TCA, synthesis, motion curves, ease-off "
     "([theory](../theory/gearing.md), [TCA](../theory/tca.md))."),
    ("manufacturing", "Manufacturing", ("manufacturing",),
     "Forging draft, 5-axis tool paths, measurement grids and corrective settings."),
    ("files", "Design files and the main job", ("io", "job"),
     "Loading design files ([reference](../reference/design-file.md)) and running the main job."),
    ("basics", "Enumerations and errors", ("conventions", "errors"),
     "Members, hands, sides ([conventions](../conventions.md)) and the exception hierarchy."),
    ("more", "More", ("",), "Public names from modules that no other group covers."),
)


def _public_objects():
    """``{name: object}`` of the documented public API (``__version__`` is not an object to document)."""
    out = {}
    for name in spiralbevel.__all__:
        if name.startswith("__"):
            continue
        out[name] = getattr(spiralbevel, name)
    return out


def _group_of(obj) -> str:
    module = getattr(obj, "__module__", "") or ""
    rel = module.removeprefix("spiralbevel.")
    best, best_len = None, -1
    for stem, _title, prefixes, _intro in API_GROUPS:
        for p in prefixes:
            if (p == "" or rel == p or rel.startswith(p + ".")) and len(p) > best_len:
                best, best_len = stem, len(p)
    return best


def api_pages() -> dict[str, str]:
    """``{path: markdown}`` of the API reference pages."""
    groups: dict[str, list[tuple[str, object]]] = {g[0]: [] for g in API_GROUPS}
    for name, obj in _public_objects().items():
        groups[_group_of(obj)].append((name, obj))
    pages = {}
    index = ["# API reference", "",
             "Generated at build time from the curated public API, `spiralbevel.__all__`, and its numpydoc docstrings. "
             "Import everything from the package: `import spiralbevel as sb`. Inside the code lengths are mm and "
             "angles rad ([conventions](../conventions.md)).", ""]
    for stem, title, _prefixes, intro in API_GROUPS:
        members = sorted(groups[stem], key=lambda x: x[0])
        if not members:
            continue
        lines = [f"# {title}", "", intro, ""]
        for name, obj in members:
            target = f"{obj.__module__}.{getattr(obj, '__qualname__', name)}"
            lines += [f"::: {target}", "    options:", "      show_root_heading: true",
                      "      show_root_full_path: false", ""]
        pages[f"api/{stem}.md"] = "\n".join(lines)
        index.append(f"- [{title}]({stem}.md): " + ", ".join(f"`{n}`" for n, _ in members))
    pages["api/index.md"] = "\n".join(index) + "\n"
    return pages


# ----------------------------------------------------------------------------------------------- design-file reference

_BOUNDS = (("ge", "≥"), ("gt", ">"), ("le", "≤"), ("lt", "<"))


def _type_text(ann) -> str:
    origin = typing.get_origin(ann)
    args = typing.get_args(ann)
    if origin is typing.Annotated:
        base = args[0]
        if any(getattr(m, "func", None) is design_schema.parse_angle_deg for m in args[1:]):
            return "angle"
        return _type_text(base)
    if origin is typing.Literal:
        return " \\| ".join(f'`"{a}"`' if isinstance(a, str) else f"`{a}`" for a in args)
    if origin in (typing.Union, types.UnionType):
        parts = [_type_text(a) for a in args if a is not type(None)]
        return " or ".join(parts) + (" (optional)" if type(None) in args else "")
    if origin is tuple:
        if len(args) == 2 and args[1] is Ellipsis:
            return f"list of {_type_text(args[0])}"
        return "[" + ", ".join(_type_text(a) for a in args) + "]"
    if inspect.isclass(ann) and issubclass(ann, design_schema.BaseModel):
        return "table"
    return getattr(ann, "__name__", str(ann))


def _bounds(info) -> str:
    parts = []
    for meta in info.metadata:
        for attr, sym in _BOUNDS:
            v = getattr(meta, attr, None)
            if v is not None:
                parts.append(f"{sym} {v:g}")
    ann = info.annotation
    for a in typing.get_args(ann) or ():
        for inner in typing.get_args(a)[1:] if typing.get_origin(a) is typing.Annotated else ():
            for attr, sym in _BOUNDS:
                v = getattr(inner, attr, None)
                if v is not None:
                    parts.append(f"{sym} {v:g} each")
    return ", ".join(parts)


def _default_text(info) -> str:
    if info.is_required():
        return "**required**"
    d = info.default
    if isinstance(d, design_schema.BaseModel):
        return "table"
    if d is None:
        return "—"
    if isinstance(d, str):
        return f'`"{d}"`'
    if isinstance(d, bool):
        return f"`{str(d).lower()}`"
    if isinstance(d, tuple):
        return "`[" + ", ".join(f'"{x}"' if isinstance(x, str) else f"{x:g}" for x in d) + "]`"
    return f"`{d:g}`" if isinstance(d, (int, float)) else f"`{d}`"


def _is_angle(info) -> bool:
    return any(getattr(m, "func", None) is design_schema.parse_angle_deg for m in info.metadata)


def _model_of(ann):
    for a in (ann, *typing.get_args(ann)):
        if inspect.isclass(a) and issubclass(a, design_schema.BaseModel):
            return a
    return None


def _section(model, path: str, out: list[str]) -> None:
    subs = []
    title = f"`[{path}]`" if path else "Top level"
    out += [f"## {title}", "", (inspect.getdoc(model) or "").strip(), ""]
    rows = []
    for key, info in model.model_fields.items():
        sub = _model_of(info.annotation)
        if sub is not None:
            subs.append((key, sub))
            continue
        unit = (info.json_schema_extra or {}).get("unit", "-") if isinstance(info.json_schema_extra, dict) else "-"
        desc = (info.description or "").replace("|", "\\|")
        typ = "angle" if _is_angle(info) else _type_text(info.annotation)
        rows.append(f"| `{key}` | {typ} | {_default_text(info)} | {unit} | "
                    f"{_bounds(info)} | {desc} |")
    if rows:
        out += ["| key | type | default | unit | allowed | meaning |", "|---|---|---|---|---|---|", *rows, ""]
    for key, sub in subs:
        _section(sub, f"{path}.{key}" if path else key, out)


def design_file_page() -> str:
    out = ["# Design-file reference", "",
           "Generated at build time from the pydantic schema of design files (`spiralbevel.io.design_schema`), so it "
           "always matches the version you have. Design files are TOML and validated strictly: an unknown key is an "
           "error, and every problem is reported with the dotted key, the value, the allowed range and the unit. "
           "Angles (type *angle*) are degrees or DMS strings (`\"22°30'\"`, `\"59 20 7\"`); lengths are mm. The "
           "bundled designs (`spiralbevel examples`) are commented examples. Signs of every machine setting are "
           "defined in [Conventions](../conventions.md).", ""]
    _section(design_schema.DesignFile, "", out)
    return "\n".join(out) + "\n"


def on_files(files, config):
    pages = {"reference/design-file.md": design_file_page(), **api_pages()}
    for path, text in pages.items():
        files.append(File.generated(config, path, content=text))
    return files


def on_config(config):
    """Expand the nav entry 'API reference' into one page per non-empty API group; anchor the snippet paths."""
    stems = {p.removeprefix("api/").removesuffix(".md") for p in api_pages()}
    entries = [{"Overview": "api/index.md"}] + [{title: f"api/{stem}.md"} for stem, title, *_ in API_GROUPS
                                                if stem in stems]
    for item in config["nav"]:
        if isinstance(item, dict) and "API reference" in item:
            item["API reference"] = entries
    # snippets resolve paths against the working directory: anchor them to docs/ so that a build from anywhere works
    config["mdx_configs"].setdefault("pymdownx.snippets", {})["base_path"] = [config["docs_dir"]]
    return config


# ------------------------------------------------------------------------------------------------- tutorial outputs

_OUTPUT_MARK = re.compile(r"<!--\s*tutorial-output:\s*([\w.]+)\s*-->")


@functools.lru_cache(maxsize=None)
def tutorial_output(script: str, docs_dir: str) -> str:
    """Run ``docs/tutorials/<script>`` in a fresh interpreter and return what it prints (the build fails if it fails).

    Runs in a temporary directory, with a temporary FE cache, so that a build never reuses or pollutes user state.
    """
    path = Path(docs_dir) / "tutorials" / script
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, SPIRALBEVEL_CACHE=str(Path(tmp) / "cache"), MPLBACKEND="Agg")
        args = [sys.executable, str(path), str(Path(tmp) / "out")]
        if script == "misalignment.py":
            args[-1] = "sequential"
        proc = subprocess.run(args, cwd=tmp, env=env, capture_output=True, text=True, timeout=300)
    if proc.returncode != 0:
        raise RuntimeError(f"tutorial {script} failed:\n{proc.stderr[-3000:]}")
    return proc.stdout


def on_page_markdown(markdown, page, config, files):
    def block(match):
        return "```text\n" + tutorial_output(match.group(1), config["docs_dir"]).rstrip() + "\n```"
    return _OUTPUT_MARK.sub(block, markdown)
