"""Level files: TOML <-> dataclasses, with validation that names file, field, value and range.

A level file (schema version 1) looks like::

    schema_version = 1
    kind = "feed"
    gravity = 9.81

    [meta]
    name = "paper_tall"
    description = "What the user should see"

    [chain]
    link_length = 0.02
    ...

Top-level keys other than ``schema_version`` and ``[meta]`` are the fields of
:class:`chainfountain.sim.config.SimConfig`; tables are its nested sections
and arrays of tables (``[[rollers]]``) its tuples. Every field is declared
with :func:`chainfountain.fields.param`; ``docs/levels.md`` is generated
from those declarations by :func:`schema_markdown`.
"""

from __future__ import annotations

import dataclasses
import re
import tomllib
from pathlib import Path
from typing import Any

import tomli_w

from chainfountain import atomic
from chainfountain.fields import allowed_text, in_range, tuple_item_type
from chainfountain.level.checks import MAX_LINKS, check_consistency
from chainfountain.level.model import (
    _SKIP_TOP,
    SCHEMA_VERSION,
    Level,
    LevelError,
    Meta,
    _fail,
    _hints,
    _is_dataclass_type,
)
from chainfountain.level.resolve import CHOSEN, resolve
from chainfountain.level.schema_doc import field_meta, schema_markdown
from chainfountain.sim.config import KINDS, SimConfig

__all__ = [
    "MAX_LINKS", "SCHEMA_VERSION", "Level", "LevelError", "Meta", "check_consistency",
    "dumps", "field_meta", "from_mapping", "load", "loads", "make_level", "parse_level",
    "save", "schema_markdown", "shown_path", "to_mapping",
]

# ----------------------------------------------------------------------------- reading
_PLAIN_KEY = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
"""A key shown as it is in messages; any other key is shown quoted (``repr``)."""


def _convert_scalar(value: Any, tp: Any, meta: dict[str, Any], where: str, field: str) -> Any:
    shown = repr(value)
    if tp is bool:
        if not isinstance(value, bool):
            _fail(where, field, f"{shown} is not allowed; allowed: true or false")
        return value
    if tp is str:
        if not isinstance(value, str):
            _fail(where, field, f"{shown} is not allowed; allowed: "
                  + (allowed_text(meta) if meta.get("choices") else "a text string"))
        if meta.get("choices") and value not in meta["choices"]:
            _fail(where, field, f"{shown} is not allowed; allowed: {allowed_text(meta)}")
        return value
    if tp is int:
        if isinstance(value, bool) or not isinstance(value, int):
            _fail(where, field, f"{shown} is not allowed; allowed: a whole number"
                  + (f", {allowed_text(meta)}" if meta.get("min") is not None else ""))
        if not in_range(value, meta):
            _fail(where, field, f"{value} is out of range; allowed: {allowed_text(meta)}")
        return value
    if tp is float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            _fail(where, field, f"{shown} is not allowed; allowed: {allowed_text(meta)}")
        try:
            value = float(value)
        except OverflowError:  # an integer beyond the largest float
            _fail(where, field, f"{value} is out of range; allowed: {allowed_text(meta)}")
        if not in_range(value, meta):
            _fail(where, field, f"{value!r} is out of range; allowed: {allowed_text(meta)}")
        return value
    raise TypeError(f"unsupported field type {tp!r} for {field}")  # programming error


def _allowed_for(tp: Any, meta: dict[str, Any]) -> str:
    """What a field of type ``tp`` allows (a text field: a text string, not a number)."""
    if meta.get("choices"):
        return allowed_text(meta)
    if tp is str:
        return "a text string"
    if tp is bool:
        return "true or false"
    if tp is int:
        return "a whole number" + (f", {allowed_text(meta)}" if meta.get("min") is not None
                                   or meta.get("max") is not None else "")
    return allowed_text(meta)


