"""The options of a run that the command line and the Python API share (the duration, the
seed), with their ranges and one-line messages: ``chainfountain run --duration -1`` and
``chainfountain.run(..., duration=-1)`` say the same thing."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from chainfountain.errors import UserError
from chainfountain.fields import in_range


@dataclass(frozen=True)
class Range:
    """A number an option takes: what it is, its bounds, whether it is whole."""

    what: str
    min: float | None = None
    max: float | None = None
    min_inclusive: bool = True
    max_inclusive: bool = True
    whole: bool = False

    def allowed(self) -> str:
        """``a duration in s > 0 and <= 3600``."""
        parts = []
        if self.min is not None:
            parts.append(f"{'>=' if self.min_inclusive else '>'} {self.min:g}")
        if self.max is not None:
            parts.append(f"{'<=' if self.max_inclusive else '<'} {self.max:g}")
        return f"{self.what}" + (f" {' and '.join(parts)}" if parts else "")

    def _meta(self) -> dict[str, Any]:
        return {"min": self.min, "max": self.max, "min_inclusive": self.min_inclusive,
                "max_inclusive": self.max_inclusive}

    def problem(self, value: Any) -> str | None:
        """Why ``value`` is not allowed (``None`` when it is)."""
        if self.whole:
            if isinstance(value, bool) or not isinstance(value, int):
                return f"{value!r} is not a whole number; allowed: {self.allowed()}"
            if not in_range(value, self._meta()):
                return f"{value:.6g} is out of range; allowed: {self.allowed()}"
            return None
        if isinstance(value, bool) or not isinstance(value, int | float):
            return f"{value!r} is not a number; allowed: {self.allowed()}"
        if not math.isfinite(float(value)) or not in_range(float(value), self._meta()):
            return f"{float(value):g} is out of range; allowed: {self.allowed()}"
        return None

    def check(self, value: Any, name: str) -> Any:
        """``value`` when allowed; else :class:`UserError` ``name: <problem>``."""
        problem = self.problem(value)
        if problem:
            raise UserError(f"{name}: {problem}")
        return float(value) if not self.whole else value


DURATION = Range("a duration in s", min=0, min_inclusive=False, max=3600)
"""Simulated seconds of a run."""
SEED = Range("a seed", min=0, whole=True)
"""A run's random seed."""
