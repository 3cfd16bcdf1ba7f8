"""Slider spans of a machine: where its carts and offsets still run a fountain.

A machine field's slider (``feed.xi2``, ``feed.cart_force``, ``feed.xi3``,
``feed.lower_cart_force``, ``feed.bearing_drag``, ``feed.turn_drop`` of a level with
``feed.drive`` an ideal machine) spans only the values the level's own checks accept with
every other field as it is: the range in which the machine selects (or keeps) a
fountain the window can run (its budget, :mod:`chainfountain.app.cost`), found by
bisection from the present value towards each end of the schema's range. Out there the
machine would stop, run away or lose its fountain; a value typed beyond the span is
refused with the check's reason. A loss-free full machine's upper cart has a single
admissible value (the balance): its slider does not move.

The contact floor machine's upper cart, bearing drag and offset span where this model's
pick-up law leaves the chain running (:data:`FLOOR_FIELDS`; the limit is measured:
:data:`~chainfountain.sim.apparatus.laws.FLOOR_KH_MAX`). A contact 'fold' machine's carts
span the measured band around the balance the level was built with
(:data:`FOLD_FIELDS`, :data:`~chainfountain.sim.apparatus.laws.FOLD_CART_BAND`), and so
do a gripped fold's with a brake
(:data:`~chainfountain.sim.apparatus.laws.BRAKED_CART_BAND`). A gripped fold from rest's
drop, start speed and launch angle span its measured start region (:data:`START_FIELDS`,
:mod:`chainfountain.sim.apparatus.region`), and so do a contact machine from rest's link
length and joints; a field it was measured only as built at (``region.pinned``) has a
one-value span, its slider greyed out.
"""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Callable

from chainfountain.app import interactive
from chainfountain.app.controls import FieldSpec
from chainfountain.fields import get_value, set_value
from chainfountain.level import io
from chainfountain.level.io import Level, LevelError
from chainfountain.sim import joints
from chainfountain.sim.apparatus import region as start_region
from chainfountain.sim.apparatus.laws import floor_runs_on, fold_cart_span, fold_runs_on
from chainfountain.sim.config import SimConfig
from chainfountain.sim.kinds import kind_of
from chainfountain.sim.live import plan
from chainfountain.sim.machine_rules import MACHINE_FIELDS

FLOOR_FIELDS = ("carts[0].mass", "carts[0].incline", "apparatus.bearing_drag", "apparatus.xi2")
"""A contact 'floor' machine's fields whose sliders span where the chain runs on
(:func:`~chainfountain.sim.apparatus.laws.floor_runs_on`, measured limits)."""

FOLD_FIELDS = ("carts[0].mass", "carts[1].mass")
"""A contact 'fold' machine's fields whose sliders span the measured band around the
level's own balance (:func:`~chainfountain.sim.apparatus.laws.fold_cart_span`; when the
other cart is so far off that no value runs, the span of the level as built)."""

FOLD_OTHER_FIELDS = ("apparatus.bearing_drag", "apparatus.fold_brake", "carts[0].incline",
                     "carts[1].incline")
"""A contact 'fold' machine's other fields that move its carts' push: their sliders span
where :func:`~chainfountain.sim.apparatus.laws.fold_runs_on` holds (by bisection)."""

FOLD_OFFSETS = ("apparatus.xi2", "apparatus.xi3")
"""A contact 'fold' machine's offsets: its carts are balanced for the offsets it was built
with, and the slider keeps to them. Measured on ``apparatus_special`` (``xi3 = 0.5``),
rebuilt with ``xi3`` 0.48: stopped at 5.6 s; 0.52: held 40 s; 0.4 and 0.6 with the lower
cart moved by the paper's law (63 g and 53 g): stopped at 3.7 and 2.6 s
(``docs/apparatus.md``, "Tuning the damped folds live")."""

START_FIELDS = ("apparatus.drop", "apparatus.speed", "apparatus.launch_angle",
                "apparatus.floor_depth", "apparatus.swing_damper", "chain.friction",
                "chain.link_length")
"""A contact machine from rest's geometry (a gripped fold's, the floor machine's): their
sliders span its measured start region at the other fields' values
(:mod:`chainfountain.sim.apparatus.region`, which the level check reads), found by
bisection."""

JOINT_FIELDS = ("chain.bending_stiffness", "chain.bending_damping")
"""The joints' spring and damper: their sliders stop short of the step limits the level
check refuses (:mod:`chainfountain.sim.joints`: the spring's ``omega h < 2``, the damper's
``2 d h/I <= 0.3``)."""

NARROWED_FIELDS = frozenset(MACHINE_FIELDS) | frozenset(FLOOR_FIELDS) | \
    frozenset(FOLD_FIELDS) | frozenset(FOLD_OTHER_FIELDS) | frozenset(FOLD_OFFSETS) | \
    frozenset(JOINT_FIELDS) | frozenset(START_FIELDS)
"""Every field whose slider may span less than the schema's range (the window recomputes
their spans after any change)."""

BISECTIONS = 30
"""Bisection steps towards each end (the span's ends to about 1e-9 of the schema range)."""


