"""Angles at the boundary: degrees or DMS strings in files, CLI and reports; radians inside.

Accepted forms (all in degrees): ``30``, ``22.5``, ``"22.5"``, ``"22°30'"``, ``"59°20'07\""``, ``"59°20′07″"``,
``"59 20 7"``, ``"22d30m"``, ``"-1°20'"``. Minutes and seconds must be below 60.
"""

from __future__ import annotations

import math
import re

__all__ = ["parse_angle_deg", "format_dms", "deg", "rad"]

_DMS = re.compile(
    r"""^\s*(?P<sign>[-+−])?\s*(?P<d>\d+(?:\.\d*)?)\s*(?:°|d|deg|\s)?\s*
        (?:(?P<m>\d+(?:\.\d*)?)\s*(?:'|′|m|min|\s)?\s*)?
        (?:(?P<s>\d+(?:\.\d*)?)\s*(?:"|″|''|s|sec)?\s*)?$""",
    re.VERBOSE,
)


def parse_angle_deg(value) -> float:
    """Parse an angle given in degrees (number or DMS string) and return degrees as float.

    Raises
    ------
    ValueError
        With a message that says which forms are accepted.
    """
    if isinstance(value, bool):
        raise ValueError("an angle must be a number of degrees or a DMS string such as \"22°30'\"")
    if isinstance(value, (int, float)):
        if not math.isfinite(value):
            raise ValueError("an angle must be finite")
        return float(value)
    if not isinstance(value, str):
        raise ValueError("an angle must be a number of degrees or a DMS string such as \"22°30'\"")
    text = value.strip()
    try:
        return float(text)
    except ValueError:
        pass
    match = _DMS.match(text)
    if not match or not text:
        raise ValueError(f"cannot read {value!r} as an angle: use degrees (22.5) or DMS (\"22°30'\", \"59 20 7\")")
    d = float(match["d"])
    m = float(match["m"]) if match["m"] else 0.0
    s = float(match["s"]) if match["s"] else 0.0
    if m >= 60 or s >= 60:
        raise ValueError(f"cannot read {value!r} as an angle: minutes and seconds must be below 60")
    out = d + m / 60.0 + s / 3600.0
    return -out if match["sign"] in ("-", "−") else out


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
