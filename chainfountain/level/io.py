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
import math
import re
import tomllib
import typing
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import tomli_w

from chainfountain import atomic
from chainfountain.errors import UserError
from chainfountain.fields import REQUIRED, allowed_text, in_range, param, tuple_item_type
from chainfountain.sim.config import KINDS, InitialConfig, SimConfig

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


_PLAIN_KEY = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
"""A key shown as it is in messages; any other key is shown quoted (``repr``)."""


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
        try:
            value = float(value)
        except OverflowError:  # an integer beyond the largest float
            _fail(where, field, f"{value} is out of range; allowed: {allowed_text(meta)}")
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


MAX_LINKS = 20_000
"""Most chain links a level may put into the simulation at its start (the chain in
flight, plus an apparatus's upper plate strand): a level beyond it would take minutes
to build and hours to run, or exhaust the machine's memory."""


def check_consistency(level: Level, where: str) -> None:
    """Cross-field checks: the configured fountain must exist, fit the simulator, and
    every setting given must have an effect in this kind of level."""
    sim = level.sim
    g = sim.gravity
    if not g > 0:
        _fail(where, "gravity", f"{g!r} is out of range; allowed: a number > 0 (m/s^2)")
    _check_other_kind(sim, where)
    if sim.kind == "apparatus":
        _check_apparatus(level, where)
    if sim.kind == "feed":
        _check_feed(level, where)


def _check_other_kind(sim: SimConfig, where: str) -> None:
    """The table of the other level kind is left out or at its defaults (it has no effect)."""
    defaults = SimConfig()
    for kind in KINDS:
        if kind == sim.kind:
            continue
        table, default = getattr(sim, kind), getattr(defaults, kind)
        for f in dataclasses.fields(table):
            value = getattr(table, f.name)
            if value != getattr(default, f.name):
                _fail(where, f"{kind}.{f.name}",
                      f"{value!r} has no effect in a {sim.kind!r} level (the [{kind}] table "
                      f"belongs to kind {kind!r}); allowed: {getattr(default, f.name)!r} or "
                      f"no [{kind}] table")


def _fountain_or_fail(where: str, field: str, v: float, alpha0: float, H: float,
                      TE_bar: float, g: float):
    """The paper's fountain for a launch (the checks before this one make it exist)."""
    from chainfountain.theory import Fountain

    try:
        return Fountain.from_launch(v=v, alpha0=alpha0, H=H, TE_bar=TE_bar, g=g)
    except (ValueError, ArithmeticError) as exc:
        _fail(where, field, f"{v!r} m/s gives no fountain ({exc})")


def _fastest_fitting(v_lo: float, v_hi: float, alpha0: float, H: float, TE_bar: float,
                     g: float, length: float, depth: float = 0.0) -> float:
    """The highest speed in ``(v_lo, v_hi)`` whose fountain has at most ``length`` m of chain
    in flight (bisection; the length in flight grows with the speed). ``depth``: an
    apparatus floor that far below the fountain end adds ``g*depth/v**2`` to ``TE_bar``."""
    from chainfountain.theory import Fountain

    lo, hi = v_lo, v_hi
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        try:
            ok = Fountain.from_launch(v=mid, alpha0=alpha0, H=H, TE_bar=TE_bar + g * depth / mid**2,
                                      g=g).length <= length
        except (ValueError, ArithmeticError):
            ok = True  # below the fountain's least speed: nothing in flight yet
        lo, hi = (mid, hi) if ok else (lo, mid)
    return lo


def _check_size(where: str, speed_field: str, flight: float, extra_links: float,
                link: float, link_max: float, v: float, v_min: float, fit) -> None:
    """At most :data:`MAX_LINKS` links at the start: ``flight`` m of chain in flight plus
    ``extra_links``; names ``chain.link_length`` when longer links would do, else the speed
    (``fit(length)``: the fastest speed with at most ``length`` m in flight)."""
    n = flight / link + extra_links
    if n <= MAX_LINKS:
        return
    room = MAX_LINKS - extra_links
    link_need = flight / room if room > 0 else math.inf
    if link_need <= link_max:
        _fail(where, "chain.link_length",
              f"{link!r} m puts {n:.0f} links into the simulation ({flight:.4g} m of chain in "
              f"flight); allowed: at most {MAX_LINKS} links, here a link_length >= "
              f"{link_need:.4g} m (at most {link_max:.4g} m for this drop)")
    v_fit = fit(link_max * room) if room > 0 else v_min
    _fail(where, speed_field,
          f"{v!r} m/s throws {flight:.4g} m of chain into flight, {n:.0f} links even at the "
          f"longest link allowed ({link_max:.4g} m); allowed: at most {MAX_LINKS} links, here a "
          f"speed <= {v_fit:.4g} m/s (or stronger gravity, a lower launch angle)")


