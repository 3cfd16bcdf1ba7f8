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
with :func:`chainfountain.level.fields.param`; ``docs/levels.md`` is generated
from those declarations by :func:`schema_markdown`.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
import typing
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import tomli_w

from chainfountain import atomic
from chainfountain.errors import UserError
from chainfountain.level.fields import REQUIRED, allowed_text, in_range, param, tuple_item_type
from chainfountain.sim.config import KINDS, SimConfig

SCHEMA_VERSION = 1
_SKIP_TOP = frozenset({"name"})  # SimConfig.name mirrors meta.name


class LevelError(UserError):
    """A level file or level value is not acceptable."""


@dataclass
class Meta:
    """Name and description of a level."""

    name: str = param(REQUIRED, unit="", doc="Short name of the level (shown in the picker)")
    description: str = param(
        "", unit="", doc="What the level shows and what the user should see"
    )


@dataclass
class Level:
    """One saved configuration: its meta data and the simulation setup."""

    meta: Meta
    sim: SimConfig

    @property
    def name(self) -> str:
        return self.meta.name


# ----------------------------------------------------------------------------- reading
def _fail(where: str, field: str, msg: str) -> typing.NoReturn:
    raise LevelError(f"{where}: {field}: {msg}")


def _hints(cls: type) -> dict[str, Any]:
    return typing.get_type_hints(cls)


def _is_dataclass_type(tp: Any) -> bool:
    return isinstance(tp, type) and dataclasses.is_dataclass(tp)


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
        value = float(value)
        if not in_range(value, meta):
            _fail(where, field, f"{value!r} is out of range; allowed: {allowed_text(meta)}")
        return value
    raise TypeError(f"unsupported field type {tp!r} for {field}")  # programming error


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
        _fail(where, prefix + unknown[0], f"unknown key; allowed keys here: {known}")
    kwargs: dict[str, Any] = {}
    for name, f in fields.items():
        tp = hints[name]
        path = prefix + name
        if name not in data:
            if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
                meta = dict(f.metadata)
                _fail(where, path, "missing; required"
                      + (f", {allowed_text(meta)}" if meta else ""))
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


def check_consistency(level: Level, where: str) -> None:
    """Cross-field checks: the configured fountain must be reachable."""
    sim = level.sim
    if sim.kind == "apparatus":
        _check_apparatus(level, where)
    if sim.kind == "feed":
        feed = sim.feed
        g = sim.gravity
        if g <= 0:
            _fail(where, "gravity", f"{g!r} is out of range; allowed: a number > 0 (m/s^2)")
        v_need = math.sqrt(g * feed.drop)
        if feed.speed <= v_need:
            _fail(
                where, "feed.speed",
                f"{feed.speed!r} m/s cannot make a fountain that lands {feed.drop:g} m below "
                f"the launch point (k*H >= 1); allowed: a speed > sqrt(g*H) = {v_need:.4g} m/s",
            )
        if sim.chain.link_length > 0.1 * feed.drop:
            _fail(
                where, "chain.link_length",
                f"{sim.chain.link_length!r} m is too coarse for a drop of {feed.drop:g} m; "
                f"allowed: at most a tenth of feed.drop ({0.1 * feed.drop:.4g} m)",
            )


