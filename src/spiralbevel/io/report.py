"""``report.json``: every computed quantity with units, written atomically.

Values are plain JSON: floats, lists, dicts. Units are part of the names (``_mm``, ``_deg``, ``_arcsec``,
``_N_per_mm2``, ``_N_m``; dimensionless names bare), angles in degrees; the JSON Schema shipped with the package
(:func:`report_schema`) states the layout. numpy scalars and arrays are converted. JSON has no NaN: a value that
does not exist (for example the TE of a tooth pair at a position where it has no contact) is written as ``null``;
infinities (the contact ellipse of a line contact) likewise.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

__all__ = ["to_jsonable", "dumps_report", "write_report", "report_schema"]


def to_jsonable(obj):
    """Convert numpy types, tuples, enums and dataclass-like objects into JSON-ready Python objects."""
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return to_jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        value = float(obj)
        return value if math.isfinite(value) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, (np.bool_,)):
        return bool(obj)
    if hasattr(obj, "value") and hasattr(obj, "name") and not isinstance(obj, (str, int)):
        return obj.value  # Enum
    if isinstance(obj, Path):
        return str(obj)
    return obj


def dumps_report(report: dict) -> str:
    """Serialize a report dict to indented JSON text."""
    return json.dumps(to_jsonable(report), indent=2, ensure_ascii=False, allow_nan=False) + "\n"


def write_report(path, report: dict) -> None:
    """Write ``report`` to ``path`` atomically (whole or not at all)."""
    from .atomic import atomic_write_text

    atomic_write_text(path, dumps_report(report))


def report_schema() -> dict:
    """The JSON Schema (draft 2020-12) of report.json, shipped as ``spiralbevel/data/report.schema.json``."""
    from importlib import resources

    return json.loads(resources.files("spiralbevel.data").joinpath("report.schema.json").read_text(encoding="utf-8"))