def from_mapping(cls: type, data: Any, where: str, prefix: str = "", skip: frozenset = frozenset()):
    """Build dataclass ``cls`` from a TOML table, validating every field."""
    label = prefix.rstrip(".") or "top level"
    if not isinstance(data, dict):
        _fail(where, label, f"{data!r} is not allowed; allowed: a table of settings")
    hints = _hints(cls)
    fields = {f.name: f for f in dataclasses.fields(cls) if f.name not in skip}
    unknown = sorted(set(data) - set(fields))
    if unknown:
        known = ", ".join(sorted(fields))
        key = unknown[0]
        shown = key if _PLAIN_KEY.fullmatch(key) else repr(key)  # one line, whatever it holds
        _fail(where, prefix + shown, f"unknown key; allowed keys here: {known}")
    kwargs: dict[str, Any] = {}
    for name, f in fields.items():
        tp = hints[name]
        path = prefix + name
        if name not in data:
            if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
                meta = dict(f.metadata)
                _fail(where, path, "missing; required"
                      + (f", {_allowed_for(tp, meta)}" if meta else ""))
            continue
        value = data[name]
        item_tp = tuple_item_type(tp)
        if _is_dataclass_type(tp):
            kwargs[name] = from_mapping(tp, value, where, path + ".")
        elif item_tp is not None and _is_dataclass_type(item_tp):
            if not isinstance(value, list):
                _fail(where, path, f"{value!r} is not allowed; allowed: an array of tables "
                      f"([[{path}]])")
            kwargs[name] = tuple(
                from_mapping(item_tp, v, where, f"{path}[{i}].") for i, v in enumerate(value)
            )
        else:
            kwargs[name] = _convert_scalar(value, tp, dict(f.metadata), where, path)
    return cls(**kwargs)


def _with_kind_solver_defaults(data: dict[str, Any]) -> dict[str, Any]:
    """``data`` with its kind's own ``[solver]`` defaults
    (:attr:`~chainfountain.sim.kinds.base.Kind.solver_defaults`) where the file leaves
    those fields out; as it is for a kind without any, or a ``kind`` or ``solver`` the
    table check refuses anyway."""
    from chainfountain.sim.kinds import REGISTRY

    kind = REGISTRY.get(data.get("kind")) if isinstance(data.get("kind"), str) else None
    solver = data.get("solver", {})
    if kind is None or not kind.solver_defaults or not isinstance(solver, dict):
        return data
    return {**data, "solver": {**kind.solver_defaults, **solver}}


def _sets_settings(data: dict[str, Any]) -> bool:
    """Whether a level file sets ``solver.accuracy`` or a field it chooses
    (:data:`chainfountain.level.resolve.CHOSEN`)."""
    for path in ("solver.accuracy", *CHOSEN):
        table, _, key = path.partition(".")
        node = data.get(table)
        if isinstance(node, dict) and key in node:
            return True
    return False


def _with_default_accuracy(level: Level, where: str) -> Level | None:
    """``level`` at its kind's default accuracy
    (:attr:`~chainfountain.sim.kinds.base.Kind.default_accuracy`), its settings chosen,
    where the error model reaches it, the settings pass the level's checks and the choice
    changes no field but those it chooses (a link radius too thick for the chosen links is
    the file's); else ``None``: ``level`` runs as it is, and its run states the bound the
    model gives its settings, or why none."""
    from chainfountain.sim.kinds import kind_of

    kind = kind_of(level.sim)
    if kind.default_accuracy <= 0.0 or kind.accuracy_refusal(level.sim) is not None:
        return None
    trial = dataclasses.replace(level, sim=dataclasses.replace(
        level.sim, solver=dataclasses.replace(level.sim.solver,
                                              accuracy=kind.default_accuracy)))
    try:
        check_consistency(trial, where)
        chosen, _ = resolve(trial, where)
        check_consistency(chosen, where)
    except LevelError:
        return None
    if chosen.sim.chain.link_radius != level.sim.chain.link_radius:
        return None
    return chosen


def parse_level(data: dict[str, Any], where: str = "<level>") -> Level:
    """Validate a parsed TOML mapping and build a :class:`Level`."""
    if not isinstance(data, dict):
        raise LevelError(f"{where}: not a table")
    data = dict(data)
    version = data.pop("schema_version", None)
    if version is None:
        _fail(where, "schema_version", f"missing; required, allowed: {SCHEMA_VERSION}")
    if version != SCHEMA_VERSION or isinstance(version, bool):
        _fail(where, "schema_version", f"{version!r} is not supported; allowed: {SCHEMA_VERSION}")
    meta_data = data.pop("meta", None)
    if meta_data is None:
        _fail(where, "meta", "missing; required, a [meta] table with name and description")
    meta = from_mapping(Meta, meta_data, where, "meta.")
    if not meta.name.strip():
        _fail(where, "meta.name", "'' is not allowed; allowed: a non-empty name")
    given = _sets_settings(data)
    data = _with_kind_solver_defaults(data)
    sim = from_mapping(SimConfig, data, where, "", skip=_SKIP_TOP)
    sim = dataclasses.replace(sim, name=meta.name)
    level = Level(meta=meta, sim=sim)
    check_consistency(level, where)
    default = None if given else _with_default_accuracy(level, where)
    if default is not None:
        return default
    level, chosen = resolve(level, where)
    if chosen:
        check_consistency(level, where)  # the chosen settings, as any level's
    return level


