"""Reading design files: TOML → validated :class:`DesignFile`, every problem reported at once.

Errors are :class:`spiralbevel.errors.DesignError` whose problems name the dotted field path, the value given, the
allowed range (from the schema's constraints) and the unit.

The reader is bounded so that no file can hang it or make it fail with a traceback: at most :data:`MAX_DESIGN_BYTES`
bytes, UTF-8 text (a byte-order mark is allowed; UTF-16, latin-1 and binary files are rejected with the position of the
first bad byte), tables and arrays nested at most :data:`MAX_NESTING` deep, and at most :data:`MAX_PROBLEMS` problems
listed (the rest counted).
"""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path

from pydantic import BaseModel, ValidationError

from ..errors import DesignError, Problem
from .design_schema import DesignFile

__all__ = ["load_design", "parse_design", "validate_design", "read_text_file", "default_design_text", "bundled_designs",
           "DEFAULT_DESIGN_NAME", "MAX_DESIGN_BYTES", "MAX_NESTING", "MAX_PROBLEMS"]

DEFAULT_DESIGN_NAME = "aviation_23x65_logspiral.toml"
#: largest design file read, bytes (the bundled examples are about 3 kB)
MAX_DESIGN_BYTES = 1 << 20
#: deepest nesting of tables and arrays in a design file (the schema needs 3)
MAX_NESTING = 16
#: most problems listed for one file; the rest are counted in a last line
MAX_PROBLEMS = 50


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
    return parse_design(read_text_file(p, "design file", MAX_DESIGN_BYTES), source=str(p))


def read_text_file(path: "str | Path", what: str, max_bytes: int) -> str:
    """Read a UTF-8 text file of at most ``max_bytes`` bytes; every failure is a :class:`DesignError` naming ``what``.

    Parameters
    ----------
    path : str or Path
    what : str
        The name of the input in messages (``"design file"``, ``"--measured"``).
    max_bytes : int
        Size limit, bytes.

    Returns
    -------
    str
        The text, without a UTF-8 byte-order mark.
    """
    p = Path(path)
    if not p.is_file():
        reason = "not a regular file" if p.exists() else "file not found"
        raise DesignError.single(what, str(p), "an existing text file", reason=reason)
    with open(p, "rb") as fh:
        data = fh.read(max_bytes + 1)
    if len(data) > max_bytes:
        raise DesignError.single(what, str(p), f"a file of at most {max_bytes} bytes", reason="file too large")
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise DesignError.single(what, str(p), "UTF-8 text", reason="the file is UTF-16; save it as UTF-8")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise DesignError.single(what, str(p), "UTF-8 text",
                                 reason=f"byte 0x{data[err.start]:02x} at offset {err.start} is not UTF-8 "
                                        "(a latin-1 or binary file?); save it as UTF-8") from None
    if "\x00" in text:
        raise DesignError.single(what, str(p), "UTF-8 text", reason=f"NUL character at offset {text.index(chr(0))} "
                                                                    "(a binary file?)")
    return text


def _nesting_depth(text: str) -> int:
    """Upper bound of the nesting of TOML arrays and inline tables: brackets and braces outside strings and comments,
    counted in one pass (quoted text and comments skipped), so a hostile file never reaches the recursive parser."""
    depth = best = 0
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c in "\"'":
            triple = text.startswith(c * 3, i)
            end = text.find(c * 3 if triple else c, i + (3 if triple else 1))
            while end != -1 and c == '"' and not triple and _escaped(text, end):
                end = text.find(c, end + 1)
            if end == -1:
                return best
            i = end + (3 if triple else 1)
            continue
        if c == "#":
            nl = text.find("\n", i)
            i = n if nl == -1 else nl + 1
            continue
        if c in "[{":
            depth += 1
            best = max(best, depth)
        elif c in "]}":
            depth = max(0, depth - 1)
        i += 1
    return best


