"""Field declarations for level dataclasses.

Every configurable number of the model is declared with :func:`param`, which
records its SI unit, a one-line description and the allowed range in the
dataclass field metadata. The level loader (``chainfountain.level.io``) uses
that metadata to validate files and to build error messages that name the
field, the value and what is allowed; the app uses it to bound sliders.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import re
import typing
from typing import Any


def param(
    default: Any,
    *,
    unit: str,
    doc: str,
    min: float | None = None,  # noqa: A002 - mirrors the metadata key
    max: float | None = None,  # noqa: A002
    min_inclusive: bool = True,
    max_inclusive: bool = True,
    choices: tuple[Any, ...] | None = None,
    live: bool = False,
) -> Any:
    """Declare a level parameter.

    Parameters
    ----------
    default:
        Value used when the level file omits the field. Use ``REQUIRED`` for
        fields a file must give.
    unit:
        SI unit ("m", "kg", "kg/m", "s", "N", "rad", "N*m/rad", "1" for
        dimensionless, "" for text).
    doc:
        One line shown in ``docs/levels.md``, in error messages and as a tooltip.
    min, max, min_inclusive, max_inclusive:
        Allowed numeric range.
    choices:
        Allowed values for a text or enumerated field.
    live:
        True when a running simulation can take a change of this field without
        a rebuild (the app applies it live).
    """
    meta = {
        "unit": unit,
        "doc": doc,
        "min": min,
        "max": max,
        "min_inclusive": min_inclusive,
        "max_inclusive": max_inclusive,
        "choices": choices,
        "live": live,
    }
    if default is REQUIRED:
        return dataclasses.field(metadata=meta)
    if isinstance(default, list | dict):
        return dataclasses.field(default_factory=lambda: type(default)(default), metadata=meta)
    return dataclasses.field(default=default, metadata=meta)


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


REQUIRED: Any = _Required()


def allowed_text(meta: dict[str, Any]) -> str:
    """Human-readable description of what a field allows, e.g. ``a number > 0 (m)``."""
    if meta.get("choices"):
        return "one of " + ", ".join(repr(c) for c in meta["choices"])
    lo, hi = meta.get("min"), meta.get("max")
    unit = meta.get("unit") or ""
    suffix = f" ({unit})" if unit and unit != "1" else ""
    lo_op = ">=" if meta.get("min_inclusive", True) else ">"
    hi_op = "<=" if meta.get("max_inclusive", True) else "<"
    if lo is not None and hi is not None:
        lo_br = "[" if meta.get("min_inclusive", True) else "("
        hi_br = "]" if meta.get("max_inclusive", True) else ")"
        return f"a number in {lo_br}{lo:g}, {hi:g}{hi_br}{suffix}"
    if lo is not None:
        return f"a number {lo_op} {lo:g}{suffix}"
    if hi is not None:
        return f"a number {hi_op} {hi:g}{suffix}"
    return f"a finite number{suffix}"


def in_range(value: float, meta: dict[str, Any]) -> bool:
    """True when ``value`` is finite and inside the range declared in ``meta`` (an integer
    of any size is compared exactly)."""
    if not isinstance(value, int) and not math.isfinite(value):
        return False
    lo, hi = meta.get("min"), meta.get("max")
    if lo is not None and (value < lo or (value == lo and not meta.get("min_inclusive", True))):
        return False
    if hi is not None and (value > hi or (value == hi and not meta.get("max_inclusive", True))):
        return False
    return True


def tuple_item_type(tp: Any) -> Any | None:
    """``X`` for a ``tuple[X, ...]`` annotation (arrays of tables in level files), else None."""
    if typing.get_origin(tp) is tuple:
        args = typing.get_args(tp)
        if len(args) == 2 and args[1] is Ellipsis:
            return args[0]
    return None


@functools.cache
def type_hints(cls: type) -> dict[str, Any]:
    """``typing.get_type_hints(cls)``, once per class: the config classes do not change
    while a program runs, and resolving their string annotations took a third of the
    window's slider-span search (0.8 s a panel rebuild)."""
    return typing.get_type_hints(cls)


def iter_numeric_fields(obj: Any, prefix: str = "") -> typing.Iterator[tuple[str, Any, dict]]:
    """``(path, python type, metadata)`` of every int/float leaf of a config instance."""
    hints = type_hints(type(obj))
    for f in dataclasses.fields(obj):
        val = getattr(obj, f.name)
        tp = hints[f.name]
        path = prefix + f.name
        if dataclasses.is_dataclass(val):
            yield from iter_numeric_fields(val, path + ".")
        elif isinstance(val, tuple) and tuple_item_type(tp) is not None:
            for i, item in enumerate(val):
                if dataclasses.is_dataclass(item):
                    yield from iter_numeric_fields(item, f"{path}[{i}].")
        elif tp in (int, float):
            yield path, tp, dict(f.metadata)


_TOKEN = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)(?:\[(\d+)\])?")


def parse_path(path: str) -> list[tuple[str, int | None]]:
    """``"carts[1].mass"`` -> ``[("carts", 1), ("mass", None)]``."""
    out: list[tuple[str, int | None]] = []
    for part in path.split("."):
        m = _TOKEN.fullmatch(part)
        if m is None:
            raise KeyError(path)
        out.append((m.group(1), None if m.group(2) is None else int(m.group(2))))
    return out


def _owner(obj: Any, path: str) -> tuple[Any, str]:
    """The object holding the last field of ``path`` and that field's name; ``KeyError``
    when ``obj`` has no such field (a list item beyond its list included)."""
    parts = parse_path(path)
    for name, idx in parts[:-1]:
        obj = getattr(obj, name)
        if idx is not None:
            if not -len(obj) <= idx < len(obj):
                raise KeyError(path)
            obj = obj[idx]
    name, idx = parts[-1]
    if idx is not None:
        raise KeyError(path)
    if not hasattr(obj, name):
        raise KeyError(path)
    return obj, name


def get_value(config: Any, path: str) -> Any:
    """Value of a dotted field path (``"carts[1].mass"``) in a config dataclass."""
    obj, name = _owner(config, path)
    return getattr(obj, name)


def set_value(config: Any, path: str, value: Any) -> None:
    """Set a dotted field path in a (mutable) config dataclass in place."""
    obj, name = _owner(config, path)
    setattr(obj, name, value)
