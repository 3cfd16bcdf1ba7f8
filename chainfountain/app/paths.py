"""Where the app finds and writes files: built-in levels, the user's levels, captures."""

from __future__ import annotations

from pathlib import Path

from chainfountain.level.library import home_dir as user_home
from chainfountain.level.library import safe_name
from chainfountain.level.library import shipped_dir as builtin_levels_dir
from chainfountain.level.library import user_dir as user_levels_dir

__all__ = ["builtin_levels_dir", "captures_dir", "list_levels", "safe_name", "user_home",
           "user_levels_dir"]


def captures_dir(create: bool = False) -> Path:
    """Folder for screenshots (F12) and clips (G)."""
    p = user_home() / "captures"
    if create:
        p.mkdir(parents=True, exist_ok=True)
    return p


def list_levels() -> list[tuple[str, Path]]:
    """All level files the picker offers: ``(label, path)``, shipped first, then the user's."""
    out: list[tuple[str, Path]] = []
    for label, folder in (("levels", builtin_levels_dir()), ("saved", user_levels_dir())):
        if folder.is_dir():
            for p in sorted(folder.glob("*.toml")):
                out.append((f"{label}/{p.name}", p))
    return out
