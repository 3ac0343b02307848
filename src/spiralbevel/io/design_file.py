"""Reading design files: TOML → validated :class:`DesignFile`, every problem reported at once.

Errors are :class:`spiralbevel.errors.DesignError` whose problems name the dotted field path, the value given, the
allowed range (from the schema's constraints) and the unit.
"""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path

from pydantic import BaseModel, ValidationError

from ..errors import DesignError, Problem
from .design_schema import DesignFile

__all__ = ["load_design", "parse_design", "default_design_text", "bundled_designs", "DEFAULT_DESIGN_NAME"]

DEFAULT_DESIGN_NAME = "aviation_23x65_logspiral.toml"


def default_design_text(name: str = DEFAULT_DESIGN_NAME) -> str:
    """Text of a design bundled in ``spiralbevel/data``."""
    return resources.files("spiralbevel.data").joinpath(name).read_text(encoding="utf-8")


def bundled_designs() -> dict:
    """{name: path} of the example designs bundled in ``spiralbevel/data`` (name = file stem)."""
    root = resources.files("spiralbevel.data")
    return {Path(str(p)).stem: Path(str(p)) for p in sorted(root.iterdir(), key=lambda q: str(q))
            if str(p).endswith(".toml")}


def load_design(path: "str | Path | None" = None) -> DesignFile:
    """Read and validate a TOML design file; ``None`` loads the bundled default design."""
    if path is None:
        return parse_design(default_design_text(), source="<bundled default>")
    p = Path(path)
    if not p.is_file():
        raise DesignError.single("design file", str(p), "an existing TOML file", reason="file not found")
    return parse_design(p.read_text(encoding="utf-8"), source=str(p))


def parse_design(text: str, source: str = "<string>") -> DesignFile:
    """Parse TOML text and validate it."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise DesignError.single("design file", source, "valid TOML", reason=f"malformed TOML: {err}") from err
    try:
        return DesignFile.model_validate(data)
    except ValidationError as err:
        problems, seen = [], set()
        for e in err.errors():
            p = _problem(e)
            if p.field not in seen:          # a union (e.g. 'approach' or a number) reports once per member
                seen.add(p.field)
                problems.append(p)
        raise DesignError(problems) from err


def _field_info(loc):
    """The pydantic FieldInfo at a location, or None."""
    model: type[BaseModel] | None = DesignFile
    info = None
    for key in loc:
        if model is None or not isinstance(key, str) or key not in model.model_fields:
            return info if isinstance(key, int) else None
        info = model.model_fields[key]
        model = _model_of(info.annotation)
    return info


def _model_of(ann):
    """The BaseModel class inside an annotation (plain, Optional[...] or Union[...]), or None."""
    if isinstance(ann, type) and issubclass(ann, BaseModel):
        return ann
    for arg in getattr(ann, "__args__", ()) or ():
        if isinstance(arg, type) and issubclass(arg, BaseModel):
            return arg
    return None


def _allowed(info) -> str:
    parts = []
    for meta in getattr(info, "metadata", []):
        for name, sym in (("gt", ">"), ("ge", ">="), ("lt", "<"), ("le", "<=")):
            v = getattr(meta, name, None)
            if v is not None:
                parts.append(f"{sym} {v}")
    return "value " + " and ".join(parts) if parts else ""


def _problem(e) -> Problem:
    # drop pydantic's validator and union-member tags from the location (function-..., literal[...], float, int)
    loc = tuple(k for k in e["loc"] if not (isinstance(k, str) and (k.startswith("function-") or "[" in k
                                                                     or k in ("float", "int", "str", "bool"))))
    field = ".".join(str(k) for k in loc) or "design"
    info = _field_info(loc)
    unit = ""
    allowed = ""
    if info is not None:
        extra = info.json_schema_extra or {}
        unit = extra.get("unit", "") if isinstance(extra, dict) else ""
        allowed = _allowed(info)
    kind = e.get("type", "")
    if kind == "extra_forbidden":
        return Problem(field, e.get("input"), "", "", "unknown key; check the spelling")
    if kind == "missing":
        return Problem(field, "<missing>", allowed, unit, "required")
    msg = e.get("msg", "")
    msg = msg.removeprefix("Value error, ")
    value = e.get("input")
    if isinstance(value, dict):                # a rule across fields of a section: the message names them
        value = "(section)"
    if kind in ("literal_error", "float_parsing", "float_type") and len(e["loc"]) > len(loc):
        msg = "expected one of the allowed forms"
        allowed = allowed or _union_allowed(loc)
    return Problem(field, value, allowed, unit, msg)


def _union_allowed(loc) -> str:
    """Allowed forms of a union-typed field, from its description."""
    info = _field_info(loc)
    return (info.description or "") if info is not None else ""
