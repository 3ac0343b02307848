"""``report.html``: the whole run on one self-contained page (no network: styles, script, figures and meshes inline).

The page is built from the report dict (the content of ``report.json``) and the files of the run. The sections a
reader expects (dimension sheet, machine summary, design vs achieved, TCA, misalignment sensitivity, ease-off, LTCA,
manufacturing, warnings, 3-D view) are picked by :data:`SECTIONS`, a short table of report paths and figure names:
the one place to change when report keys are renamed. Inside a section everything is rendered generically
(:mod:`spiralbevel.io.report_tables`), and whatever no section claims appears under "Other results", so no computed
value is left out. Curves over the pinion rotation (transmission error, load sharing) are drawn as inline SVG; the
PNG figures the run wrote are embedded (base64); the 3-D view is a small WebGL viewer bundled in the package
(``report_assets/viewer.js``) fed with one tooth mesh per member.
"""

from __future__ import annotations

import base64
import fnmatch
import json
import math
from dataclasses import dataclass
from html import escape
from importlib import resources
from pathlib import Path

from .report_svg import line_chart
from .report_tables import format_value, label_of, render_tree, unit_of

__all__ = ["Section", "SECTIONS", "render_report_html", "write_report_html", "write_run_report_html"]


@dataclass(frozen=True)
class Section:
    """One section of the page.

    Attributes
    ----------
    id, title : str
    paths : tuple of str
        Dotted report paths shown in this section, in order (missing ones are skipped).
    figures : tuple of str
        File-name patterns of the run's PNG figures shown here.
    absent : str
        What the page says when the run has none of ``paths``.
    """

    id: str
    title: str
    paths: tuple[str, ...] = ()
    figures: tuple[str, ...] = ()
    absent: str = "Not computed in this run."


#: the lookup from report keys and figure files to the sections of the page (adapt here when report.json changes)
SECTIONS = (
    Section("dimensions", "Dimension sheet (ISO 23509)", ("blank",)),
    Section("machine", "Machine summary", ("machine_settings", "synthesis"),
            absent="No machine settings: the flanks of this design are not face-milled (the log-spiral flanks are "
                   "cut by the 5-axis tool paths under Manufacturing)."),
    Section("flanks", "Flanks: design vs achieved", ("flanks", "logspiral"),
            ("axial_section.png", "curvature_maps.png", "curvature_domain.png", "pitch_traces.png",
             "transverse_section.png")),
    Section("tca", "Tooth contact analysis", ("tca", "logspiral.tca", "mismatch.tca"), ("tca_*.png",)),
    Section("misalignment", "Misalignment sensitivity",
            ("tca.misalignment_sensitivity", "mismatch.misalignment_sensitivity"),
            absent="No misalignment cases in this run (face-milled designs, and log-spiral designs with "
                   "[crowning], compute them)."),
    Section("easeoff", "Ease-off", ("easeoff",), ("easeoff_*.png",),
            absent="No ease-off in this run (computed for face-milled designs)."),
    Section("ltca", "Loaded TCA and rating", ("ltca", "rating"), ("ltca.png", "root_stress.png"),
            absent="No loaded TCA in this run (add an [ltca] section to the design file)."),
    Section("manufacturing", "Manufacturing", ("draft", "forging", "toolpaths", "measurement", "cad", "mismatch"),
            ("draft_map*.png", "forging_deviation.png", "meshing_pair_3d.png")),
)
#: top-level keys that are not results (shown in the header or the input section)
HEADER_KEYS = ("spiralbevel_version", "title", "design", "files")
#: pinion rotation keys for curves over the mesh cycle, and the TE key pattern (suffix gives the unit)
ROTATION_KEYS = ("pinion_rotation_deg", "pinion_rotation_rad")
TE_PATTERN = "*transmission_error_arcsec"
#: file names of the tooth meshes the 3-D view draws (written by the job's STL step)
TOOTH_STL = "{member}_tooth.stl"


def _get(report: dict, path: str):
    node = report
    for part in path.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


def _numbers(v) -> bool:
    """A list of numbers (``None`` where a value does not exist)."""
    return isinstance(v, list) and all(r is None or (isinstance(r, (int, float)) and not isinstance(r, bool))
                                       for r in v)