def _check_apparatus(level: Level, where: str) -> None:
    """Apparatus cross-field checks (paper: ``Tbar_E + k*H < 1`` for the launch)."""
    sim = level.sim
    a = sim.apparatus
    g = sim.gravity
    if g <= 0:
        _fail(where, "gravity", f"{g!r} is out of range; allowed: a number > 0 (m/s^2)")
    if a.floor_depth > 0:
        if a.variant != "floor" or a.end != "absorbing":
            _fail(where, "apparatus.floor_depth",
                  f"{a.floor_depth!r} m needs apparatus.variant = 'floor' with end = "
                  f"'absorbing' (it is {a.variant!r} with end {a.end!r}); allowed: 0")
        if a.end_tension != 0:
            _fail(where, "apparatus.end_tension",
                  f"{a.end_tension!r} conflicts with apparatus.floor_depth = {a.floor_depth:g} m, "
                  "which sets Tbar_E = g*floor_depth/speed**2; allowed: 0 with a floor_depth")
        v_need = math.sqrt(g * (a.drop + a.floor_depth))
        if a.speed <= v_need:
            _fail(where, "apparatus.speed",
                  f"{a.speed!r} m/s cannot launch a fountain that reaches a free end "
                  f"{a.drop + a.floor_depth:g} m lower (drop + floor_depth); allowed: a speed > "
                  f"sqrt(g*(H + floor_depth)) = {v_need:.4g} m/s")
    v_need = math.sqrt(g * a.drop / (1.0 - a.end_tension))
    if a.speed <= v_need:
        _fail(where, "apparatus.speed",
              f"{a.speed!r} m/s cannot launch a fountain that ends {a.drop:g} m lower with "
              f"Tbar_E = {a.end_tension:g}; allowed: a speed > sqrt(g*H/(1 - Tbar_E)) = "
              f"{v_need:.4g} m/s")
    if sim.chain.link_length > 0.1 * a.drop:
        _fail(where, "chain.link_length",
              f"{sim.chain.link_length!r} m is too coarse for a drop of {a.drop:g} m; "
              f"allowed: at most a tenth of apparatus.drop ({0.1 * a.drop:.4g} m)")
    if a.plate_links and a.plate != "groove":
        _fail(where, "apparatus.plate_links",
              f"{a.plate_links!r} needs apparatus.plate = 'groove' (it is {a.plate!r}); "
              "allowed: 0 with a 'contact' plate")
    if a.plate_links and a.plate_links < 4:
        _fail(where, "apparatus.plate_links",
              f"{a.plate_links!r} is too short a plate strand to cut or extend in the middle; "
              "allowed: 0 (off) or at least 4")
    if 0 < a.pickup_rest_links < 5:
        _fail(where, "apparatus.pickup_rest_links",
              f"{a.pickup_rest_links!r} leaves the pick-up roller too little resting chain to "
              "roll on; allowed: 0 (as apparatus.rest_links) or at least 5")
    default_initial = type(sim.initial)()
    for f in dataclasses.fields(sim.initial):
        value, default = getattr(sim.initial, f.name), getattr(default_initial, f.name)
        if value != default:
            _fail(where, f"initial.{f.name}",
                  f"{value!r} has no effect in an 'apparatus' level: the apparatus lays its "
                  "chain along its own path, moving at apparatus.speed (to start a perturbed "
                  f"run, change apparatus.speed slightly); allowed: {default!r}")
    if a.fold_clearance and (a.variant != "fold" or a.plate != "groove"):
        _fail(where, "apparatus.fold_clearance",
              f"{a.fold_clearance!r} m only applies to variant = 'fold' with plate = 'groove' "
              f"(here variant {a.variant!r}, plate {a.plate!r}); allowed: 0")
    if a.upper_guide == "joints" and a.plate != "groove":
        _fail(where, "apparatus.upper_guide",
              f"'joints' needs apparatus.plate = 'groove' (it is {a.plate!r}): the joint guide "
              "takes the links from the plate's grooves; allowed: 'walls' with a 'contact' plate")


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
    sim = from_mapping(SimConfig, data, where, "", skip=_SKIP_TOP)
    sim = dataclasses.replace(sim, name=meta.name)
    level = Level(meta=meta, sim=sim)
    check_consistency(level, where)
    return level


def load(path: str | Path) -> Level:
    """Read and validate a level file. Raises :class:`LevelError` with one clear line."""
    p = Path(path)
    where = str(path)
    try:
        raw = p.read_bytes()
    except FileNotFoundError:
        raise LevelError(f"{where}: no such file") from None
    except IsADirectoryError:
        raise LevelError(f"{where}: is a directory, expected a .toml level file") from None
    except OSError as exc:
        raise LevelError(f"{where}: cannot read ({exc.strerror})") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise LevelError(f"{where}: not a UTF-8 text file") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise LevelError(f"{where}: not valid TOML ({exc})") from None
    return parse_level(data, where)


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
    for kind in KINDS:  # a kind's own table is left out of other kinds' files while unused
        if kind != level.sim.kind and hasattr(level.sim, kind) and \
                getattr(level.sim, kind) == getattr(defaults, kind):
            skip.add(kind)
    sim_map = to_mapping(level.sim, skip=frozenset(skip))
    data.update({k: v for k, v in sim_map.items() if not isinstance(v, dict | list)})
    data["meta"] = to_mapping(level.meta)
    data.update({k: v for k, v in sim_map.items() if isinstance(v, dict | list)})
    return tomli_w.dumps(data)


