"""Mutated level files: hypothesis strategies and the checks every mutant must pass.

Shared by ``tests/level/test_fuzz_levels.py`` (a few hundred mutants) and
``benchmarks/fuzz_levels.py`` (ten thousand and more); pytest does not collect this
module. A mutant starts from one of the shipped levels in ``levels/*.toml`` and is

- *structured*: the TOML is parsed, one to four keys get a value of the wrong type, NaN,
  an infinity, zero, a negative, huge or tiny number, a value at or just past the field's
  declared limit, a scaled value, or are deleted; unknown keys (any text, newlines
  included) are added, tables become scalars or arrays, arrays of tables become tables,
  ``[[carts]]``/``[[rollers]]`` entries are added, the kind is switched or another
  level's table is copied in; the result is written back as TOML;
- *textual*: the file is truncated, lines are dropped or repeated (duplicate keys), a
  value is replaced by a raw TOML token (``nan``, ``inf``, ``1e999``, ``0x1F``, a date,
  an unterminated string ...), or random characters are inserted;
- *binary*: random bytes, invalid UTF-8 spliced into the text, NUL bytes, a byte order
  mark, an empty file.

:func:`check_file` is the level check's contract: :func:`chainfountain.level.io.load`
either accepts the file or raises :class:`~chainfountain.level.io.LevelError` whose
message is one line, starts with the file's path and names a field (or says the file is
not valid TOML or not UTF-8); anything else is a failure. :func:`run_briefly` is the
simulator's: an accepted level builds and runs for 0.3 s, and the only exception
allowed is :class:`~chainfountain.errors.RunEnded` (a run that stops itself).
"""

from __future__ import annotations

import copy
import dataclasses
import datetime
import math
import re
import time
import tomllib
import typing
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import tomli_w
from hypothesis import strategies as st

from chainfountain.errors import RunEnded
from chainfountain.fields import tuple_item_type
from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim.config import CartConfig, RollerConfig, SimConfig

LEVELS_DIR = shipped_dir()
SHIPPED: dict[str, str] = {p.stem: p.read_text(encoding="utf-8")
                           for p in sorted(LEVELS_DIR.glob("*.toml"))}
"""Text of every shipped level, by name."""

CHEAP: tuple[str, ...] = tuple(n for n in ("classroom", "paper_tall", "wide_low",
                                            "apparatus_floor", "apparatus_floor_heavy",
                                            "apparatus_special", "apparatus_open")
                               if n in SHIPPED)
"""Shipped levels that run 0.3 s in well under a second (bases of the run checks)."""


# ----------------------------------------------------------------------------- the schema
def _schema_fields(cls: type, prefix: str = "") -> dict[str, tuple[Any, dict[str, Any]]]:
    """``{dotted path: (python type, metadata)}`` of every leaf field, array entries as
    ``carts[].mass``; tables and arrays of tables appear with type ``dict``/``list``."""
    out: dict[str, tuple[Any, dict[str, Any]]] = {}
    hints = typing.get_type_hints(cls)
    for f in dataclasses.fields(cls):
        tp = hints[f.name]
        item = tuple_item_type(tp)
        path = prefix + f.name
        if isinstance(tp, type) and dataclasses.is_dataclass(tp):
            out[path] = (dict, {})
            out.update(_schema_fields(tp, path + "."))
        elif item is not None and dataclasses.is_dataclass(item):
            out[path] = (list, {})
            out[path + "[]"] = (dict, {})
            out.update(_schema_fields(item, path + "[]."))
        else:
            out[path] = (tp, dict(f.metadata))
    return out


FIELDS: dict[str, tuple[Any, dict[str, Any]]] = {
    "schema_version": (int, {}),
    "meta": (dict, {}),
    **_schema_fields(io.Meta, "meta."),
    **_schema_fields(SimConfig),
}
"""Every key a level file may have (``name`` is set through ``meta.name``)."""
FIELDS.pop("name", None)

_PATH_RX = re.compile(r"[A-Za-z_]\w*(\[\d+\])?(\.[A-Za-z_]\w*(\[\d+\])?)*")
_INDEX_RX = re.compile(r"\[\d+\]")
_UNKNOWN_RX = re.compile(r"(?:(?P<parent>.*?)\.)?(?P<key>'.*'|\".*\"|[A-Za-z_]\w*)")
"""An unknown key in a message: its table's path, a dot, the key (quoted unless plain)."""


