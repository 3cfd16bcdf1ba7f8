"""Where the app finds and writes files: built-in levels, the user's levels, captures."""

from __future__ import annotations

import tomllib
from pathlib import Path

from chainfountain.level.library import home_dir as user_home
from chainfountain.level.library import safe_name
from chainfountain.level.library import shipped_dir as builtin_levels_dir
from chainfountain.level.library import user_dir as user_levels_dir

__all__ = ["builtin_levels_dir", "captures_dir", "level_description", "list_levels",
           "safe_name", "user_home", "user_levels_dir"]


def captures_dir(create: bool = False) -> Path:
    """Folder for screenshots (F12) and clips (G)."""
    p = user_home() / "captures"
    if create:
        p.mkdir(parents=True, exist_ok=True)
    return p


def _is_scene(path: Path) -> bool:
    """Whether ``path`` is a scene level (they run headless only); an unreadable file is
    offered, so that opening it says what is wrong."""
    try:
        return tomllib.loads(path.read_text(encoding="utf-8")).get("kind") == "scene"
    except (OSError, ValueError):
        return False


def level_description(path: Path) -> str:
    """A level file's ``meta.description`` as written (not validated: the picker shows it
    before the level is opened), or a line saying why it cannot be read."""
    try:
        meta = tomllib.loads(path.read_text(encoding="utf-8")).get("meta") or {}
    except (OSError, ValueError) as exc:
        return f"cannot read this file ({exc})"
    text = meta.get("description") if isinstance(meta, dict) else None
    return text.strip() if isinstance(text, str) and text.strip() else "(no description)"


def list_levels() -> list[tuple[str, Path]]:
    """All level files the picker offers: ``(label, path)``, shipped first, then the user's;
    scene levels are left out (``chainfountain run`` runs them)."""
    out: list[tuple[str, Path]] = []
    for label, folder in (("levels", builtin_levels_dir()), ("saved", user_levels_dir())):
        if folder.is_dir():
            for p in sorted(folder.glob("*.toml")):
                if not _is_scene(p):
                    out.append((f"{label}/{p.name}", p))
    return out
