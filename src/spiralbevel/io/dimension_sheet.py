"""Dimension sheet of a bevel blank: rows for reports and a JSON structure (formatting only, no computation).

Angles are shown in degrees and lengths in mm; the conversion from the internal radians happens here, at the I/O
boundary (``docs/conventions.md``).

JSON layout of :func:`dimension_sheet_json`::

    {
      "method": "ISO 23509 Method 0, face milling, no offset",   # or "... Method 1 (Gleason) ..." for a != 0
      "pair":   {"u": ..., "Sigma": ..., "Rm": ..., "mmn": ..., "hmw": ..., ...},   # shared quantities
      "pinion": {"z1": ..., "delta1": ..., "Re1": ..., ...},                      # symbols ending in 1
      "gear":   {"z2": ..., "delta2": ..., "Re2": ..., ...},                      # symbols ending in 2
      "units":  {"delta1": "deg", "Re1": "mm", "u": "-", ...},                    # every symbol
      "descriptions": {"delta1": "pitch angle, pinion", ...},
      "warnings": ["face width b2 = ... exceeds ...", ...]
    }

Keys are the ISO 23509 symbols in ASCII (the attribute names of ``BevelBlank``); angles in degrees; a value that is
not finite (e.g. the virtual diameter of a crown gear, δ2 = 90°) is written as ``null``.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["dimension_sheet_rows", "dimension_sheet_json", "format_dimension_sheet"]

Value = Any  # float, int or str


def _json_value(v: Any) -> Any:
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def dimension_sheet_rows(blank) -> list[tuple[str, str, str, Value, Value]]:
    """Rows ``(symbol, description, unit, pinion value, gear value)`` in display units (deg, mm).

    Parameters
    ----------
    blank : BevelBlank
        Result of :func:`spiralbevel.design.blank.compute_blank`.

    Returns
    -------
    list of tuple
        One row per quantity in the order of ``blank_meta.QUANTITIES``. Member quantities use the base symbol
        (``"delta"`` for δ1, δ2); quantities common to the pair (``"Sigma"``, ``"mmn"``, ``"hmw"`` ...) show the same
        value in both columns. The pair row ``Rm`` is omitted because the ``Rm`` member row shows Rm1 and Rm2.
    """
    from ..design.blank_meta import QUANTITIES, unit_of

    values = blank.to_dict(degrees=True)
    member_bases = {base for base, _d, _k, scope in QUANTITIES if scope == "member"}
    rows: list[tuple[str, str, str, Value, Value]] = []
    for base, desc, kind, scope in QUANTITIES:
        unit = unit_of(kind, degrees=True)
        if scope == "member":
            rows.append((base, desc, unit, values[base + "1"], values[base + "2"]))
        elif base not in member_bases:
            rows.append((base, desc, unit, values[base], values[base]))
    return rows


def dimension_sheet_json(blank) -> dict[str, Any]:
    """JSON-ready dictionary of the blank, keyed by ISO symbol, angles in degrees (layout in the module docstring).

    Parameters
    ----------
    blank : BevelBlank
        Result of :func:`spiralbevel.design.blank.compute_blank`.

    Returns
    -------
    dict
        ``{"method", "pair", "pinion", "gear", "units", "descriptions", "warnings"}``.
    """
    from ..design.blank_meta import QUANTITIES

    values = blank.to_dict(degrees=True)
    meta = {sym: (desc, unit) for sym, desc, unit in blank.metadata(degrees=True)}
    method = ("ISO 23509 Method 0, face milling, no offset" if blank.a == 0.0
              else "ISO 23509 Method 1 (Gleason), face milling, hypoid offset")
    out: dict[str, Any] = {"method": method, "pair": {}, "pinion": {},
                           "gear": {}, "units": {}, "descriptions": {}, "warnings": list(blank.warnings)}
    for base, _desc, _kind, scope in QUANTITIES:
        names = [(base, "pair")] if scope == "pair" else [(base + "1", "pinion"), (base + "2", "gear")]
        for sym, group in names:
            out[group][sym] = _json_value(values[sym])
            out["descriptions"][sym], out["units"][sym] = meta[sym]
    return out


def _fmt(v: Value, unit: str) -> str:
    if isinstance(v, str) or isinstance(v, int):
        return str(v)
    if not math.isfinite(v):
        return "-"
    return f"{v:.4f}" if unit == "deg" else f"{v:.3f}"


def format_dimension_sheet(blank) -> str:
    """Plain-text dimension sheet: one line per row of :func:`dimension_sheet_rows`, then the warnings.

    Parameters
    ----------
    blank : BevelBlank
        Result of :func:`spiralbevel.design.blank.compute_blank`.

    Returns
    -------
    str
        Fixed-width table (angles in decimal degrees to 4 places, lengths in mm to 3 places).
    """
    rows = dimension_sheet_rows(blank)
    w_sym = max(len(r[0]) for r in rows)
    w_desc = max(len(r[1]) for r in rows)
    head = f"{'symbol':<{w_sym}}  {'quantity':<{w_desc}}  {'unit':<4}  {'pinion':>12}  {'gear':>12}"
    lines = [head, "-" * len(head)]
    for sym, desc, unit, p, g in rows:
        lines.append(f"{sym:<{w_sym}}  {desc:<{w_desc}}  {unit:<4}  {_fmt(p, unit):>12}  {_fmt(g, unit):>12}")
    if blank.warnings:
        lines.append("")
        lines.extend(f"warning: {w}" for w in blank.warnings)
    return "\n".join(lines)