def schema_path(field: str) -> str:
    """``carts[3].mass`` -> ``carts[].mass`` (the key of :data:`FIELDS`)."""
    return _INDEX_RX.sub("[]", field)


# ----------------------------------------------------------------------------- the contract
@dataclass
class Verdict:
    """What the level check said about one file."""

    accepted: bool
    message: str = ""
    level: io.Level | None = None


def message_problem(msg: str, where: str) -> str | None:
    """Why a refusal's message breaks the contract (None when it keeps it): one line,
    starting with ``where``, then a field of the schema (or an unknown key under a known
    table, or the whole file: not valid TOML, not UTF-8)."""
    if len(msg.splitlines()) != 1 or "\n" in msg or "\r" in msg:
        return "the message is not one line"
    head = f"{where}: "
    if not msg.startswith(head):
        return "the message does not start with the file's path"
    rest = msg[len(head):]
    if rest.startswith(("not valid TOML (", "not a UTF-8 text file")):
        return None
    field, sep, why = rest.partition(": ")
    if not sep or not why.strip():
        return "the message names no field and no reason"
    if field == "top level":
        return None
    if why.startswith("unknown key"):
        m = _UNKNOWN_RX.fullmatch(field)
        if m is None:
            return f"the unknown key {field!r} is not shown plainly"
        parent = m.group("parent")
        if parent is not None and schema_path(parent) not in FIELDS:
            return f"the unknown key's table {parent!r} is not a table of the schema"
        return None
    if not _PATH_RX.fullmatch(field) or schema_path(field) not in FIELDS:
        return f"{field!r} is not a field of the schema"
    return None


def check_file(path: Path) -> Verdict:
    """The level check of one file; raises AssertionError when the contract is broken
    (any exception other than LevelError propagates as it is)."""
    try:
        level = io.load(path)
    except io.LevelError as exc:
        msg = str(exc)
        problem = message_problem(msg, str(path))
        if problem:
            raise AssertionError(f"{problem}: {msg!r}") from None
        return Verdict(False, msg)
    return Verdict(True, level=level)


def check_text(data: bytes, path: Path) -> Verdict:
    """:func:`check_file` on ``data`` written to ``path``; when the bytes are UTF-8 text,
    :func:`chainfountain.level.io.loads` must give the same verdict, and an accepted level
    must survive a save and load unchanged."""
    path.write_bytes(data)
    verdict = check_file(path)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        text = None
    if text is not None:
        try:
            same = io.loads(text, str(path))
        except io.LevelError as exc:
            assert not verdict.accepted, f"loads refused what load accepted: {exc}"
            assert str(exc) == verdict.message, (str(exc), verdict.message)
        else:
            assert verdict.accepted, f"loads accepted what load refused: {verdict.message}"
            assert same == verdict.level
    if verdict.level is not None:
        back = io.loads(io.dumps(verdict.level), "<saved>")
        assert back == verdict.level, "an accepted level does not survive a save and load"
    return verdict


@dataclass
class RunResult:
    """How a short run of an accepted level went."""

    status: str
    """``"ran"`` (the whole span), ``"stopped"`` (a RunEnded) or ``"cut"`` (wall limit)."""
    reason: str = ""
    """The RunEnded's class name and first words, for ``"stopped"``."""
    simulated: float = 0.0
    wall: float = 0.0


def run_briefly(level: io.Level, seconds: float = 0.3,
                wall_limit: float | None = None) -> RunResult:
    """Build the level's :class:`~chainfountain.sim.Simulation` and run it ``seconds``
    (or until ``wall_limit`` wall seconds have passed). A RunEnded is a result; any
    other exception propagates."""
    from chainfountain.sim import Simulation

    t0 = time.perf_counter()
    sim = Simulation(level.sim)
    n = int(round(seconds / sim.dt))
    try:
        for i in range(n):
            sim.step()
            if wall_limit is not None and i % 64 == 63 and \
                    time.perf_counter() - t0 > wall_limit:
                return RunResult("cut", simulated=sim.time, wall=time.perf_counter() - t0)
    except RunEnded as exc:
        first = re.sub(r"[-+]?\d[\d.e+-]*", "#", str(exc).split(";")[0].split(" (")[0])
        return RunResult("stopped", f"{type(exc).__name__}: {first[:90]}", sim.time,
                         time.perf_counter() - t0)
    return RunResult("ran", simulated=sim.time, wall=time.perf_counter() - t0)


