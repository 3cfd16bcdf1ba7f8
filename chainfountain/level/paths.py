"""Field paths of a level: ``gravity``, ``feed.speed``, ``carts[0].mass``,
``scene.pins[0].release``, ``scene.vertices[2].x`` -- dotted names, each optionally
indexing an array of tables (``[[carts]]``, ``[[scene.pins]]``), as ``docs/levels.md``
lists them.

:func:`declared` gives the type and metadata a path's field is declared with, so that a
value can be checked for its type before a level is built (:func:`check_type`, a sweep's
grid) and a command-line text read as the field's type (:func:`parse_value`, ``chainfountain
run LEVEL feed.speed=6``); :func:`set_in` writes a value into a level's TOML mapping.
"""

from __future__ import annotations

import dataclasses
import math
import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from chainfountain.fields import tuple_item_type
from chainfountain.level import io, resolve
from chainfountain.level.io import _allowed_for
from chainfountain.level.model import Level, LevelError, Meta, _hints, _is_dataclass_type
from chainfountain.sim.config import SimConfig

_SEGMENT = r"[a-z_][a-z0-9_]*(?:\[\d+\])?"
PATH = re.compile(rf"^{_SEGMENT}(?:\.{_SEGMENT})*$")
"""A field path: dotted names, each optionally with one ``[index]``."""
EXAMPLES = "'feed.speed', 'carts[0].mass' or 'scene.pins[0].release'"


@dataclass(frozen=True)
class Field:
    """What a path names: its declared type (``float``, ``int``, ``str``, ``bool``, a
    dataclass for a table, ``tuple`` for an array of tables) and its metadata."""

    path: str
    type: Any
    meta: dict[str, Any]

    def allowed(self) -> str:
        """What the field allows, as messages say it."""
        return allowed_for(self.type, self.meta)


def allowed_for(tp: Any, meta: dict[str, Any]) -> str:
    """What a field of type ``tp`` with metadata ``meta`` allows (``a text string``, ``true
    or false``, ``a whole number, a number >= 0``, ``a number in (0, 3600] (s)``, ...)."""
    if tp is tuple:
        return "an array of tables"
    if _is_dataclass_type(tp):
        return "a table of settings"
    return _allowed_for(tp, meta)


def parse(path: Any, where: str) -> list[tuple[str, int | None]]:
    """``path`` as ``[(name, index or None), ...]``; :class:`LevelError` when it is not a
    field path."""
    if not isinstance(path, str) or not PATH.match(path):
        raise LevelError(f"{where}: {path!r} is not a field path; allowed: a dotted path as "
                         f"in docs/levels.md, e.g. {EXAMPLES}")
    out: list[tuple[str, int | None]] = []
    for seg in path.split("."):
        name, _, index = seg.partition("[")
        out.append((name, int(index[:-1]) if index else None))
    return out


def declared(path: str, where: str = "change") -> Field | None:
    """The declaration of the field ``path`` names (``None`` when no field has that path:
    the loader then says which keys are allowed there)."""
    owner: Any = SimConfig
    tp: Any = None
    meta: dict[str, Any] = {}
    for k, (name, index) in enumerate(parse(path, where)):
        if k == 0 and name == "meta":
            if index is not None:
                return None
            owner = tp = Meta
            continue
        if not _is_dataclass_type(owner):
            return None
        fields = {f.name: f for f in dataclasses.fields(owner)}
        if name not in fields or (owner is SimConfig and name == "name"):
            return None
        tp, meta = _hints(owner)[name], dict(fields[name].metadata)
        item = tuple_item_type(tp)
        if index is not None:
            if item is None:
                return None
            tp, meta = item, {}
        elif item is not None:
            tp = tuple
        owner = tp
    return Field(path=path, type=tp, meta=meta)


def type_problem(field: Field, value: Any) -> str | None:
    """Why ``value`` cannot be ``field``'s value whatever its range (a text for a number,
    a number for a text, ...), or ``None`` when its type fits."""
    tp = field.type
    ok = {str: lambda v: isinstance(v, str),
          bool: lambda v: isinstance(v, bool),
          int: lambda v: isinstance(v, int) and not isinstance(v, bool),
          float: lambda v: isinstance(v, int | float) and not isinstance(v, bool),
          tuple: lambda v: isinstance(v, list) and all(isinstance(x, dict) for x in v)}
    check = ok.get(tp, (lambda v: isinstance(v, dict)) if _is_dataclass_type(tp) else None)
    if check is None or check(value):
        return None
    return f"{value!r} is not allowed; allowed: {field.allowed()}"


def check_type(path: str, value: Any, where: str) -> None:
    """:class:`LevelError` (one line naming ``path``, the value and what is allowed) when
    ``value`` has a type the field never takes; unknown paths pass (the loader names
    them)."""
    field = declared(path, where)
    problem = type_problem(field, value) if field is not None else None
    if problem:
        raise LevelError(f"{where}: {path}: {problem}")


