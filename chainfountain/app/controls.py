"""Control specifications generated from the level schema (no pygame here).

Every number a level has is declared with :func:`chainfountain.fields.param`
(unit, doc, min, max, live). :func:`control_fields` walks a level's
:class:`~chainfountain.sim.config.SimConfig` instance (so array entries such as
``carts[1].mass`` appear when the level has carts) and returns a
:class:`FieldSpec` for every field that matches :data:`CONTROL_PATTERNS`, in
that order. The panel builds one slider and one text field per spec; a value
outside the declared range is clamped by :meth:`FieldSpec.clamp`, which says so.
"""

from __future__ import annotations

import bisect
import math
import re
from dataclasses import dataclass
from typing import Any

from chainfountain.fields import allowed_text, get_value, iter_numeric_fields

CONTROL_PATTERNS: tuple[str, ...] = (
    r"(feed|apparatus)\.speed",
    r"(feed|apparatus)\.launch_angle",
    r"(feed|apparatus|beaker)\.drop",
    r"beaker\.pile_depth",
    r"chain\.bend_limit",
    r"feed\.end_tension",
    r"(.*\.)?xi2",
    r"(.*\.)?xi3",
    r"feed\.cart_force",
    r"feed\.lower_cart_force",
    r"feed\.bearing_drag",
    r"feed\.turn_drop",
    r"apparatus\.floor_depth",
    r"apparatus\.fold_clearance",
    r"apparatus\.bearing_drag",
    r"apparatus\.fold_brake",
    r"apparatus\.swing_damper",
    r"carts\[\d+\]\.mass",
    r"carts\[\d+\]\.incline",
    r"(.*\.)?launch_speed",
    r"chain\.bending_stiffness",
    r"chain\.bending_damping",
    r"chain\.link_length",
    r"chain\.friction",
    r"rollers\[\d+\]\.angular_speed",
)
"""Which schema fields get a control, in panel order (full-match regular expressions)."""

LABELS: dict[str, str] = {
    "feed.speed": "launch speed v",
    "feed.launch_angle": "launch angle alpha0",
    "feed.drop": "drop H",
    "feed.end_tension": "floor pull Tbar_E",
    "feed.xi2": "beaker below start xi2",
    "feed.xi3": "bottom above end xi3",
    "feed.cart_force": "upper cart F_uc",
    "feed.lower_cart_force": "lower cart F_lc",
    "feed.bearing_drag": "bearing drag c",
    "feed.turn_drop": "turn drop to the plate d",
    "apparatus.speed": "start speed v0",
    "apparatus.launch_angle": "launch angle alpha0",
    "apparatus.drop": "drop H",
    "apparatus.floor_depth": "floor below end d",
    "apparatus.fold_clearance": "fold clearance",
    "apparatus.bearing_drag": "bearing drag c",
    "apparatus.fold_brake": "fold brake c_b",
    "apparatus.swing_damper": "swing damper c_s",
    "apparatus.xi2": "beaker below start xi2",
    "apparatus.xi3": "bottom above end xi3",
    "carts[0].mass": "upper cart mass",
    "carts[1].mass": "lower cart mass",
    "carts[0].incline": "upper cart's track beta",
    "carts[1].incline": "lower cart's track beta",
    "beaker.drop": "drop H (rim to floor)",
    "beaker.pile_depth": "pile below the rim",
    "chain.bend_limit": "largest bend per joint",
    "chain.bending_stiffness": "bending stiffness c",
    "chain.bending_damping": "bending damping d",
    "chain.link_length": "link length",
    "chain.friction": "friction",
}