def _curves(d: dict) -> str:
    """SVG charts of the lists in ``d`` that run over the pinion rotation (TE together, every other list alone)."""
    key = next((k for k in ROTATION_KEYS if _numbers(d.get(k)) and len(d[k]) > 2), None)
    if key is None:
        return ""
    x = [None if v is None else (math.degrees(v) if key.endswith("_rad") else v) for v in d[key]]
    te: list[tuple[str, list, list]] = []
    other: list[tuple[str, list[tuple[str, list, list]]]] = []  # (key, series) of one chart each
    for k, v in d.items():
        if k == key or not isinstance(v, list) or len(v) != len(x):
            continue
        if _numbers(v):
            name = unit_of(k)[0].replace("_", " ")
            if fnmatch.fnmatch(k, TE_PATTERN):
                te.append((name, x, v))
            else:
                other.append((k, [(name, x, v)]))
        elif all(_numbers(r) for r in v) and len({len(r) for r in v}) == 1 and v[0]:
            n = len(v[0])  # one column per tooth pair, named by pair_names when it fits
            names = d.get("pair_names")
            if not (isinstance(names, list) and len(names) == n):
                names = [f"{k} {j}" for j in range(n)]
            other.append((k, [(str(names[j]), x, [r[j] for r in v]) for j in range(n)]))
    charts = []
    if te:
        charts.append(line_chart(te, "pinion rotation [°]", "transmission error [″]", "Transmission error"))
    for k, series in other:
        charts.append(line_chart(series, "pinion rotation [°]", f"{unit_of(k)[0]} [{unit_of(k)[1] or '-'}]",
                                 label_of(k)))
    return "".join(f'<div class="chart-box">{c}</div>' for c in charts)


def _walk_curves(d: dict, path: str, skip) -> str:
    out = _curves(d)
    for k, v in d.items():
        p = f"{path}.{k}"
        if isinstance(v, dict) and not skip(p):
            inner = _walk_curves(v, p, skip)
            if inner:
                out += f"<h4>{escape(label_of(k))}: curves</h4>{inner}"
    return out


def _figure(out_dir: Path, name: str) -> str:
    data = base64.b64encode((out_dir / name).read_bytes()).decode("ascii")
    return (f'<figure><img alt="{escape(name)}" src="data:image/png;base64,{data}">'
            f"<figcaption>{escape(name)}</figcaption></figure>")


def _warnings(report: dict) -> list[str]:
    """Every warning of the report: lists named ``warnings``/``*_warnings``/``checks``, failed analyses, failed checks
    (``passes: false``), statuses other than ok; each once."""
    found: list[str] = []

    def add(text):
        if text not in found:
            found.append(text)

    def walk(node, path):
        if isinstance(node, dict):
            if node.get("status") not in (None, "ok", "converged", "contact"):
                add(f"{path}: {node['status']}" + (f" ({node['reason']})" if node.get("reason") else ""))
            if node.get("passes") is False:
                add(f"{path}: does not pass")
            for k, v in node.items():
                p = f"{path}.{k}" if path else k
                if (k in ("warnings", "checks") or k.endswith("_warnings")) and isinstance(v, list):
                    for w in v:
                        add(w if isinstance(w, str) else json.dumps(w))
                elif k == "failed_analyses" and isinstance(v, list):
                    for f in v:
                        add(f"failed: {f.get('analysis')}: {f.get('reason')}" if isinstance(f, dict) else str(f))
                elif k != "design":
                    walk(v, p)

    walk(report, "")
    return found


