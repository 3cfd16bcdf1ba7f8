"""The shipped levels (``chainfountain/levels/*.toml``), found one way: by name.

A test takes the ``level`` fixture (``level("beaker")``, :func:`level`); module constants,
parameter lists and module-scoped runs, which no function fixture reaches, use this
module's :func:`level`, :func:`path` and :data:`NAMES`. All go through
:func:`chainfountain.level.library.resolve`, the lookup the package itself uses.
"""

from __future__ import annotations

from pathlib import Path

from chainfountain.level import io, library
from chainfountain.level.model import Level

NAMES: list[str] = sorted(p.stem for p in library.shipped_dir().glob("*.toml"))
"""Every shipped level's name, sorted (``"apparatus_floor"``, ..., ``"wide_low"``)."""


def path(name: str) -> Path:
    """The file of the shipped level ``name``."""
    found = library.resolve(name)
    if found.parent != library.shipped_dir():
        raise LookupError(f"{name}: not a shipped level ({found})")
    return found


def level(name: str) -> Level:
    """The shipped level ``name``, parsed afresh (a test may change it)."""
    return io.load(path(name))


PATHS: list[Path] = [path(n) for n in NAMES]
"""Every shipped level's file, in the order of :data:`NAMES`."""
