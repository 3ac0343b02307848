"""Angles at the boundary: degrees or DMS strings in files, CLI and reports; radians inside.

Accepted forms (all in degrees): ``30``, ``22.5``, ``"22.5"``, ``"2.25e1"``, ``"22°30'"``, ``"59°20'07\""``,
``"59°20′07″"``, ``"59 20 7"``, ``"22d30m"``, ``"-1°20'"``. Minutes and seconds must be below 60; only the last
component of a DMS string may have a fraction (``"22.5 30"`` and ``"22.5.5"`` are rejected, not guessed).

The parser is a hand-written scanner over at most :data:`MAX_ANGLE_TEXT` characters (no backtracking regular
expression), so any input, however long or malformed, is answered in time linear in its length.
"""

from __future__ import annotations

import math
import re

__all__ = ["parse_angle_deg", "format_dms", "deg", "rad", "MAX_ANGLE_TEXT"]

#: longest angle text read; anything longer is rejected before it is scanned
MAX_ANGLE_TEXT = 64

_DIGITS = frozenset("0123456789")
_FORMS = "use degrees (22.5) or DMS (\"22°30'\", \"59°20'07\\\"\", \"59 20 7\")"
# a plain decimal number: one optional sign, digits, an optional fraction, an optional exponent (no nested repeats)
_NUMBER = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
# unit marks of the three DMS slots, longest first so that "''" is read before "'"
_UNITS = (("deg", 0), ("°", 0), ("d", 0), ("min", 1), ("′", 1), ("m", 1), ("''", 2), ("'", 1), ("sec", 2),
          ("″", 2), ('"', 2), ("s", 2))


def _bad(value, why: str = "") -> ValueError:
    shown = value if len(value) <= 40 else value[:40] + f"... ({len(value)} characters)"
    return ValueError(f"cannot read {shown!r} as an angle{': ' + why if why else ''}; {_FORMS}")


def _scan_dms(text: str, original: str) -> float:
    """Sign, then up to three (number, optional unit) components for degrees, minutes and seconds."""
    i, n = 0, len(text)
    sign = 1.0
    if i < n and text[i] in "+-−":
        sign = -1.0 if text[i] in "-−" else 1.0
        i += 1
    while i < n and text[i].isspace():
        i += 1
    values = [0.0, 0.0, 0.0]
    slot = 0
    count = 0
    fractional = False
    while i < n:
        if slot > 2:
            raise _bad(original, "more than degrees, minutes and seconds")
        if fractional:
            raise _bad(original, "only the last component may have a fraction")
        start = i
        while i < n and text[i] in _DIGITS:
            i += 1
        if i < n and text[i] == ".":
            i += 1
            fractional = True
            while i < n and text[i] in _DIGITS:
                i += 1
        digits = text[start:i]
        if not digits.strip(".") or digits.count(".") > 1:
            raise _bad(original)
        spaced = i < n and text[i].isspace()
        while i < n and text[i].isspace():
            i += 1
        unit_slot = None
        for mark, s in _UNITS:
            if text.startswith(mark, i):
                unit_slot = s
                i += len(mark)
                break
        if unit_slot is None:
            if i < n and not spaced:
                raise _bad(original)
            unit_slot = slot
        elif unit_slot < slot:
            raise _bad(original, "degrees, minutes and seconds out of order")
        values[unit_slot] = float(digits)
        slot = unit_slot + 1
        count += 1
        while i < n and text[i].isspace():
            i += 1
    if count == 0:
        raise _bad(original)
    deg, mins, secs = values
    if mins >= 60 or secs >= 60:
        raise _bad(original, "minutes and seconds must be below 60")
    return sign * (deg + mins / 60.0 + secs / 3600.0)


def parse_angle_deg(value) -> float:
    """Parse an angle given in degrees (number or DMS string) and return degrees.

    Parameters
    ----------
    value : float, int or str
        A finite number of degrees, or a string in one of the accepted forms (module docstring).

    Returns
    -------
    float, deg

    Raises
    ------
    ValueError
        With a message that says which forms are accepted; also for a string longer than :data:`MAX_ANGLE_TEXT`
        characters, a non-finite number, or ambiguous text such as ``"22.5.5"``.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ValueError("an angle must be a number of degrees or a DMS string such as \"22°30'\"")
    if isinstance(value, (int, float)):
        if not math.isfinite(value):
            raise ValueError("an angle must be finite")
        return float(value)
    if len(value) > MAX_ANGLE_TEXT:
        raise _bad(value, f"longer than {MAX_ANGLE_TEXT} characters")
    text = value.strip()
    if not text:
        raise _bad(value, "empty")
    if _NUMBER.fullmatch(text):
        out = float(text)
        if not math.isfinite(out):
            raise _bad(value, "not finite")
        return out
    return _scan_dms(text, value)


def format_dms(degrees: float, seconds_decimals: int = 0) -> str:
    """Format degrees as ``D°MM'SS"`` (shop-floor style), e.g. ``59°20'07"``."""
    sign = "-" if degrees < 0 else ""
    total = round(abs(degrees) * 3600.0, seconds_decimals)
    d = int(total // 3600)
    m = int((total - 3600 * d) // 60)
    s = total - 3600 * d - 60 * m
    sec = f"{s:0{3 + seconds_decimals if seconds_decimals else 2}.{seconds_decimals}f}"
    return f"{sign}{d}°{m:02d}'{sec}\""


def deg(radians):
    """Radians → degrees (works on arrays)."""
    return radians * (180.0 / math.pi)


def rad(degrees):
    """Degrees → radians (works on arrays)."""
    return degrees * (math.pi / 180.0)