def parse_value(path: str, text: str, where: str) -> Any:
    """A command-line text as the value of the field ``path``: a text field takes it as it
    is (quotes optional); any other as a TOML value (``6``, ``5.5``, ``true``, ``[...]``)."""
    field = declared(path, where)
    if field is not None and field.type is str:
        if len(text) >= 2 and text[0] == text[-1] and text[0] in "\"'":
            return text[1:-1]
        return text
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except (tomllib.TOMLDecodeError, ValueError, RecursionError):
        pass
    if field is not None and field.type is float:
        try:
            value = float(text)
            if math.isfinite(value):
                return value
        except ValueError:
            pass
    allowed = field.allowed() if field is not None else "a TOML value (a number, true or " \
        "false, a quoted text)"
    raise LevelError(f"{where}: {path}: {text!r} is not a value; allowed: {allowed}")


def set_in(data: dict[str, Any], path: str, value: Any, where: str) -> None:
    """Write ``value`` at ``path`` into a level's TOML mapping ``data`` (missing tables are
    made; the loader then checks what was written). An index beyond an array's end, or a
    path through a value that is not a table, raises :class:`LevelError`."""
    parts = parse(path, where)
    node: Any = data
    shown = ""
    for k, (name, index) in enumerate(parts):
        last = k == len(parts) - 1
        shown = f"{shown}.{name}" if shown else name
        if not isinstance(node, dict):
            raise LevelError(f"{where}: {path}: {shown.rsplit('.', 1)[0]!r} is not a table; "
                             f"allowed: a field path as in docs/levels.md, e.g. {EXAMPLES}")
        if index is None:
            if last:
                node[name] = value
                return
            node = node.setdefault(name, {})
            continue
        items = node.get(name)
        n = len(items) if isinstance(items, list) else 0
        if not isinstance(items, list) or index >= n:
            raise LevelError(f"{where}: {path}: the level has {n} {shown}; allowed: an index "
                             f"below {n}" + (" (none to change)" if n == 0 else ""))
        shown += f"[{index}]"
        if last:
            items[index] = value
            return
        node = items[index]


def get(level: Level, path: str, where: str = "field") -> Any:
    """The value at ``path`` in ``level`` (:class:`LevelError` when it has none)."""
    if declared(path, where) is None:
        raise LevelError(f"{where}: {path}: no such field; allowed: a field path of "
                         f"docs/levels.md, e.g. {EXAMPLES}")
    node: Any = None
    for k, (name, index) in enumerate(parse(path, where)):
        node = (level.meta if name == "meta" else getattr(level.sim, name)) if k == 0 \
            else getattr(node, name)
        if index is not None:
            if index >= len(node):
                raise LevelError(f"{where}: {path}: the level has {len(node)} {name}; "
                                 f"allowed: an index below {len(node)}")
            node = node[index]
    return node


def changed(level: Level, changes: Mapping[str, Any], where: str = "change") -> Level:
    """``level`` with each field of ``changes`` set (any path here), checked as a level
    file is: a field that does not exist, a value of another type or out of its range, an
    index beyond an array's end, or a combination the loader refuses raises
    :class:`LevelError` naming the field. A new level (``solver.accuracy`` applied
    again); ``level`` is untouched."""
    if not isinstance(changes, Mapping):
        raise LevelError(f"{where}: {changes!r} is not allowed; allowed: a mapping of field "
                         "paths to values, e.g. {'feed.speed': 6.0}")
    data = tomllib.loads(io.dumps(level))
    for path, value in changes.items():
        check_type(path, value, where)
        set_in(data, path, value, where)
    new = io.parse_level(data, where)
    mine = taken_over(new, changes)
    if not mine:
        return new
    acc = changes.get("solver.accuracy")
    if acc is not None and acc != 0.0:
        raise LevelError(f"{where}: {mine[0]}: {changes[mine[0]]!r} together with "
                         f"solver.accuracy = {acc!r}, which chooses {get(new, mine[0])!r}; "
                         "allowed: one of them (solver.accuracy = 0 to set the settings by "
                         "hand)")
    data.setdefault("solver", {})["accuracy"] = 0.0  # the change takes over, as a slider's
    return io.parse_level(data, where)


def taken_over(level: Level, changes: Mapping[str, Any]) -> list[str]:
    """The fields of ``changes`` that ``level``'s ``solver.accuracy`` chose otherwise
    (:data:`chainfountain.level.resolve.CHOSEN`); ``level`` is the changed level as
    loaded, its accuracy applied."""
    if level.sim.solver.accuracy == 0.0:
        return []
    return [p for p, v in changes.items()
            if p in resolve.CHOSEN and v != get(level, p)]
