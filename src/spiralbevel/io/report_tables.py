"""Generic HTML of ``report.json`` content: tables from dicts and lists, units from the key names.

Nothing here knows a section's keys. A key's unit comes from its suffix (``_mm``, ``_deg``, ``_arcsec``,
``_N_per_mm2``, ...) or from a ``units`` mapping beside it or above it; a ``descriptions`` mapping gives a third column.
Sibling dicts with the same keys (pinion and gear, convex and concave, the misalignment cases) become the columns of
one table; a trailing member digit (``z1``, ``z2``) is dropped for that comparison.
"""

from __future__ import annotations

import json
import math
import re
from html import escape

__all__ = ["unit_of", "label_of", "format_value", "render_tree", "is_scalar"]

#: key suffix -> unit shown; longest first (``_N_per_mm2`` before ``_mm2`` before ``_mm``)
UNIT_SUFFIXES = (("_N_per_mm2", "N/mm²"), ("_per_mm", "1/mm"), ("_arcsec", "″"), ("_deg", "°"),
                 ("_mm_per_rad", "mm/rad"), ("_per_rad", "1/rad"), ("_rad", "rad"),
                 ("_mm2", "mm²"), ("_mm3", "mm³"), ("_mm", "mm"), ("_um", "µm"), ("_N_m", "N m"), ("_Nm", "N m"),
                 ("_N", "N"), ("_m_per_s", "m/s"), ("_per_min", "1/min"),
                 ("_s", "s"), ("_percent", "%"))
_DIGIT = re.compile(r"(?<=[A-Za-z_])[12]$")
#: keys that hold metadata of their siblings, not results
META_KEYS = ("units", "descriptions")


def unit_of(key: str, units: dict | None = None) -> tuple[str, str]:
    """(label, unit) of a key: the unit from a ``units`` mapping or from the name suffix (then cut from the label)."""
    if units and isinstance(units.get(key), str):
        return key, units[key]
    for suffix, unit in UNIT_SUFFIXES:
        if key.endswith(suffix) and len(key) > len(suffix):
            return key[: -len(suffix)], unit
    return key, ""


def label_of(key: str) -> str:
    """Heading text of a key: underscores and hyphens to spaces, first letter up."""
    text = key.replace("_", " ").replace("-", " – ") if "-" in key and "_" not in key else key.replace("_", " ")
    return text[:1].upper() + text[1:]


def is_scalar(v) -> bool:
    return v is None or isinstance(v, (str, int, float, bool))


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def format_value(v) -> str:
    """HTML text of a scalar or short list."""
    if v is None:
        return "—"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.6g}" if math.isfinite(v) else str(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return escape(v)
    if isinstance(v, list) and all(_is_number(x) or x is None for x in v):
        if not v:
            return "—"
        if len(v) <= 8:
            return ", ".join(format_value(x) for x in v)
        nums = [x for x in v if x is not None]
        rng = f": {format_value(min(nums))} … {format_value(max(nums))}" if nums else ""
        return f"{len(v)} values{rng}"
    return escape(json.dumps(v)[:200])


def _norm(key: str) -> str:
    return _DIGIT.sub("", key)


def _scalar_like(v) -> bool:
    return is_scalar(v) or (isinstance(v, list) and all(_is_number(x) or x is None for x in v))


def _ctx(d: dict, ctx: dict) -> dict:
    out = {"units": dict(ctx.get("units", {})), "descriptions": dict(ctx.get("descriptions", {}))}
    for k in META_KEYS:
        if isinstance(d.get(k), dict):
            out[k].update({str(a): b for a, b in d[k].items() if isinstance(b, str)})
    return out


def _scalar_table(items: list[tuple[str, object]], ctx: dict) -> str:
    desc = ctx.get("descriptions", {})
    has_desc = any(k in desc for k, _ in items)
    rows = []
    for k, v in items:
        label, unit = unit_of(k, ctx.get("units"))
        cells = f"<td><code>{escape(label)}</code></td><td class=num>{format_value(v)}</td><td>{escape(unit)}</td>"
        if has_desc:
            cells += f"<td>{escape(desc.get(k, ''))}</td>"
        rows.append(f"<tr>{cells}</tr>")
    head = "<tr><th>name</th><th>value</th><th>unit</th>" + ("<th>description</th>" if has_desc else "") + "</tr>"
    return f'<table class="kv"><thead>{head}</thead><tbody>{"".join(rows)}</tbody></table>'