def _accepts(level: Level, path: str, origin: SimConfig | None,
             runs: Callable[[SimConfig], bool] | None = None) -> Callable[[float], bool]:
    def ok(value: float) -> bool:
        cand: SimConfig = copy.deepcopy(level.sim)
        for p, v in plan(level.sim, path, value).items():  # and what follows it
            set_value(cand, p, v)
        if runs is not None and not runs(cand):
            return False
        try:
            io.check_consistency(Level(meta=level.meta, sim=cand), "span")
        except LevelError:
            return False
        return origin is None or interactive.over_budget(cand, origin) is None
    return ok


def _edge(ok: Callable[[float], bool], inside: float, outside: float) -> float:
    """The last accepted value between ``inside`` (accepted) and ``outside``."""
    if ok(outside):
        return outside
    for _ in range(BISECTIONS):
        mid = 0.5 * (inside + outside)
        if ok(mid):
            inside = mid
        else:
            outside = mid
    return inside


def admissible(level: Level, spec: FieldSpec,
               origin: SimConfig | None = None) -> tuple[float, float] | None:
    """The span (schema units) of values around the present one that ``level``'s checks
    accept for ``spec``'s field (and, given the level as loaded, ``origin``, that the
    window's budget runs: :mod:`chainfountain.app.cost`; a contact floor machine's, that
    its chain runs on; a contact fold machine's, that its carts stay within their measured
    band of ``origin``'s), or ``None`` when the field is none of an ideal machine's,
    :data:`FLOOR_FIELDS` of a contact floor machine or the ``FOLD_*`` fields of a contact
    fold machine, or the present value is outside already (the schema's range then). The
    joints' spring and damper (:data:`JOINT_FIELDS`) span the slider's own range cut at
    their step limits."""
    sim = level.sim
    from_rest = kind_of(sim).start_region(sim) and sim.apparatus.start_region != "unchecked"
    if from_rest:
        pinned = start_region.pinned(sim)
        if spec.path in pinned:  # measured only as built (region.pinned)
            return pinned[spec.path], pinned[spec.path]
    if spec.path in JOINT_FIELDS and not from_rest:
        return _joint_span(sim, spec)
    variant = kind_of(sim).style(sim)  # an apparatus's variant ("fold", "floor", ...)
    fold = (variant == "fold" and origin is not None and len(sim.carts) >= 2
            and len(origin.carts) >= 2 and (origin.apparatus.fold_roller == "contact"
                                             or origin.apparatus.fold_brake > 0.0))
    if fold and spec.path in FOLD_FIELDS:  # linear in the carts' forces: exact
        i = FOLD_FIELDS.index(spec.path)
        scale = start_region.cart_scale(sim)  # a gripped fold from rest: its margin
        return (fold_cart_span(sim, origin, i, scale)
                or fold_cart_span(origin, origin, i, scale))
    if fold and spec.path in FOLD_OFFSETS:  # the carts are balanced for these only
        built = float(get_value(origin, spec.path))
        return built, built
    if fold and spec.path in FOLD_OTHER_FIELDS:
        ok = _accepts(level, spec.path, origin, lambda c: fold_runs_on(c, origin))
    elif from_rest and (spec.path in START_FIELDS or spec.path in JOINT_FIELDS):
        ok = _accepts(level, spec.path, origin)
    elif variant == "floor" and spec.path in FLOOR_FIELDS:
        ok = _accepts(level, spec.path, origin, floor_runs_on)
    elif spec.path in MACHINE_FIELDS and spec.path in kind_of(sim).live:
        ok = _accepts(level, spec.path, origin)
    else:
        return None
    now = float(get_value(sim, spec.path))
    if not ok(now) and origin is not None:  # typed beyond the span: it stays, from the
        now = float(get_value(origin, spec.path))  # value the level was loaded with
    if not ok(now):  # set outside on purpose (the fountain-D presets, near-critical)
        return None
    lo = spec.lo if spec.lo is not None else spec.slider_lo
    hi = spec.hi if spec.hi is not None else spec.slider_hi
    if not spec.hi_incl:
        hi = hi - 1e-9 * (hi - lo)
    return _edge(ok, now, lo), _edge(ok, now, hi)


def _joint_span(sim: SimConfig, spec: FieldSpec) -> tuple[float, float] | None:
    """The joint field's slider span cut at its step limit (``None``: the present value
    is beyond it already, set on purpose)."""
    h = sim.solver.dt / sim.solver.substeps
    if spec.path == "chain.bending_stiffness":
        limit = joints.stiffness_limit(sim.chain, h) * (1.0 - 1e-6)  # strictly below
    else:
        limit = joints.damping_limit(sim.chain, h)
    lo, hi = spec.slider_lo / spec.scale, spec.slider_hi / spec.scale
    if float(get_value(sim, spec.path)) > limit:
        return None
    return lo, min(hi, limit)


def narrowed(level: Level, spec: FieldSpec, origin: SimConfig | None = None) -> FieldSpec:
    """``spec`` with its slider spanning :func:`admissible` (linear), when that applies."""
    span = admissible(level, spec, origin)
    if span is None:
        return spec
    lo, hi = span
    refused = spec.path in JOINT_FIELDS or spec.path in START_FIELDS
    return dataclasses.replace(spec, slider_lo=lo * spec.scale, slider_hi=hi * spec.scale,
                               log=False, log_floor=0.0, narrowed=True,
                               refused_beyond=refused)
