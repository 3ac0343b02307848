"""Library problems restated for the user: design-file paths, angles in degrees.

The computational layers name their own parameters (``boundaries[pinion].root_angle``, ``eta``) in rad; the job
knows which design-file field each comes from.
"""

from __future__ import annotations

import math
import re

from ..errors import DesignError, Problem

# a number standing alone (not the digit of a name such as "k1" or "delta2"), and "pi" or "pi/2" as whole words only
_NUM = re.compile(r"(?<![\w.])[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?(?![\w.])")
_PI = re.compile(r"\bpi(/2)?\b")


def _deg_text(text: str) -> str:
    """Numbers in an allowed-range text, read as rad, rewritten in degrees ("pi/2" and "pi" as words too; "pitch
    angle" stays as it is)."""
    text = _PI.sub(lambda m: "\x00" if m.group(1) else "\x01", text)
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


def with_design_keys(err: DesignError, section: str, context: str = "") -> DesignError:
    """A DesignError whose every problem names a design-file key: a field that is not already a dotted path into the
    design file (``grid(face station)``, ``locate(axial, radius)``: names of the computational layers) is shown as
    ``section (field, context)``, ``section`` being the design-file section that controls it."""
    from ..io.design_schema import DesignFile

    heads = set(DesignFile.model_fields) | {"design file", "-o/--out"}
    out, changed = [], False
    for p in err.problems:
        head = p.field.split(".", 1)[0].split(" ", 1)[0].split(":", 1)[0]
        if p.field and head not in heads and not p.field.startswith("--"):
            extra = f", {context}" if context else ""
            out.append(Problem(f"{section} ({p.field}{extra})", p.value, p.allowed, p.unit, p.reason))
            changed = True
        else:
            out.append(p)
    return type(err)(out) if changed else err
