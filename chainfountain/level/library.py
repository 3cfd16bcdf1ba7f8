"""Where levels live: the shipped ``chainfountain/levels/`` folder (inside the package, so
every install has it), the user's folder, the built-in default."""

from __future__ import annotations

import os
from pathlib import Path

from chainfountain.level import io

DEFAULT_LEVEL_NAME = "beaker"
"""Stem of the level ``chainfountain`` opens with no arguments."""


def shipped_dir() -> Path:
    """The package's ``chainfountain/levels/`` folder (shipped inside the wheel)."""
    return Path(__file__).resolve().parents[1] / "levels"


def home_dir() -> Path:
    """``$CHAINFOUNTAIN_HOME`` or ``~/.local/share/chainfountain`` (not created here)."""
    home = os.environ.get("CHAINFOUNTAIN_HOME")
    return Path(home).expanduser() if home else Path.home() / ".local" / "share" / "chainfountain"


def user_dir(create: bool = False) -> Path:
    """The user's level folder (levels saved from the app): ``home_dir()/levels``."""
    d = home_dir() / "levels"
    if create:
        d.mkdir(parents=True, exist_ok=True)
    return d


def safe_name(name: str) -> str:
    """A file-name-safe version of a level name (letters, digits, ``-``, ``_``)."""
    keep = "".join(c if (c.isalnum() or c in "-_") else "_" for c in name.strip())
    keep = keep.strip("_")[:60]
    return keep or "level"


def available() -> list[Path]:
    """All level files: shipped ones first, then the user's, each sorted by name."""
    out: list[Path] = []
    for d in (shipped_dir(), user_dir()):
        if d.is_dir():
            out.extend(sorted(d.glob("*.toml")))
    return out


def resolve(name_or_path: str | os.PathLike[str]) -> Path:
    """A level path from a file path or a bare level name (``paper_tall``)."""
    p = Path(name_or_path)
    try:
        if p.suffix == ".toml" or p.is_file():
            return p
        for d in (shipped_dir(), user_dir()):
            cand = d / f"{p.name}.toml"
            if cand.exists():
                return cand
    except (OSError, ValueError):  # a name too long for the file system, a NUL byte
        pass
    names = ", ".join(sorted(x.stem for x in available())) or "none found"
    shown = str(name_or_path)
    shown = shown if shown and shown.isprintable() else repr(shown)
    raise io.LevelError(f"{shown}: no such level file or level name; known levels: {names}")


TWINS: dict[str, str] = {
    "apparatus_floor": "ideal_floor",
    "apparatus_fold": "ideal_fold",
    "apparatus_fold_gripped": "ideal_fold",
    "apparatus_special": "ideal_special",
    "apparatus_special_gripped": "ideal_special",
    "apparatus_limit": "ideal_limit",
    "apparatus_open": "ideal_open",
}
"""Each contact-machine preset and the ideal machine that shows the same arrangement by the
paper's laws (both ways round: :func:`twin`; an ideal machine opens the first preset that
names it)."""


def twin(name: str) -> str | None:
    """The shipped level showing ``name``'s arrangement in the other machine (contact or
    ideal), or ``None``."""
    if name in TWINS:
        return TWINS[name]
    return next((a for a, b in TWINS.items() if b == name), None)


def default_level() -> io.Level:
    """The built-in default level (``chainfountain/levels/beaker.toml``; the code defaults if
    absent)."""
    path = shipped_dir() / f"{DEFAULT_LEVEL_NAME}.toml"
    if path.exists():
        return io.load(path)
    return io.make_level(
        "default", "Built-in default: a fed fountain with the simulator's default settings."
    )
