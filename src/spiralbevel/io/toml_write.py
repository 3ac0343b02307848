"""A small TOML writer for design files (tables, strings, numbers, booleans and arrays of them): what ``tomllib``
reads back unchanged. Floats are written with ``repr``, so they round-trip exactly."""

from __future__ import annotations

import json
import math

__all__ = ["dumps_toml"]


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)  # a JSON string is a TOML basic string
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def _key(k: str) -> str:
    return k if k and all(c.isalnum() or c in "_-" for c in k) else json.dumps(k, ensure_ascii=False)


def dumps_toml(data: dict, header: str = "") -> str:
    """TOML text of a nested dict.

    Parameters
    ----------
    data : dict
        Keys are strings; values are bool, int, float, str, lists of these, or dicts (written as tables).
    header : str
        Comment lines written first (each prefixed with ``# ``).

    Returns
    -------
    str
    """
    lines = [f"# {ln}".rstrip() for ln in header.splitlines()]

    def table(d: dict, path: list[str]) -> None:
        scalars = {k: v for k, v in d.items() if not isinstance(v, dict)}
        tables = {k: v for k, v in d.items() if isinstance(v, dict)}
        if path and (scalars or not tables):
            lines.append("")
            lines.append("[" + ".".join(_key(p) for p in path) + "]")
        for k, v in scalars.items():
            lines.append(f"{_key(k)} = {_value(v)}")
        for k, v in tables.items():
            table(v, [*path, k])

    table(data, [])
    return "\n".join(lines).lstrip("\n") + "\n"