# ----------------------------------------------------------------------------- values
WEIRD: tuple[Any, ...] = (
    math.nan, math.inf, -math.inf, 0, 0.0, -0.0, -1, -1.0, -1e-9, 1e308, -1e308, 5e-324,
    1e-300, 1e300, 2**63 - 1, -(2**63), 10**400, True, False, "", "abc", "nan", "1.5",
    "\n", "a\nb", [], [1, 2], [1.5, "x"], {}, {"a": 1}, [{"a": 1}],
    datetime.date(2024, 1, 1), datetime.time(12, 30),
    datetime.datetime(1979, 5, 27, 7, 32, tzinfo=datetime.UTC),
)
"""Values of the wrong type or out of any sensible range."""

_WEIRD_VALUES = st.sampled_from(WEIRD).map(copy.deepcopy)  # later mutations may change it

RAW_TOKENS: tuple[str, ...] = (
    "nan", "+nan", "-nan", "inf", "+inf", "-inf", "1e999", "-1e999", "0x1F", "0o17", "0b101",
    "1_000", "1__0", "01", ".5", "5.", "1e", "--1", "1,5", '"str"', "'lit'", '"""multi',
    '"unterminated', "[1,", "[1, 2]", "{", "{ a = 1 }", "true", "True", "1979-05-27",
    "07:32:00", "1979-05-27T07:32:00Z", "", "=", "[[x]]", "\\u0000", "9" * 400,
    "9" * 5000, "[" * 3000 + "]" * 3000, "{ a = " * 3000 + "1" + " }" * 3000,
)
"""Raw right-hand sides spliced into the text (many are not TOML at all)."""

KEY_TEXT = st.one_of(
    st.sampled_from(["sped", "speeed", "Speed", "link length", "a.b", "", "\n", "x\ny",
                     "carts", "feed", "kind", "gravity", "\u2028", "\x00"]),
    st.text(max_size=12),
)


def _numbers(meta: dict[str, Any]) -> list[Any]:
    """Values at and just past a field's declared limits."""
    out: list[Any] = []
    for key, sign in (("min", -1.0), ("max", 1.0)):
        b = meta.get(key)
        if b is None:
            continue
        out += [b, math.nextafter(b, sign * math.inf), b + sign * max(abs(b), 1.0),
                b * (1 + sign * 1e-9) if b else sign * 1e-12]
    return out


def _leaves(obj: Any, prefix: tuple = ()) -> list[tuple]:
    """Paths (tuples of keys and indices) of every value in a parsed TOML document."""
    out: list[tuple] = []
    if isinstance(obj, dict):
        for k, v in obj.items():
            out.append((*prefix, k))
            out += _leaves(v, (*prefix, k))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            if isinstance(v, dict | list):
                out.append((*prefix, i))
                out += _leaves(v, (*prefix, i))
    return out


def _get(doc: Any, path: tuple) -> Any:
    for k in path:
        doc = doc[k]
    return doc


def _set(doc: Any, path: tuple, value: Any) -> None:
    _get(doc, path[:-1])[path[-1]] = value


def _delete(doc: Any, path: tuple) -> None:
    parent = _get(doc, path[:-1])
    del parent[path[-1]]


def _dotted(path: tuple) -> str:
    """``("carts", 0, "mass")`` -> ``carts[].mass``."""
    out = ""
    for k in path:
        out += "[]" if isinstance(k, int) else (f".{k}" if out else str(k))
    return out


def _tables(doc: dict) -> list[tuple]:
    return [()] + [p for p in _leaves(doc) if isinstance(_get(doc, p), dict)]