STUDENT_LABELS: dict[str, str] = {
    "feed.speed": "launch speed",
    "apparatus.speed": "start speed",
    "feed.launch_angle": "launch angle",
    "apparatus.launch_angle": "launch angle",
    "feed.drop": "drop to the floor",
    "apparatus.drop": "drop to the end",
    "beaker.drop": "drop from the rim",
    "beaker.pile_depth": "pile below the rim",
    "carts[0].mass": "upper cart",
    "carts[1].mass": "lower cart",
    "carts[0].incline": "upper ramp's slope",
    "carts[1].incline": "lower ramp's slope",
    "feed.cart_force": "upper cart's pull",
    "feed.lower_cart_force": "lower cart's pull",
    "feed.xi2": "upper table, x drop below",
    "apparatus.xi2": "upper table, x drop below",
    "feed.xi3": "lower table, x drop above",
    "apparatus.xi3": "lower table, x drop above",
    "feed.bearing_drag": "friction in the bearings",
    "apparatus.bearing_drag": "friction in the bearings",
    "apparatus.fold_brake": "folding roller's brake",
    "apparatus.swing_damper": "swing damper",
    "apparatus.floor_depth": "floor below the end",
    "feed.turn_drop": "drop onto the plate",
    "chain.friction": "chain's friction",
    "chain.bending_stiffness": "chain's stiffness",
    "chain.bending_damping": "chain's damping",
    "chain.bend_limit": "chain's largest bend",
    "chain.link_length": "link length",
}
"""The student view's names of the fields (plain words; the expert view shows
:data:`LABELS`, with the paper's symbols)."""

STUDENT_DEFAULTS: dict[str, tuple[str, ...]] = {
    "beaker": ("beaker.drop", "beaker.pile_depth", "chain.friction"),
    "motor": ("feed.speed", "feed.launch_angle", "feed.drop"),
    "ideal_fold": ("feed.cart_force", "feed.lower_cart_force", "feed.xi2", "feed.xi3"),
    "ideal_floor": ("feed.cart_force", "feed.xi2"),
    "ideal_open": ("feed.cart_force", "feed.xi2", "feed.turn_drop"),
    "fold": ("carts[0].mass", "carts[1].mass"),
    "floor": ("carts[0].mass", "apparatus.xi2"),
    "open": ("carts[0].mass", "apparatus.xi2"),
}
"""The student view's sliders of a level that names none (``meta.controls``), by its
kind, feed drive or apparatus variant."""


def student_paths(level: Any) -> list[str]:
    """The field paths the student view shows for ``level`` (a
    :class:`~chainfountain.level.model.Level`): its ``meta.controls``, else
    :data:`STUDENT_DEFAULTS` for its kind, in that order, each only where the expert view
    has a slider for it."""
    sim = level.sim
    named = level.meta.control_paths()
    if not named:
        from chainfountain.sim.kinds import kind_of

        named = list(STUDENT_DEFAULTS.get(kind_of(sim).style(sim), ()))
    offered = {spec.path for spec in control_fields(sim)}
    return [p for p in named if p in offered]


LINEAR: frozenset[str] = frozenset({"apparatus.fold_clearance"})
"""Fields whose slider stays linear although their range starts at zero (a gap of a few
millimetres: a logarithmic slider would spend most of its travel below a micrometre)."""