def _columns_table(group: dict, ctx: dict) -> str:
    """One table, one column per sibling dict; rows are their (digit-normalized) scalar keys."""
    names = list(group)
    rows: dict[str, dict] = {}
    keys: dict[str, str] = {}
    for name, d in group.items():
        for k, v in d.items():
            if k not in META_KEYS and _scalar_like(v):
                rows.setdefault(_norm(k), {})[name] = v
                keys.setdefault(_norm(k), k)
    desc = ctx.get("descriptions", {})
    has_desc = any(keys[n] in desc for n in rows)
    head = "<tr><th>name</th>" + "".join(f"<th>{escape(label_of(n))}</th>" for n in names) + "<th>unit</th>" + (
        "<th>description</th>" if has_desc else "") + "</tr>"
    body = []
    for n, vals in rows.items():
        label, unit = unit_of(keys[n], ctx.get("units"))
        label = _norm(label)
        cells = "".join(f"<td class=num>{format_value(vals.get(c))}</td>" for c in names)
        d = desc.get(keys[n], "")
        for suffix in (", pinion", ", wheel", ", gear"):
            d = d.removesuffix(suffix)
        body.append(f"<tr><td><code>{escape(label)}</code></td>{cells}<td>{escape(unit)}</td>"
                    + (f"<td>{escape(d)}</td>" if has_desc else "") + "</tr>")
    return f'<table class="kv"><thead>{head}</thead><tbody>{"".join(body)}</tbody></table>'


def _list_table(rows: list, ctx: dict) -> str:
    if all(isinstance(r, dict) for r in rows):
        cols: list[str] = []
        for r in rows:
            cols += [k for k in r if k not in cols]
        head = "".join(f"<th>{escape(unit_of(c)[0])}{' [' + escape(unit_of(c)[1]) + ']' if unit_of(c)[1] else ''}"
                       "</th>" for c in cols)
        body = "".join("<tr>" + "".join(f"<td class=num>{format_value(r.get(c))}</td>" for c in cols) + "</tr>"
                       for r in rows)
        return f'<table class="grid"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'
    if all(isinstance(r, list) for r in rows):  # a sheet: each row a list of cells
        body = "".join("<tr>" + "".join(f"<td>{format_value(c)}</td>" for c in r) + "</tr>" for r in rows)
        return f'<table class="grid">{body}</table>'
    if all(isinstance(r, str) for r in rows):
        return "<ul>" + "".join(f"<li>{escape(r)}</li>" for r in rows) + "</ul>"
    return f"<pre>{escape(json.dumps(rows, indent=1)[:4000])}</pre>"


def render_tree(d: dict, depth: int = 3, ctx: dict | None = None, skip=lambda key: False, path: str = "") -> str:
    """HTML of a report dict: its scalars in one table, its sub-dicts as sub-headings (``<details>`` when deep).

    Parameters
    ----------
    d : dict
    depth : int
        Heading level of the sub-dicts (3 = ``<h3>``); past 6 they fold into ``<details>``.
    ctx : dict, optional
        ``units`` and ``descriptions`` inherited from above.
    skip : callable
        ``skip(dotted_path)`` true for the paths shown elsewhere in the page.
    path : str
        Dotted path of ``d`` in the report.
    """
    ctx = _ctx(d, ctx or {})
    parts = []
    if d.get("status") == "failed":
        parts.append(f'<p class="bad">Failed: {escape(str(d.get("reason", "")))}</p>')
    items = [(k, v) for k, v in d.items() if k not in META_KEYS and not skip(_join(path, k))]
    for k in META_KEYS:  # a units text (not a mapping) is a note for the whole dict
        if isinstance(d.get(k), str):
            parts.append(f'<p class="note">{escape(k)}: {escape(d[k])}</p>')
    scalars = [(k, v) for k, v in items if _scalar_like(v)]
    if scalars:
        parts.append(_scalar_table(scalars, ctx))
    subs = [(k, v) for k, v in items if isinstance(v, dict)]
    groups: dict[frozenset, dict] = {}
    for k, v in subs:
        keys = frozenset(_norm(a) for a, b in v.items() if a not in META_KEYS and _scalar_like(b))
        if keys:
            groups.setdefault(keys, {})[k] = v
    merged = {k for g in groups.values() if len(g) > 1 for k in g}
    for g in groups.values():
        if len(g) > 1:
            parts.append(_heading(" / ".join(label_of(k) for k in g), depth, _columns_table(g, ctx)))
    for k, v in subs:  # the scalars of merged siblings are in their common table; the rest under their own name
        rest = {a: b for a, b in v.items() if not _scalar_like(b)} if k in merged else v
        parts.append(_heading(label_of(k), depth, render_tree(rest, depth + 1, ctx, skip, _join(path, k))))
    for k, v in items:
        if isinstance(v, list) and not _scalar_like(v) and v:
            parts.append(_heading(label_of(k), depth, _list_table(v, ctx)))
    return "".join(parts)


def _join(path: str, key: str) -> str:
    return f"{path}.{key}" if path else key


def _heading(title: str, depth: int, body: str) -> str:
    if not body:
        return ""
    if depth <= 6:
        return f"<h{depth}>{escape(title)}</h{depth}>{body}"
    return f"<details><summary>{escape(title)}</summary>{body}</details>"