def _escaped(text: str, pos: int) -> bool:
    """True when the character at ``pos`` is preceded by an odd number of backslashes."""
    k = pos - 1
    while k >= 0 and text[k] == "\\":
        k -= 1
    return (pos - 1 - k) % 2 == 1


def parse_design(text: str, source: str = "<string>") -> DesignFile:
    """Parse TOML text and validate it.

    Parameters
    ----------
    text : str
        The TOML text (at most :data:`MAX_DESIGN_BYTES` UTF-8 bytes).
    source : str
        The file name shown in messages.

    Returns
    -------
    DesignFile

    Raises
    ------
    DesignError
        Every problem (at most :data:`MAX_PROBLEMS` listed), each naming the design-file key.
    """
    if len(text) > MAX_DESIGN_BYTES:
        raise DesignError.single("design file", source, f"at most {MAX_DESIGN_BYTES} bytes", reason="too large")
    depth = _nesting_depth(text)
    if depth > MAX_NESTING:
        raise DesignError.single("design file", source, f"arrays and tables nested at most {MAX_NESTING} deep",
                                 reason=f"nested {depth} deep")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise DesignError.single("design file", source, "valid TOML", reason=f"malformed TOML: {err}") from err
    except RecursionError:
        raise DesignError.single("design file", source, f"arrays and tables nested at most {MAX_NESTING} deep",
                                 reason="nested too deep") from None
    return validate_design(data)


def validate_design(data: dict) -> DesignFile:
    """Validate a design given as a dict of design-file sections (degrees, mm).

    Raises
    ------
    DesignError
        Every problem (at most :data:`MAX_PROBLEMS` listed), each naming the design-file key.
    """
    try:
        return DesignFile.model_validate(data)
    except ValidationError as err:
        problems: list[Problem] = []
        seen: set[str] = set()
        dropped = 0
        for e in err.errors():
            p = _problem(e)
            if p.field in seen:          # a union (e.g. 'approach' or a number) reports once per member
                continue
            seen.add(p.field)
            if len(problems) < MAX_PROBLEMS:
                problems.append(p)
            else:
                dropped += 1
        if dropped:
            problems.append(Problem("", None, reason=f"... and {dropped} more problem(s) not listed"))
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
    if len(field) > 80:
        field = field[:80] + "..."
    info = _field_info(loc)
    unit = ""
    allowed = ""
    if info is not None:
        extra = info.json_schema_extra or {}
        unit = extra.get("unit", "") if isinstance(extra, dict) else ""
        allowed = _allowed(info)
    kind = e.get("type", "")
    if kind == "extra_forbidden":
        return Problem(field, _short(e.get("input")), "", "", "unknown key; check the spelling")
    if kind == "missing":
        return Problem(field, "<missing>", allowed, unit, "required")
    msg = e.get("msg", "")
    msg = msg.removeprefix("Value error, ")
    value = _short(e.get("input"))
    if isinstance(value, dict):                # a rule across fields of a section: the message names them
        value = "(section)"
    if kind in ("literal_error", "float_parsing", "float_type") and len(e["loc"]) > len(loc):
        msg = "expected one of the allowed forms"
        allowed = allowed or _union_allowed(loc)
    elif kind in ("float_parsing", "int_parsing") and isinstance(value, str) and unit not in ("", "-"):
        # "5 mm", "30mm": a design file holds bare numbers, each key in its unit
        msg = f"write a bare number without quotes or unit: {field} is in {unit}"
    return Problem(field, value, allowed, unit, msg)


def _short(value):
    """A value as shown in a message: long strings and containers cut to about 60 characters."""
    if isinstance(value, (str, list, tuple)) and len(value) > 60:
        text = value if isinstance(value, str) else repr(value)
        return text[:60] + f"... ({len(value)} {'characters' if isinstance(value, str) else 'items'})"
    return value


def _union_allowed(loc) -> str:
    """Allowed forms of a union-typed field, from its description."""
    info = _field_info(loc)
    return (info.description or "") if info is not None else ""
