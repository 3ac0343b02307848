"""Exception hierarchy and warning classes of spiralbevel.

Every error raised on bad user input is a :class:`DesignError`; its message names the parameter (a dotted path where
it comes from a design file), the offending value, the allowed range and the unit. Solvers raise
:class:`ConvergenceError` (never return NaN silently) and contact solvers :class:`NoContactError`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = [
    "SpiralBevelError",
    "DesignError",
    "Problem",
    "GeometryError",
    "ConvergenceError",
    "NoContactError",
    "MissingDependencyError",
    "SpiralBevelWarning",
    "DesignWarning",
    "PartialResultWarning",
    "CacheWarning",
]


class SpiralBevelError(Exception):
    """Base class of every error raised by spiralbevel."""


@dataclass(frozen=True)
class Problem:
    """One problem with an input value.

    Parameters
    ----------
    field : str
        Dotted path of the input (``"gear_set.spiral_angle"``) or a parameter name.
    value : Any
        The offending value, as given.
    allowed : str
        The allowed range or set of values, in words (``"0 < value < 90"``).
    unit : str
        Unit of the value (``"deg"``, ``"mm"``, ``"-"`` for dimensionless).
    reason : str
        Optional extra explanation.
    """

    field: str
    value: Any
    allowed: str = ""
    unit: str = ""
    reason: str = ""

    def __str__(self) -> str:
        if not self.field:
            return self.reason
        unit = f" {self.unit}" if self.unit and self.unit != "-" else ""
        # a quoted value is shown as given ('5 mm', '<missing>'), without the key's unit after it
        quoted = isinstance(self.value, str)
        text = f"{self.field} = {self.value!r}{'' if quoted else unit}"
        tail = ""
        if self.allowed:
            # the unit follows a numeric range ("< 60 deg"), not a sentence
            tail = unit if any(ch.isdigit() for ch in self.allowed) else ""
            text += f": allowed {self.allowed}{tail}"
        reason = self.reason
        if quoted and unit and not tail:     # the unit is said once: with the range, else with the reason
            reason = f"{reason}; in {self.unit}" if reason else f"in {self.unit}"
        if reason:
            text += f" ({reason})"
        return text


class DesignError(SpiralBevelError, ValueError):
    """Invalid input: one or several :class:`Problem` s.

    ``DesignError("text")`` is accepted for a problem that is not tied to a single field; the preferred form is
    ``DesignError.single(field, value, allowed, unit, reason)`` or ``DesignError([Problem(...), ...])``.
    """

    def __init__(self, problems: "list[Problem] | Problem | str"):
        if isinstance(problems, str):
            problems = [Problem(field="", value=None, reason=problems)]
        elif isinstance(problems, Problem):
            problems = [problems]
        self.problems: list[Problem] = list(problems)
        super().__init__(self._format())

    @classmethod
    def single(cls, field: str, value: Any, allowed: str = "", unit: str = "", reason: str = "") -> "DesignError":
        return cls([Problem(field, value, allowed, unit, reason)])

    def _format(self) -> str:
        if len(self.problems) == 1:
            return str(self.problems[0])
        return f"{len(self.problems)} problems:\n" + "\n".join(f"  - {p}" for p in self.problems)


class GeometryError(DesignError):
    """The requested geometry is impossible (undercut, pointed teeth, singular edge, cutter misses the blank...)."""


class ConvergenceError(SpiralBevelError, RuntimeError):
    """An iterative solver failed to converge.

    Attributes
    ----------
    iterations : int
        Iterations performed.
    residual : float
        Largest residual norm at the end.
    last : object
        The last iterate (array), for diagnosis.
    message : str
        The message without the iteration count and residual (to quote it inside another message once).
    """

    def __init__(self, message: str, iterations: int = 0, residual: float = float("nan"), last: Any = None):
        super().__init__(f"{message} (after {iterations} iterations, residual {residual:.3e})")
        self.message = message
        self.iterations = iterations
        self.residual = residual
        self.last = last


class NoContactError(SpiralBevelError, RuntimeError):
    """The surfaces do not touch (at the position named in the message)."""


class MissingDependencyError(SpiralBevelError, ImportError):
    """An optional dependency is missing; the message names the extra to install."""

    def __init__(self, package: str, extra: str, purpose: str):
        super().__init__(
            f"{purpose} needs the optional package '{package}': install it with "
            f"pip install 'spiralbevel[{extra}]'"
        )
        self.package = package
        self.extra = extra


class SpiralBevelWarning(UserWarning):
    """Base class of spiralbevel warnings."""


class DesignWarning(SpiralBevelWarning):
    """A design is possible but outside recommended practice (face width too large, small top land, ...)."""


class PartialResultWarning(SpiralBevelWarning):
    """A secondary analysis failed; its report entry holds the reason and the rest of the report was written."""


class CacheWarning(SpiralBevelWarning):
    """The on-disk cache could not be read or written; the result was computed instead (the run goes on)."""