def render_report_html(report: dict, out_dir=None, view: dict | None = None) -> str:
    """The page as text.

    Parameters
    ----------
    report : dict
        JSON-ready report (as written to ``report.json``).
    out_dir : path, optional
        Directory of the run's files: the PNG figures listed in ``report["files"]`` are embedded from here.
    view : dict, optional
        :func:`spiralbevel.io.report_mesh.view_payload` of the meshing pair; without it the 3-D section says why.
    """
    from .report import to_jsonable

    report = to_jsonable(report)
    out_dir = Path(out_dir) if out_dir is not None else None
    files = report.get("files")
    files = [f for f in files if isinstance(f, str)] if isinstance(files, list) else []
    pngs = [f for f in files if f.endswith(".png")]
    if out_dir is not None:
        pngs = [f for f in pngs if (out_dir / f).is_file()]
    claimed = [p for s in SECTIONS for p in s.paths]
    used_figures: set[str] = set()
    body, nav = [], []

    def add_section(sid, title, html):
        nav.append(f'<a href="#{sid}">{escape(title)}</a>')
        body.append(f'<section id="{sid}"><h2>{escape(title)}</h2>{html}</section>')

    for s in SECTIONS:
        own = set(s.paths)

        def skip(p, own=own):  # a path claimed by another section (deeper than this one's own) is shown there
            return p not in own and p in claimed

        parts = []
        for p in s.paths:
            node = _get(report, p)
            if node is None:
                continue
            inner = render_tree(node, 3, skip=skip, path=p) if isinstance(node, dict) else format_value(node)
            curves = _walk_curves(node, p, skip) if isinstance(node, dict) else ""
            parts.append(f'<div class="part" data-path="{escape(p)}"><h3><code>{escape(p)}</code></h3>'
                         f"{curves}{inner}</div>")
        figs = [f for f in pngs if f not in used_figures and any(fnmatch.fnmatch(f, g) for g in s.figures)]
        used_figures.update(figs)
        if figs and out_dir is not None:  # the pictures first, the numbers below them
            parts.insert(0, '<div class="figs">' + "".join(_figure(out_dir, f) for f in figs) + "</div>")
        add_section(s.id, s.title, "".join(parts) or f'<p class="note">{escape(s.absent)}</p>')

    warnings = _warnings(report)
    add_section("warnings", f"Warnings ({len(warnings)})", "<ul class=warn>" + "".join(
        f"<li>{escape(w)}</li>" for w in warnings) + "</ul>" if warnings else '<p class="note">None.</p>')
    add_section("view3d", "3-D view of the meshing pair", _view_html(view))
    top = {p.split(".")[0] for p in claimed}
    rest = {k: v for k, v in report.items() if k not in top and k not in HEADER_KEYS}
    other = render_tree(rest, 3) if rest else ""
    left = [f for f in pngs if f not in used_figures]
    if left and out_dir is not None:
        other += '<div class="figs">' + "".join(_figure(out_dir, f) for f in left) + "</div>"
    add_section("other", "Other results and files", other + _files_html(report))
    design = json.dumps(report.get("design", {}), indent=2, ensure_ascii=False)
    add_section("design", "Design (input)", f"<details><summary>design file as read (JSON)</summary><pre>"
                f"{escape(design)}</pre></details>")
    design_title = report.get("design", {}).get("title") if isinstance(report.get("design"), dict) else None
    title = str(report.get("title") or design_title or "spiralbevel report")
    return _PAGE.format(title=escape(title), version=escape(str(report.get("spiralbevel_version", ""))),
                        css=_asset("report.css"), nav=" ".join(nav), body="\n".join(body),
                        script=_asset("viewer.js") if view else "")


def _files_html(report: dict) -> str:
    files = report.get("files")
    files = [str(f) for f in files] if isinstance(files, list) else []
    if not files:
        return ""
    return "<h3>Files of this run</h3><p>" + ", ".join(f"<code>{escape(f)}</code>" for f in files) + "</p>"


def _view_html(view: dict | None) -> str:
    if not view:
        return ('<p class="note">No 3-D view: the run wrote no tooth meshes (set <code>output.stl = true</code> in '
                "the design file).</p>")
    data = json.dumps(view).replace("</", "<\\/")
    buttons = "".join(f'<button id="pair-toggle-{m["name"]}" type="button">{m["name"]} on/off</button>'
                      for m in view["members"])
    return (f'<div class="viewer"><canvas id="pair-canvas"></canvas><div class="tools">'
            f'<button id="pair-reset" type="button">Reset view</button><button id="pair-roll" type="button">Roll'
            f'</button>{buttons}<span id="pair-status"></span></div></div>'
            f'<script type="application/json" id="pair-data">{data}</script>')


def _asset(name: str) -> str:
    return resources.files("spiralbevel.io").joinpath("report_assets", name).read_text(encoding="utf-8")


def write_report_html(path, report: dict, out_dir=None, view: dict | None = None) -> None:
    """Write :func:`render_report_html` to ``path`` atomically (whole or not at all)."""
    from .atomic import atomic_write_text

    atomic_write_text(path, render_report_html(report, out_dir, view))


def write_run_report_html(out_dir, report: dict, teeth: dict, shaft_angle: float) -> str:
    """``report.html`` of a run in ``out_dir``; returns its name.

    Parameters
    ----------
    out_dir : path
        The run's directory (figures embedded from it; the tooth STL files, when written, feed the 3-D view).
    report : dict
    teeth : {"pinion": int, "gear": int}
    shaft_angle : float, rad
    """
    from .report_mesh import decimate, view_payload, weld
    from .stl import read_stl

    out_dir = Path(out_dir)
    stl = {m: out_dir / TOOTH_STL.format(member=m) for m in ("pinion", "gear")}
    view = None
    if all(p.is_file() for p in stl.values()):
        meshes = {}
        for m, p in stl.items():
            mesh = read_stl(p)
            meshes[m] = decimate(weld(mesh.vertices[mesh.faces]))
        view = view_payload(meshes, teeth, shaft_angle)
    write_report_html(out_dir / "report.html", report, out_dir, view)
    return "report.html"


_PAGE = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><link rel="icon" href="data:,">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title}: spiralbevel report</title>
<style>{css}</style></head>
<body><header><h1>{title}</h1><p class="meta">spiralbevel {version}. Angles in degrees, lengths in mm, transmission
error in arcseconds unless a column says otherwise.</p><nav>{nav}</nav></header>
<main>
{body}
</main>
<script>{script}</script>
</body></html>
"""