def _check_blocks_in_scene(sim: SimConfig, where: str) -> None:
    """Rollers and carts of a feed level lie inside the scene the divergence watchdog
    allows (:func:`chainfountain.sim.watchdog.limits_for`): a body beyond it would stop the
    run at once as diverged."""
    from chainfountain.sim.watchdog import limits_for

    reach = limits_for(sim).radius
    for i, r in enumerate(sim.rollers):
        d = math.hypot(r.x, r.y) + r.radius
        if d >= reach:
            _fail(where, f"rollers[{i}].x",
                  f"{r.x!r} m (with y = {r.y:g} m) puts the roller {d:.4g} m from the launch "
                  f"point, outside this level's scene; allowed: rollers within {reach:.4g} m "
                  "of the launch point")
    for i, c in enumerate(sim.carts):
        half = 0.5 * c.track_length + 0.5 * math.hypot(c.width, c.height)
        d = math.hypot(c.x, c.y) + half
        if d >= reach:
            _fail(where, f"carts[{i}].x",
                  f"{c.x!r} m (with y = {c.y:g} m and a {c.track_length:g} m track) lets the "
                  f"cart reach {d:.4g} m from the launch point, outside this level's scene; "
                  f"allowed: carts and their tracks within {reach:.4g} m of the launch point")


def _check_feed(level: Level, where: str) -> None:
    """Feed cross-field checks (paper: ``Tbar_E + k*H < 1`` for the launch)."""
    sim = level.sim
    feed = sim.feed
    g = sim.gravity
    v, H, te = feed.speed, feed.drop, feed.end_tension
    v_need = math.sqrt(g * H)
    if v <= v_need:
        with_te = (f" (with feed.end_tension = {te:g}: > sqrt(g*H/(1 - Tbar_E)) = "
                   f"{math.sqrt(g * H / (1.0 - te)):.4g} m/s)" if te > 0 else "")
        _fail(
            where, "feed.speed",
            f"{v!r} m/s cannot make a fountain that lands {H:g} m below "
            f"the launch point (k*H >= 1); allowed: a speed > sqrt(g*H) = {v_need:.4g} m/s"
            + with_te,
        )
    if te > 0 and feed.floor == "solid":
        _fail(where, "feed.end_tension",
              f"{te!r} has no effect with feed.floor = 'solid' (the pull on the chain end is "
              "the absorbing floor's; a solid floor only carries the pile); allowed: 0 with a "
              "solid floor")
    kH = g * H / v**2
    if te + kH >= 1.0:
        _fail(where, "feed.end_tension",
              f"{te!r} leaves no fountain at feed.speed = {v:g} m/s and feed.drop = {H:g} m "
              f"(Tbar_E + k*H = {te + kH:.4g}, k = g/v^2; the paper needs < 1); allowed: "
              f"Tbar_E < 1 - k*H = {1.0 - kH:.4g} at this speed and drop (this end tension "
              f"needs a speed > sqrt(g*H/(1 - Tbar_E)) = {math.sqrt(g * H / (1.0 - te)):.4g} "
              "m/s)")
    link_max = min(0.1 * H, 0.2)
    if sim.chain.link_length > 0.1 * H:
        _fail(
            where, "chain.link_length",
            f"{sim.chain.link_length!r} m is too coarse for a drop of {H:g} m; "
            f"allowed: at most a tenth of feed.drop ({0.1 * H:.4g} m)",
        )
    a0 = feed.launch_angle
    f = _fountain_or_fail(where, "feed.speed", v, a0, H, te, g)
    _check_size(where, "feed.speed", f.length, 0.0, sim.chain.link_length, link_max, v,
                v_need, lambda length: _fastest_fitting(v_need, v, a0, H, te, g, length))
    if feed.floor == "solid" and 0.5 * feed.floor_width <= f.l:
        _fail(where, "feed.floor_width",
              f"{feed.floor_width!r} m reaches {0.5 * feed.floor_width:g} m from the launch "
              f"point, short of where the fountain lands ({f.l:.4g} m), so the chain would "
              f"fall past the solid floor's end; allowed: a width > 2*l = {2.0 * f.l:.4g} m "
              "(the floor is centred on the launch point)")
    _check_blocks_in_scene(sim, where)
    init, default_init = sim.initial, InitialConfig()
    if init.mode == "catenary" and init.stub_length != default_init.stub_length:
        _fail(where, "initial.stub_length",
              f"{init.stub_length!r} m has no effect with initial.mode = 'catenary' (the chain "
              f"starts on the predicted fountain); allowed: {default_init.stub_length!r}, or "
              "initial.mode = 'stub'")


