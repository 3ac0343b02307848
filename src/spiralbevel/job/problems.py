"""Library problems restated for the user: design-file paths, angles in degrees.

The computational layers name their own parameters (``boundaries[pinion].root_angle``, ``eta``) in rad; the job
knows which design-file field each comes from.
"""

from __future__ import annotations

import math
import re

from ..errors import DesignError, Problem

_NUM = re.compile(r"[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")


def _deg_text(text: str) -> str:
    """Numbers in an allowed-range text, read as rad, rewritten in degrees ("pi/2" too)."""
    # "pi" only as a word: "pitch angle" in an allowed text stays as it is
    text = re.sub(r"\bpi/2\b", "\x00", text)
    text = re.sub(r"\bpi\b", "\x01", text)
    text = _NUM.sub(lambda m: f"{math.degrees(float(m.group())):.6g}", text)
    return text.replace("\x00", "90").replace("\x01", "180")


def restated(err: DesignError, paths: dict, default: str | None = None) -> DesignError:
    """A DesignError of the same type with fields renamed by ``paths`` (exact name, or a prefix ending in '.'),
    values and ranges in rad converted to degrees, and unknown fields prefixed by ``default``."""
    out = []
    for p in err.problems:
        field = p.field
        new = paths.get(field)
        if new is None:
            for k, v in paths.items():
                if k.endswith(".") and field.startswith(k):
                    new = v + field[len(k) - 1:]
                    break
        if new is None:
            new = f"{default} ({field})" if default and field else field
        value, allowed, unit = p.value, p.allowed, p.unit
        if unit == "rad":
            try:
                value = round(math.degrees(float(value)), 6)
            except (TypeError, ValueError):
                pass
            allowed = _deg_text(allowed) if allowed else allowed
            unit = "deg"
        out.append(Problem(new, value, allowed, unit, p.reason))
    return type(err)(out)
