"""Where the app finds and writes files: built-in levels, the user's levels, captures."""

from __future__ import annotations

import os
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]


def user_home() -> Path:
    """``$CHAINFOUNTAIN_HOME`` or ``~/.local/share/chainfountain`` (not created here)."""
    env = os.environ.get("CHAINFOUNTAIN_HOME")
    if env:
        return Path(env).expanduser()
    return Path.home() / ".local" / "share" / "chainfountain"


def user_levels_dir(create: bool = False) -> Path:
    """Folder for levels the user saves from the app (Ctrl+S)."""
    p = user_home() / "levels"
    if create:
        p.mkdir(parents=True, exist_ok=True)
    return p


def captures_dir(create: bool = False) -> Path:
    """Folder for screenshots (F12) and clips (G)."""
    p = user_home() / "captures"
    if create:
        p.mkdir(parents=True, exist_ok=True)
    return p


def builtin_levels_dir() -> Path:
    """The repository's ``levels/`` folder."""
    return REPO_ROOT / "levels"


def list_levels() -> list[tuple[str, Path]]:
    """All level files the picker offers: ``(label, path)``, shipped first, then the user's."""
    out: list[tuple[str, Path]] = []
    for label, folder in (("levels", builtin_levels_dir()), ("saved", user_levels_dir())):
        if folder.is_dir():
            for p in sorted(folder.glob("*.toml")):
                out.append((f"{label}/{p.name}", p))
    return out


def safe_name(name: str) -> str:
    """A file-name-safe version of a level name (letters, digits, ``-``, ``_``)."""
    keep = "".join(c if (c.isalnum() or c in "-_") else "_" for c in name.strip())
    keep = keep.strip("_")[:60]
    return keep or "level"
