"""argparse helpers: value parsers whose errors name the flag, the value and the range."""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import NoReturn

from chainfountain.errors import UserError
from chainfountain.fields import in_range


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
            raise argparse.ArgumentTypeError(f"{val:g} is out of range; allowed: {allowed}")
        return val

    parse.__name__ = what  # argparse shows this in "invalid <name> value" messages
    return parse


def integer(what: str, *, min: int | None = None,  # noqa: A002
            max: int | None = None) -> Callable[[str], int]:  # noqa: A002
    """Parser for an integer ``>= min`` and ``<= max``."""
    parts = [f">= {min}"] if min is not None else []
    parts += [f"<= {max}"] if max is not None else []
    allowed = f"{what} {' and '.join(parts)}".rstrip()

    def parse(text: str) -> int:
        try:
            val = int(text)
        except ValueError:  # not a whole number, or more digits than Python converts
            raise argparse.ArgumentTypeError(
                f"{shown(text[:40] + ('...' if len(text) > 40 else ''))} is not a whole "
                f"number; allowed: {allowed}"
            ) from None
        if (min is not None and val < min) or (max is not None and val > max):
            raise argparse.ArgumentTypeError(f"{val:.6g} is out of range; allowed: {allowed}")
        return val

    parse.__name__ = what
    return parse


def path_arg(what: str) -> Callable[[str], Path]:
    """Parser for a non-empty path; ``what`` describes it, e.g. ``"an output folder"``."""

    def parse(text: str) -> Path:
        if not text.strip():
            raise argparse.ArgumentTypeError(f"{shown(text)} is empty; allowed: {what}")
        return Path(text)

    parse.__name__ = what
    return parse


def shown(text: str) -> str:
    """``text`` quoted for a one-line message (newlines and other controls escaped)."""
    return repr(text)


def writable_file(path: Path, option: str) -> Path:
    """Check, before any work, that a file can be written at ``path`` (its folder is created
    when missing); :class:`UserError` naming ``option`` otherwise."""
    problem = ""
    if path.is_dir():
        problem = "a folder, not a file"
    else:
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=".test", dir=path.parent)
            os.close(fd)
            os.unlink(tmp)
        except OSError as exc:
            problem = exc.strerror or str(exc)
    if problem:
        raise UserError(f"argument {option}: cannot write to {shown(str(path))} ({problem}); "
                        "allowed: a file in a folder you can write to")
    return path


def stdout_is_tty() -> bool:
    return sys.stdout.isatty()