# ----------------------------------------------------------------------------- mutations
@st.composite
def _value_for(draw: st.DrawFn, path: tuple, old: Any) -> Any:
    """A replacement value for the key at ``path`` (old value ``old``)."""
    tp, meta = FIELDS.get(_dotted(path), (None, {}))
    choices = ["weird", "float", "int", "text"]
    if isinstance(old, int | float) and not isinstance(old, bool):
        choices += ["scale", "scale", "scale", "bound", "bound"]
    if meta.get("choices"):
        choices += ["choice"]
    kind = draw(st.sampled_from(choices))
    if kind == "weird":
        return draw(_WEIRD_VALUES)
    if kind == "float":
        return draw(st.floats(allow_nan=True, allow_infinity=True))
    if kind == "int":
        return draw(st.integers(min_value=-(2**70), max_value=2**70))
    if kind == "text":
        return draw(st.text(max_size=20))
    if kind == "choice":
        return draw(st.sampled_from([*meta["choices"], "nope", meta["choices"][0].upper()]))
    if kind == "bound":
        return draw(st.sampled_from(_numbers(meta) or [0.0, -1.0]))
    factor = draw(st.sampled_from([0.0, -1.0, 1e-3, 0.5, 0.9, 0.99, 1.01, 1.1, 2.0, 10.0,
                                   1e3, 1e9]))
    try:
        new = old * factor
    except OverflowError:  # an integer beyond any float (a "weird" value) stays as it is
        return old
    return int(new) if isinstance(old, int) and abs(new) < 2**63 else float(new)


@st.composite
def _entry(draw: st.DrawFn, array: str, cls: type) -> dict[str, Any]:
    """A ``[[carts]]`` or ``[[rollers]]`` entry with some fields, some of them odd."""
    names = [f.name for f in dataclasses.fields(cls)]
    picked = draw(st.lists(st.sampled_from(names), max_size=len(names), unique=True))
    out: dict[str, Any] = {}
    for name in picked:
        default = getattr(cls(), name)
        out[name] = draw(st.one_of(st.just(default), _value_for((array, 0, name), default)))
    return out


@st.composite
def _mutate_doc(draw: st.DrawFn, doc: dict) -> str:
    """Apply one structural mutation to ``doc`` in place; returns what it did."""
    leaves = _leaves(doc)
    op = draw(st.sampled_from(["value", "value", "value", "value", "delete", "unknown",
                               "reshape", "entry", "kind", "transplant"]))
    if op == "value" and leaves:
        path = draw(st.sampled_from(leaves))
        new = draw(_value_for(path, _get(doc, path)))
        _set(doc, path, new)
        return f"{_dotted(path)} = {new!r}"
    if op == "delete" and leaves:
        path = draw(st.sampled_from(leaves))
        _delete(doc, path)
        return f"del {_dotted(path)}"
    if op == "unknown":
        where = draw(st.sampled_from(_tables(doc)))
        key = draw(KEY_TEXT)
        value = draw(_WEIRD_VALUES)
        _get(doc, where)[key] = value
        return f"{_dotted((*where, key))} = {value!r} (unknown)"
    if op == "reshape":
        tables = [p for p in leaves if isinstance(_get(doc, p), dict | list)]
        if tables:
            path = draw(st.sampled_from(tables))
            old = _get(doc, path)
            new = draw(st.sampled_from([1, "x", [], [old] if isinstance(old, dict) else
                                        (old[0] if old else {}), {"x": 1}, [1, 2]]))
            _set(doc, path, new)
            return f"{_dotted(path)} reshaped to {type(new).__name__}"
    if op == "entry":
        name = draw(st.sampled_from(["carts", "rollers"]))
        cls = CartConfig if name == "carts" else RollerConfig
        entries = doc.get(name)
        if not isinstance(entries, list):
            entries = doc[name] = []
        entries.append(draw(_entry(name, cls)))
        return f"{name} += entry"
    if op == "kind":
        new = draw(st.sampled_from(["feed", "apparatus", "Feed", "belt", 1]))
        doc["kind"] = new
        return f"kind = {new!r}"
    if op == "transplant":
        other = tomllib.loads(SHIPPED[draw(st.sampled_from(sorted(SHIPPED)))])
        tables = [k for k, v in other.items() if isinstance(v, dict | list) and k != "meta"]
        if tables:
            key = draw(st.sampled_from(tables))
            doc[key] = other[key]
            return f"{key} from another level"
    return "unchanged"


@st.composite
def structured(draw: st.DrawFn, bases: tuple[str, ...] | None = None) -> tuple[str, bytes]:
    """A shipped level with one to four structural mutations, written back as TOML."""
    base = draw(st.sampled_from(bases or tuple(SHIPPED)))
    doc = tomllib.loads(SHIPPED[base])
    done = [draw(_mutate_doc(doc)) for _ in range(draw(st.integers(1, 4)))]
    try:
        text = tomli_w.dumps(doc)
    except (TypeError, ValueError):  # a value tomli_w cannot write: keep the base text
        text = SHIPPED[base]
        done.append("(not writable, base kept)")
    return f"{base}: " + "; ".join(done), text.encode("utf-8")