def shown_path(path: str | Path) -> str:
    """A file name as messages show it: as it is, or quoted when it holds a newline or
    another character that is not printable (a message stays one line)."""
    text = str(path)
    return text if text.isprintable() else repr(text)


def _parse_toml(text: str, where: str) -> dict[str, Any]:
    """The TOML document in ``text``; :class:`LevelError` (one line) when it is not one."""
    try:
        return tomllib.loads(text.removeprefix("\ufeff"))  # a byte-order mark: no content
    except ValueError as exc:  # TOMLDecodeError, and an integer of more than 4300 digits
        raise LevelError(f"{where}: not valid TOML ({exc})") from None
    except RecursionError:
        raise LevelError(f"{where}: not valid TOML (arrays or tables nested too deeply)") \
            from None


def load(path: str | Path) -> Level:
    """Read and validate a level file. Raises :class:`LevelError` with one clear line."""
    p = Path(path)
    where = shown_path(path)
    try:
        raw = p.read_bytes()
    except FileNotFoundError:
        raise LevelError(f"{where}: no such file") from None
    except IsADirectoryError:
        raise LevelError(f"{where}: is a directory, expected a .toml level file") from None
    except OSError as exc:
        raise LevelError(f"{where}: cannot read ({exc.strerror or exc})") from None
    except ValueError as exc:  # a NUL byte in the name
        raise LevelError(f"{where}: cannot read ({exc})") from None
    try:
        text = raw.decode("utf-8-sig")  # a byte-order mark (Windows editors) is no content
    except UnicodeDecodeError:
        raise LevelError(f"{where}: not a UTF-8 text file") from None
    return parse_level(_parse_toml(text, where), where)


# ----------------------------------------------------------------------------- writing
def to_mapping(obj: Any, skip: frozenset = frozenset()) -> dict[str, Any]:
    """Dataclass to a TOML-ready mapping (every field written, defaults included)."""
    out: dict[str, Any] = {}
    scalars: dict[str, Any] = {}
    tables: dict[str, Any] = {}
    for f in dataclasses.fields(obj):
        if f.name in skip:
            continue
        v = getattr(obj, f.name)
        if dataclasses.is_dataclass(v):
            tables[f.name] = to_mapping(v)
        elif isinstance(v, tuple) and all(dataclasses.is_dataclass(x) for x in v):
            tables[f.name] = [to_mapping(x) for x in v]
        else:
            scalars[f.name] = v
    out.update(scalars)
    out.update(tables)
    return out


def dumps(level: Level) -> str:
    """TOML text of a level; :func:`loads` of it gives an equal level."""
    data: dict[str, Any] = {"schema_version": SCHEMA_VERSION}
    skip = set(_SKIP_TOP)
    defaults = SimConfig()
    for table in KINDS:  # a kind's own table is left out of other kinds' files while unused
        if table != level.sim.kind and hasattr(level.sim, table) and \
                getattr(level.sim, table) == getattr(defaults, table):
            skip.add(table)
    sim_map = to_mapping(level.sim, skip=frozenset(skip))
    data.update({k: v for k, v in sim_map.items() if not isinstance(v, dict | list)})
    data["meta"] = to_mapping(level.meta)
    data.update({k: v for k, v in sim_map.items() if isinstance(v, dict | list)})
    return tomli_w.dumps(data)


def loads(text: str, where: str = "<text>") -> Level:
    """Parse level TOML text."""
    return parse_level(_parse_toml(text, where), where)


def save(level: Level, path: str | Path) -> Path:
    """Write a level file atomically (validated first: a bad level is never written)."""
    text = dumps(level)
    loads(text, str(path))  # refuse to write what could not be read back
    return atomic.write_text(path, text)


def make_level(name: str, description: str, sim: SimConfig | None = None) -> Level:
    """Convenience constructor."""
    sim = sim or SimConfig()
    return Level(meta=Meta(name=name, description=description),
                 sim=dataclasses.replace(sim, name=name))


# ----------------------------------------------------------------------------- docs