@dataclass(frozen=True)
class FieldSpec:
    """One schema field as the panel shows it (display units: degrees for radians)."""

    path: str
    label: str
    unit: str
    """Display unit."""
    doc: str
    lo: float | None
    hi: float | None
    lo_incl: bool
    hi_incl: bool
    live: bool
    integer: bool
    scale: float
    """display value = schema value * scale."""
    slider_lo: float
    slider_hi: float
    log: bool
    """Logarithmic slider (position 0 is ``slider_lo``, then log-spaced up to ``slider_hi``)."""
    log_floor: float = 0.0
    """Smallest positive value on a log slider."""
    narrowed: bool = False
    """The slider spans only where the machine keeps running
    (:func:`chainfountain.app.spans.narrowed`), inside what the schema allows."""
    refused_beyond: bool = False
    """A narrowed slider's span is what the level check accepts: a value typed beyond it is
    refused (a machine's start region, the joints' step limits), not run."""
    file_unit: str = ""
    """The unit in the level file when the panel shows another (``rad`` for ``deg``,
    ``kg`` for ``g``); empty when they are the same."""

    # ---------------------------------------------------------------- range
    def allowed(self) -> str:
        """What the schema allows, in the units the panel shows (an angle in degrees, with
        the level file's radians beside it)."""
        def text(lo: float | None, hi: float | None, unit: str) -> str:
            return allowed_text({"min": lo, "max": hi, "min_inclusive": self.lo_incl,
                                 "max_inclusive": self.hi_incl, "unit": unit})

        if self.scale == 1.0:
            return text(self.lo, self.hi, self.unit)
        shown = [None if v is None else float(self.fmt(v * self.scale))
                 for v in (self.lo, self.hi)]
        return (f"{text(*shown, self.unit)}; in the level file "
                f"{text(self.lo, self.hi, self.schema_unit)}")

    @property
    def shown_unit(self) -> str:
        """The unit as text after a value, with its leading space; empty for a pure number
        (unit ``1``), so that ``xi3 = 0.4`` does not read ``xi3 = 0.4 1``."""
        return "" if self.unit in ("", "1") else f" {self.unit}"

    @property
    def schema_unit(self) -> str:
        return self.file_unit or self.unit

    def clamp(self, value: Any) -> tuple[float, str | None]:
        """Nearest allowed value (schema units) and a message when it differs from ``value``."""
        try:
            v = float(value)
        except (TypeError, ValueError):
            return self.default_like(), f"{self.label}: {value!r} is not a number"
        if math.isnan(v):
            return self.default_like(), f"{self.label}: not a number"
        orig = v
        if self.lo is not None and (v < self.lo or (v == self.lo and not self.lo_incl)):
            v = self.lo if self.lo_incl else _above(self.lo)
        if self.hi is not None and (v > self.hi or (v == self.hi and not self.hi_incl)):
            v = self.hi if self.hi_incl else _below(self.hi)
        if not math.isfinite(v):
            v = self.default_like()
        if self.integer:
            v = float(round(v))
            if self.lo is not None and v < self.lo:
                v = float(math.ceil(self.lo))
            if self.hi is not None and v > self.hi:
                v = float(math.floor(self.hi))
        if v != orig:
            return v, (f"{self.label}: {self.fmt(orig * self.scale)} is outside the allowed "
                       f"range, set to {self.fmt(v * self.scale)}{self.shown_unit} "
                       f"(allowed: {self.allowed()})")
        return v, None

    def default_like(self) -> float:
        lo = self.lo if self.lo is not None else 0.0
        return lo if self.lo_incl or self.lo is None else _above(lo)

    # ---------------------------------------------------------------- display
    def fmt(self, display_value: float) -> str:
        """Compact text of a display value."""
        if self.integer:
            return str(int(round(display_value)))
        if display_value == 0:
            return "0"
        return f"{display_value:.4g}"

    def to_display(self, value: float) -> float:
        return float(value) * self.scale

    def from_display(self, display_value: float) -> float:
        return float(display_value) / self.scale

    def ladder(self) -> list[float]:
        """The slider's positions as display values: the span's ends and the round
        values between them, a round step apart (:func:`slider_step`; a logarithmic
        slider: 1, 2, 5 in each decade after its lower end). The arrows move one rung."""
        key = (self.slider_lo, self.slider_hi, self.log, self.log_floor, self.integer)
        rungs = _LADDERS.get(key)
        if rungs is None:
            rungs = _ladder(*key)
            if len(_LADDERS) > 512:
                _LADDERS.clear()
            _LADDERS[key] = rungs
        return rungs

    @property
    def positions(self) -> int:
        """The slider's highest position (its lowest is 0)."""
        return len(self.ladder()) - 1

    def to_slider(self, value: float) -> int:
        """Slider position of a schema value (the nearest rung)."""
        d = self.to_display(value)
        rungs = self.ladder()
        if not math.isfinite(d):
            return 0
        i = bisect.bisect_left(rungs, d)
        if i <= 0:
            return 0
        if i >= len(rungs):
            return len(rungs) - 1
        return i if rungs[i] - d < d - rungs[i - 1] else i - 1

    def from_slider(self, pos: float) -> float:
        """Schema value at a slider position (its rung)."""
        rungs = self.ladder()
        p = float(pos)
        i = 0 if not math.isfinite(p) else int(round(min(max(p, 0.0), len(rungs) - 1)))
        v, _ = self.clamp(self.from_display(rungs[i]))
        return v


_LADDERS: dict[tuple, list[float]] = {}

SLIDER_RUNGS = 40
"""About how many round steps a linear slider's span is cut into."""