@st.composite
def near_valid(draw: st.DrawFn, bases: tuple[str, ...] = CHEAP) -> tuple[str, bytes]:
    """A cheap shipped level with one to three numbers scaled or set to their limits (many
    are accepted: the material of the run checks)."""
    base = draw(st.sampled_from(bases))
    doc = tomllib.loads(SHIPPED[base])
    numeric = [p for p in _leaves(doc) if isinstance(_get(doc, p), int | float)
               and not isinstance(_get(doc, p), bool) and p[0] != "schema_version"]
    done = []
    for _ in range(draw(st.integers(1, 3))):
        path = draw(st.sampled_from(numeric))
        old = _get(doc, path)
        tp, meta = FIELDS.get(_dotted(path), (None, {}))
        new = draw(st.one_of(
            st.sampled_from([0.5, 0.8, 0.95, 1.05, 1.25, 2.0]).map(lambda f, o=old: o * f),
            st.sampled_from(_numbers(meta) or [old]),
        ))
        if isinstance(old, int):
            new = int(round(new)) if math.isfinite(new) else old
        _set(doc, path, new)
        done.append(f"{_dotted(path)} = {new!r}")
    return f"{base}: " + "; ".join(done), tomli_w.dumps(doc).encode("utf-8")


@st.composite
def textual(draw: st.DrawFn) -> tuple[str, bytes]:
    """A shipped level's text truncated, with lines dropped or repeated, a raw token as a
    value, or random characters inserted."""
    base = draw(st.sampled_from(tuple(SHIPPED)))
    text = SHIPPED[base]
    lines = text.splitlines(keepends=True)
    op = draw(st.sampled_from(["truncate", "drop", "repeat", "token", "token", "insert"]))
    if op == "truncate":
        n = draw(st.integers(0, len(text)))
        return f"{base}: truncated at {n}", text[:n].encode("utf-8")
    i = draw(st.integers(0, len(lines) - 1))
    if op == "drop":
        del lines[i]
    elif op == "repeat":
        lines.insert(i, lines[i])
    elif op == "token":
        valued = [j for j, ln in enumerate(lines) if " = " in ln]
        i = draw(st.sampled_from(valued))
        key = lines[i].split(" = ", 1)[0]
        tok = draw(st.sampled_from(RAW_TOKENS))
        lines[i] = f"{key} = {tok}\n"
    else:
        pos = draw(st.integers(0, len(lines[i])))
        junk = draw(st.text(min_size=1, max_size=8))
        lines[i] = lines[i][:pos] + junk + lines[i][pos:]
    return f"{base}: {op} line {i}", "".join(lines).encode("utf-8", "surrogatepass")


@st.composite
def binary(draw: st.DrawFn) -> tuple[str, bytes]:
    """Random bytes, invalid UTF-8 spliced into a level, NUL bytes, a BOM, an empty file."""
    op = draw(st.sampled_from(["random", "splice", "nul", "bom", "empty", "utf16"]))
    if op == "random":
        return "random bytes", draw(st.binary(max_size=256))
    if op == "empty":
        return "empty file", b""
    base = draw(st.sampled_from(tuple(SHIPPED)))
    data = SHIPPED[base].encode("utf-8")
    if op == "bom":
        return f"{base}: BOM", b"\xef\xbb\xbf" + data
    if op == "utf16":
        return f"{base}: UTF-16", SHIPPED[base].encode("utf-16")
    pos = draw(st.integers(0, len(data)))
    junk = draw(st.sampled_from([b"\xff", b"\xfe\xff", b"\xc3\x28", b"\xed\xa0\x80",
                                 b"\x80", b"\xf8\x88\x80\x80\x80"])) if op == "splice" \
        else b"\x00" * draw(st.integers(1, 4))
    return f"{base}: {op} at {pos}", data[:pos] + junk + data[pos:]


def mutants() -> st.SearchStrategy[tuple[str, bytes]]:
    """Every kind of mutant (structured ones most often): ``(description, file bytes)``."""
    return st.one_of(structured(), structured(), structured(), near_valid(), textual(),
                     binary())