def _check_apparatus(level: Level, where: str) -> None:
    """Apparatus cross-field checks (paper: ``Tbar_E + k*H < 1`` for the launch)."""
    sim = level.sim
    a = sim.apparatus
    g = sim.gravity
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
        kH = g * a.drop / a.speed**2
        if a.end_tension > 0 and kH < 1.0:
            _fail(where, "apparatus.end_tension",
                  f"{a.end_tension!r} leaves no fountain at apparatus.speed = {a.speed:g} m/s "
                  f"and apparatus.drop = {a.drop:g} m (Tbar_E + k*H = {a.end_tension + kH:.4g}, "
                  f"k = g/v^2; the paper needs < 1); allowed: Tbar_E < 1 - k*H = {1.0 - kH:.4g} "
                  f"at this speed and drop (this end tension needs a speed > "
                  f"sqrt(g*H/(1 - Tbar_E)) = {v_need:.4g} m/s)")
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
    _check_apparatus_unused(sim, where)
    _check_apparatus_size(sim, where)
    _check_end_channel(sim, where)


ONLY_FOR_VARIANT: dict[str, tuple[str, ...]] = {
    "xi3": ("fold",),
    "end_pull": ("open",),
    "end": ("floor",),
    "floor_width": ("floor",),
}
"""Apparatus fields that only the named variants use: ``xi3`` is the lower table's height
(only 'fold' has one), ``end_pull`` pulls the chain sliding away ('open'), ``end`` and
``floor_width`` are the floor's (only 'floor' has one)."""


def _check_apparatus_unused(sim: SimConfig, where: str) -> None:
    """Settings an apparatus level would ignore are refused: another variant's fields,
    ``[[rollers]]``, and carts beyond the ones its rollers take."""
    a, default = sim.apparatus, type(sim.apparatus)()
    for name, variants in ONLY_FOR_VARIANT.items():
        value = getattr(a, name)
        if a.variant not in variants and value != getattr(default, name):
            only = " or ".join(repr(v) for v in variants)
            _fail(where, f"apparatus.{name}",
                  f"{value!r} has no effect with apparatus.variant = {a.variant!r} (only "
                  f"{only} uses it); allowed: {getattr(default, name)!r}")
    if sim.rollers:
        _fail(where, "rollers",
              f"{len(sim.rollers)} [[rollers]] have no effect in an 'apparatus' level (it "
              "builds its own rollers); allowed: none (rollers = [])")
    n_carts = 2 if a.variant == "fold" else 1
    if len(sim.carts) > n_carts:
        which = ("carts[0] pulls the pick-up roller, carts[1] pushes the folding roller"
                 if n_carts == 2 else "carts[0] pulls the pick-up roller")
        _fail(where, f"carts[{n_carts}]",
              f"has no effect with apparatus.variant = {a.variant!r} ({which}); allowed: at "
              f"most {n_carts} [[carts]]")


def _check_end_channel(sim: SimConfig, where: str) -> None:
    """'fold': the end channel's two bends fit into the rise ``xi3*H`` (or it is zero)."""
    from chainfountain.sim.guide import end_channel_bends, end_channel_min_rise

    a = sim.apparatus
    rise = a.xi3 * a.drop
    if a.variant != "fold" or rise <= 1e-9:
        return
    f = _fountain_or_fail(where, "apparatus.speed", a.speed, a.launch_angle, a.drop,
                          a.end_tension, sim.gravity)
    try:
        end_channel_bends(f.alphaE, rise, a.channel_radius)
    except ValueError:
        least = end_channel_min_rise(f.alphaE, a.channel_radius) / a.drop
        _fail(where, "apparatus.xi3",
              f"{a.xi3!r} lifts the chain only {rise:.3g} m, too little for the end channel's "
              f"two bends at this landing angle; allowed: 0 or at least {least:.4g} "
              f"(a rise of {least * a.drop:.3g} m)")