def slider_step(span: float, integer: bool = False) -> float:
    """A round step (1, 2 or 5 times a power of ten) cutting ``span`` into about
    :data:`SLIDER_RUNGS` parts; at least 1 for a whole-number field."""
    if not (math.isfinite(span) and span > 1e-300):
        return 1.0
    raw = span / SLIDER_RUNGS
    mag = 10.0 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 5, 10) if m * mag >= raw * 0.999)
    return max(step, 1.0) if integer else step


def _ladder(lo: float, hi: float, log: bool, floor: float, integer: bool) -> list[float]:
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo:
        return [lo]
    if hi - lo <= 1e-12 * max(abs(lo), abs(hi)) or hi - lo < 1e-300:  # a span of one value
        return [lo, hi]
    if log and floor > 0:
        out = [lo]
        e = math.floor(math.log10(floor))
        while 10.0 ** e <= hi * 1.0001:
            for m in (1, 2, 5):
                v = float(f"{m * 10.0 ** e:.12g}")
                if floor * 0.9999 <= v < hi * 0.9999 and v > out[-1]:
                    out.append(v)
            e += 1
        return out + [hi]
    step = slider_step(hi - lo, integer)
    k0, k1 = math.floor(lo / step) + 1, math.ceil(hi / step) - 1
    inner = [float(f"{k * step:.12g}") for k in range(k0, k1 + 1)]
    tol = 1e-9 * (hi - lo)
    return [lo] + [v for v in inner if lo + tol < v < hi - tol] + [hi]


def _above(x: float) -> float:
    return math.nextafter(x, math.inf) if x == 0 else x + 1e-9 * abs(x)


def _below(x: float) -> float:
    return math.nextafter(x, -math.inf) if x == 0 else x - 1e-9 * abs(x)


SPAN_AROUND = 4.0
"""A schema range wider than this many times a field's value gets a slider up to three
times the value (the text field takes the rest)."""


def _round_up(x: float) -> float:
    """``x`` rounded up to 1, 1.5, 2, 3 or 5 times a power of ten."""
    mag = 10.0 ** math.floor(math.log10(x))
    up = next(m * mag for m in (1, 1.5, 2, 3, 5, 10) if m * mag >= x * 0.999)
    return float(f"{up:.12g}")


def make_spec(path: str, tp: Any, meta: dict, current: float) -> FieldSpec:
    """A :class:`FieldSpec` from a field's schema metadata and its current value."""
    unit = meta.get("unit") or ""
    scale = 1.0
    file_unit = ""
    if unit == "rad":
        scale, unit, file_unit = 180.0 / math.pi, "deg", "rad"
    elif unit == "kg" and path.startswith("carts["):  # a cart's mass: grams read better
        scale, unit, file_unit = 1000.0, "g", "kg"
    lo, hi = meta.get("min"), meta.get("max")
    cur = abs(float(current))
    if lo is not None and hi is not None:
        s_lo, s_hi = lo * scale, hi * scale
        if cur > 0 and lo >= 0 and s_hi - s_lo > SPAN_AROUND * cur * scale and unit != "deg":
            # a schema range of many times the value (a drop of 1 m in 0.05-20 m): the
            # slider spans up to three times it, in round steps; typing goes further
            s_hi = min(s_hi, _round_up(3.0 * cur * scale))
    elif lo is not None:
        s_lo = lo * scale
        s_hi = max(10.0 * cur, 1.0) * scale + s_lo
    elif hi is not None:
        s_hi = hi * scale
        s_lo = s_hi - max(10.0 * cur, 1.0) * scale
    else:
        span = max(10.0 * cur, 50.0 if unit == "rad/s" else 1.0) * scale
        s_lo, s_hi = -span, span
    log = False
    floor = 0.0
    if tp is float and s_lo >= 0 and s_hi > 0 and path not in LINEAR:
        # many decades from (about) zero, and the current value sits near the bottom:
        # a logarithmic slider, position 0 being the lower limit itself
        if s_lo == 0:
            log = cur * scale < 0.01 * s_hi
            floor = s_hi * 1e-5
        else:
            log = s_hi / s_lo >= 1e3
            floor = s_lo
    label = LABELS.get(path)
    if label is None:
        label = path.replace(".", " ").replace("_", " ")
    return FieldSpec(
        path=path, label=label, unit=unit, doc=meta.get("doc") or "",
        lo=lo, hi=hi, lo_incl=bool(meta.get("min_inclusive", True)),
        hi_incl=bool(meta.get("max_inclusive", True)), live=bool(meta.get("live")),
        integer=tp is int, scale=scale, slider_lo=float(s_lo), slider_hi=float(s_hi),
        log=log, log_floor=float(floor), file_unit=file_unit,
    )


