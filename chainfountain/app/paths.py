"""Where the app finds and writes files: built-in levels, the user's levels, captures."""

from __future__ import annotations

import tomllib
from pathlib import Path

from chainfountain.level.library import DEFAULT_LEVEL_NAME, safe_name
from chainfountain.level.library import home_dir as user_home
from chainfountain.level.library import shipped_dir as builtin_levels_dir
from chainfountain.level.library import user_dir as user_levels_dir

__all__ = ["FORMING", "HEADING_TEXT", "LAID", "SAVED", "builtin_levels_dir", "captures_dir",
           "forms_from_rest", "is_demo", "level_description", "level_title", "list_levels",
           "safe_name", "user_home", "user_levels_dir"]


def captures_dir(create: bool = False) -> Path:
    """Folder for screenshots (F12) and clips (G)."""
    p = user_home() / "captures"
    if create:
        p.mkdir(parents=True, exist_ok=True)
    return p


def _read(path: Path) -> dict:
    """A level file's TOML as written (not validated), or ``{}`` when it cannot be read."""
    try:
        return tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}


def _is_scene(path: Path) -> bool:
    """Whether ``path`` is a scene level (they run headless only); an unreadable file is
    offered, so that opening it says what is wrong."""
    return _read(path).get("kind") == "scene"


def level_description(path: Path) -> str:
    """A level file's ``meta.description`` as written (not validated: the picker shows it
    before the level is opened), or a line saying why it cannot be read."""
    try:
        meta = tomllib.loads(path.read_text(encoding="utf-8")).get("meta") or {}
    except (OSError, ValueError) as exc:
        return f"cannot read this file ({exc})"
    text = meta.get("description") if isinstance(meta, dict) else None
    return text.strip() if isinstance(text, str) and text.strip() else "(no description)"


def is_demo(path: Path) -> bool:
    """Whether the picker lists ``path`` with the demonstrations: it forms from rest
    (:func:`forms_from_rest`) and its ``meta.demo`` is not false (a level that runs slower
    than real time in the window goes with the studies)."""
    meta = _read(path).get("meta")
    flag = meta.get("demo", True) if isinstance(meta, dict) else True
    return forms_from_rest(path) and flag is not False


def level_title(path: Path) -> str:
    """A level file's title as written (``meta.title``, else ``meta.name``, else the file's
    name; not validated: the picker shows it before the level is opened)."""
    meta = _read(path).get("meta")
    if isinstance(meta, dict):
        for key in ("title", "name"):
            v = meta.get(key)
            if isinstance(v, str) and v.strip():
                return v.strip()
    return path.stem


def forms_from_rest(path: Path) -> bool:
    """Whether a level starts at rest and forms its fountain (a beaker; a fed level or an
    apparatus with ``initial.mode = "stub"``), rather than starting laid on its path,
    moving, as the studies do."""
    data = _read(path)
    if data.get("kind") == "beaker":
        return True
    initial = data.get("initial")
    return isinstance(initial, dict) and initial.get("mode") == "stub"


FORMING, LAID, SAVED = ("-- demonstrations --", "-- studies --", "-- your saved levels --")
"""The picker's headings: shipped levels that start at rest and form their fountain in
real time (the demonstrations, :func:`is_demo`; the default first), the other shipped
levels (studies of the steady state, of where the model and the paper disagree, and of
the paper's example at the simulator's accuracy, slower than real time), and the user's
saved levels."""

HEADING_TEXT = {
    FORMING: "The levels below start at rest and form their fountain: the demonstrations.",
    LAID: "The levels below start laid on their path, already moving: studies of the "
    "steady machine, and the arrangements where this model and the paper disagree. "
    "Their descriptions say why each does not form from rest.",
    SAVED: "The levels you saved (Ctrl+S), from your own folder.",
}
"""What the picker says when a heading is clicked."""


def list_levels(default: str = DEFAULT_LEVEL_NAME) -> list[tuple[str, Path | None]]:
    """The picker's rows: ``(label, path)``, ``path`` None for a heading
    (:data:`FORMING`, :data:`LAID`, :data:`SAVED`). Shipped levels that form from rest
    come first (``default`` at their head), then the shipped ones that start on their
    path, then the user's; scene levels are left out (``chainfountain run`` runs them)."""
    shipped = [p for p in sorted(builtin_levels_dir().glob("*.toml")) if not _is_scene(p)] \
        if builtin_levels_dir().is_dir() else []
    forms = {p: is_demo(p) for p in shipped}
    forming = sorted((p for p in shipped if forms[p]), key=lambda p: p.stem != default)
    laid = [p for p in shipped if not forms[p]]
    saved = [p for p in sorted(user_levels_dir().glob("*.toml")) if not _is_scene(p)] \
        if user_levels_dir().is_dir() else []
    out: list[tuple[str, Path | None]] = []
    for heading, paths, label in ((FORMING, forming, "levels"), (LAID, laid, "levels"),
                                  (SAVED, saved, "saved")):
        if paths:
            out.append((heading, None))
            out += [(f"{label}/{p.name}", p) for p in paths]
    return out