def _check_apparatus_size(sim: SimConfig, where: str) -> None:
    """At most :data:`MAX_LINKS` links at the start: the chain in flight, and the upper
    plate strand that spans the pick-up roller's travel (``v/2`` for ``duration``) unless
    the plate is a treadmill."""
    a, g, L = sim.apparatus, sim.gravity, sim.chain.link_length
    d = a.floor_depth if a.variant == "floor" else 0.0
    te = a.end_tension + g * d / a.speed**2
    f = _fountain_or_fail(where, "apparatus.speed", a.speed, a.launch_angle, a.drop, te, g)
    v_min = math.sqrt(g * (a.drop + d) / (1.0 - a.end_tension))
    _check_size(where, "apparatus.speed", f.length, 0.0, L, min(0.1 * a.drop, 0.2), a.speed,
                v_min, lambda length: _fastest_fitting(v_min, a.speed, a.launch_angle, a.drop,
                                                       a.end_tension, g, length, d))
    if a.plate_links > 0 and a.plate == "groove":
        return
    n = (f.length + 0.5 * a.speed * a.duration + 0.15) / L
    if n > MAX_LINKS:
        room = (MAX_LINKS * L - f.length - 0.15) / (0.5 * a.speed)
        _fail(where, "apparatus.duration",
              f"{a.duration!r} s sizes the upper plate for {0.5 * a.speed * a.duration:.4g} m of "
              f"roller travel (v/2 for the duration): {n:.0f} links at the start; allowed: at "
              f"most {MAX_LINKS} links, here a duration <= {max(room, 0.0):.4g} s (or "
              "apparatus.plate_links > 0, a treadmill, for runs of any length)")


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


def shown_path(path: str | Path) -> str:
    """A file name as messages show it: as it is, or quoted when it holds a newline or
    another character that is not printable (a message stays one line)."""
    text = str(path)
    return text if text.isprintable() else repr(text)


def _parse_toml(text: str, where: str) -> dict[str, Any]:
    """The TOML document in ``text``; :class:`LevelError` (one line) when it is not one."""
    try:
        return tomllib.loads(text)
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
        text = raw.decode("utf-8")
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
        "Besides the per-key ranges the loader checks that the fountain exists, fits the "
        "simulator and that every setting given has an effect:",
        "",
        "- the paper's condition `Tbar_E + k*H < 1` with `k = gravity / speed^2`: for "
        "`kind = \"feed\"`, `feed.speed > sqrt(gravity * feed.drop / (1 - "
        "feed.end_tension))` (else no inverted catenary reaches the floor), likewise "
        "`apparatus.speed` with `apparatus.drop` and `apparatus.end_tension` (and "
        "`apparatus.floor_depth`);",
        "- `chain.link_length <= drop / 10`, and at most "
        f"{MAX_LINKS} links at the start: the chain in flight on the predicted fountain, "
        "plus an apparatus's upper plate strand (`apparatus.speed / 2 * apparatus.duration` "
        "long unless `apparatus.plate_links` makes it a treadmill);",
        "- a solid feed floor (`feed.floor = \"solid\"`) reaches past the predicted landing "
        "point and has `feed.end_tension = 0` (the pull is the absorbing floor's); the "
        "rollers and carts of a feed level lie within the scene the divergence watchdog "
        "allows (ten times the level's size plus 20 m from the launch point);",
        "- settings that would have no effect are refused: the `[apparatus]` table in a feed "
        "level and the `[feed]` table in an apparatus level (other than their defaults), "
        "`initial.stub_length` with `initial.mode = \"catenary\"`; in an apparatus level "
        "`[initial]` other than its defaults, `[[rollers]]`, carts beyond those its rollers "
        "take (`carts[0]`; `carts[1]` in 'fold'), and `apparatus.xi3` "
        "(other than 'fold'), `apparatus.end_pull` (other than 'open'), `apparatus.end` "
        "and `apparatus.floor_width` (other than 'floor') away from their defaults.",
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
    "shown_path",
]