def loads(text: str, where: str = "<text>") -> Level:
    """Parse level TOML text."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise LevelError(f"{where}: not valid TOML ({exc})") from None
    return parse_level(data, where)


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
def _rows(cls: type, prefix: str, skip: frozenset = frozenset()) -> list[str]:
    hints = _hints(cls)
    rows: list[str] = []
    nested: list[tuple[str, type]] = []
    for f in dataclasses.fields(cls):
        if f.name in skip:
            continue
        tp = hints[f.name]
        item = tuple_item_type(tp)
        if _is_dataclass_type(tp):
            nested.append((f"{prefix}{f.name}", tp))
            continue
        if item is not None and _is_dataclass_type(item):
            nested.append((f"{prefix}{f.name}[]", item))
            continue
        meta = dict(f.metadata)
        if f.default is not dataclasses.MISSING:
            default = repr(f.default)
        else:
            default = "required"
        allowed = allowed_text(meta) if meta else ""
        if tp is bool:
            allowed = "true or false"
        elif tp is str and not meta.get("choices"):
            allowed = "text"
        elif tp is int:
            allowed = allowed.replace("a number", "a whole number")
        unit = meta.get("unit", "")
        live = "yes" if meta.get("live") else ""
        rows.append(f"| `{prefix}{f.name}` | {unit} | {default} | {allowed} | {live} | "
                    f"{meta.get('doc', '')} |")
    for name, sub in nested:
        rows.extend(_rows(sub, name + ".", frozenset()))
    return rows


def schema_markdown() -> str:
    """The level schema as a Markdown page (``docs/levels.md``)."""
    head = [
        "# Level files",
        "",
        "<!-- Generated by `chainfountain schema`; edit chainfountain/sim/config.py, "
        "not this file. -->",
        "",
        f"Levels are TOML files, schema version {SCHEMA_VERSION}. SI units throughout "
        "(m, kg, s, N, rad). Every key is optional unless its default says `required`; "
        "a file is rejected, with one line naming the file, the key, the value and what is "
        "allowed, when a key is unknown, has the wrong type or lies outside its range. "
        "`chainfountain check FILE...` validates files. `[[rollers]]` and `[[carts]]` are "
        "arrays of tables. Keys marked *live* can be changed while a simulation runs.",
        "",
        "Besides the per-key ranges the loader checks that the fountain exists: for "
        "`kind = \"feed\"`, `feed.speed > sqrt(gravity * feed.drop)` (else no inverted "
        "catenary reaches the floor) and `chain.link_length <= feed.drop / 10`.",
        "",
        "| key | unit | default | allowed | live | meaning |",
        "|---|---|---|---|---|---|",
        f"| `schema_version` | | required | {SCHEMA_VERSION} | | Version of this schema |",
    ]
    rows = _rows(Meta, "meta.") + _rows(SimConfig, "", _SKIP_TOP)
    return "\n".join(head + rows) + "\n"


def field_meta(path: str) -> dict[str, Any]:
    """Metadata (unit, doc, range, live) of a dotted field path such as ``chain.link_length``."""
    cls: type = SimConfig
    parts = path.split(".")
    for i, part in enumerate(parts):
        f = {f.name: f for f in dataclasses.fields(cls)}.get(part)
        if f is None:
            raise KeyError(path)
        tp = _hints(cls)[part]
        if i == len(parts) - 1:
            return dict(f.metadata)
        cls = tp if _is_dataclass_type(tp) else tuple_item_type(tp)
        if cls is None:
            raise KeyError(path)
    raise KeyError(path)


__all__ = [
    "SCHEMA_VERSION",
    "Level",
    "LevelError",
    "Meta",
    "dumps",
    "field_meta",
    "load",
    "loads",
    "make_level",
    "parse_level",
    "save",
    "schema_markdown",
]