ONLY_FOR_VARIANT: dict[str, tuple[str, ...]] = {
    "apparatus.xi3": ("fold",),
    "apparatus.floor_depth": ("floor",),
    "apparatus.fold_clearance": ("fold",),
    "apparatus.swing_damper": ("fold",),
    "apparatus.fold_brake": ("fold",),
}
"""Apparatus fields that only the named ``apparatus.variant`` values use: for any other
variant a slider would change nothing (xi3 is the lower table's height, and only
'fold' has a lower table; only 'floor' has a floor; only 'fold' has a folding roller)."""


def _fed_unused(config: Any) -> set[str]:
    """A fed level's machine fields its ``feed.drive`` does not use (and an ideal
    machine's end tension: the machine, or the real floor, sets the pull)."""
    from chainfountain.sim.kinds.fed import DRIVE_FIELDS

    drive = config.feed.drive
    unused = {f"feed.{name}" for name, drives in DRIVE_FIELDS.items() if drive not in drives}
    if drive != "motor":
        unused.add("feed.end_tension")
    return unused


def _apparatus_unused(config: Any) -> set[str]:
    """Another variant's fields (:data:`ONLY_FOR_VARIANT`); the gripped folding roller has
    no clearance, and the brake is built for it."""
    variant = config.apparatus.variant
    roller = {"apparatus.fold_clearance"} if config.apparatus.fold_roller == "gripped" \
        else {"apparatus.fold_brake"}
    return {p for p, variants in ONLY_FOR_VARIANT.items() if variant not in variants} | roller


UNUSED_BY_KIND = {"feed": _fed_unused, "ideal": _fed_unused, "apparatus": _apparatus_unused}
"""The fields a level of each kind has but does not use, besides the bend limit."""

PILING_KINDS = frozenset({"beaker"})
"""Kinds whose links pile, so that their bend limit matters."""


def unused_fields(config: Any) -> set[str]:
    """Field paths that ``config`` has but does not use (:data:`UNUSED_BY_KIND`; the bend
    limit of a chain whose links do not pile, outside a beaker)."""
    from chainfountain.sim.kinds import kind_of

    name = kind_of(config).name
    bend = set() if name in PILING_KINDS else {"chain.bend_limit"}
    own = UNUSED_BY_KIND.get(name)
    return bend | (own(config) if own is not None else set())


def control_fields(config: Any, patterns: tuple[str, ...] = CONTROL_PATTERNS) -> list[FieldSpec]:
    """Specs for every field of ``config`` matching ``patterns``, in pattern order.

    Sections that belong to another level kind (``apparatus.*`` in a feed
    level, ``feed.*`` in an apparatus level) get no controls, nor do fields the
    level's apparatus variant ignores (:func:`unused_fields`).
    """
    from chainfountain.sim.config import KINDS

    kind = getattr(config, "kind", None)
    other = tuple(f"{k}." for k in KINDS if k != kind)
    unused = unused_fields(config)
    fields = [f for f in iter_numeric_fields(config)
              if not f[0].startswith(other) and f[0] not in unused]
    out: list[FieldSpec] = []
    seen: set[str] = set()
    for pat in patterns:
        rx = re.compile(pat)
        for path, tp, meta in fields:
            if path in seen or not rx.fullmatch(path):
                continue
            seen.add(path)
            out.append(make_spec(path, tp, meta, get_value(config, path)))
    return out


def spec_for(config: Any, path: str) -> FieldSpec:
    """The spec of any numeric field path (even one not in :data:`CONTROL_PATTERNS`)."""
    for p, tp, meta in iter_numeric_fields(config):
        if p == path:
            return make_spec(p, tp, meta, get_value(config, p))
    raise KeyError(path)
