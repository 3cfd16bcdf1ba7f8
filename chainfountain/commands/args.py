"""argparse helpers: value parsers whose errors name the flag, the value and the range."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from typing import NoReturn

from chainfountain.level.fields import in_range


class OneLineParser(argparse.ArgumentParser):
    """ArgumentParser whose errors are a single line (no usage dump, no traceback)."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"{self.prog}: error: {message} (see --help)\n")


def number(
    what: str,
    *,
    min: float | None = None,  # noqa: A002
    max: float | None = None,  # noqa: A002
    min_inclusive: bool = True,
    max_inclusive: bool = True,
) -> Callable[[str], float]:
    """Parser for a finite float in a range; ``what`` describes it, e.g. ``"a length in m"``."""
    parts = []
    if min is not None:
        parts.append(f"{'>=' if min_inclusive else '>'} {min:g}")
    if max is not None:
        parts.append(f"{'<=' if max_inclusive else '<'} {max:g}")
    allowed = f"{what}" + (f" {' and '.join(parts)}" if parts else "")
    meta = {"min": min, "max": max, "min_inclusive": min_inclusive,
            "max_inclusive": max_inclusive}

    def parse(text: str) -> float:
        try:
            val = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{text!r} is not a number; allowed: {allowed}"
            ) from None
        if not in_range(val, meta):
            raise argparse.ArgumentTypeError(f"{text} is out of range; allowed: {allowed}")
        return val

    parse.__name__ = what  # argparse shows this in "invalid <name> value" messages
    return parse


def integer(what: str, *, min: int | None = None) -> Callable[[str], int]:  # noqa: A002
    """Parser for an integer ``>= min``."""

    def parse(text: str) -> int:
        try:
            val = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{text!r} is not a whole number; allowed: {what}"
            ) from None
        if min is not None and val < min:
            raise argparse.ArgumentTypeError(f"{val} is out of range; allowed: {what} >= {min}")
        return val

    parse.__name__ = what
    return parse


def stdout_is_tty() -> bool:
    return sys.stdout.isatty()
