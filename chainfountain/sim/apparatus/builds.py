"""The builds the contact machines from rest were measured at: every field their start
regions (:mod:`.region`) do not range over, held at the shipped preset's value.

A start from rest was measured field by field around the shipped presets
(``research/contact_region/*.toml``, docs/apparatus.md, "Where the machines start from
rest"). A field swept there has its measured band in :mod:`.region`; every other field a
level can set (the chain's density and capsule radius, the rollers' and carriages'
masses, the tables' friction, the channels' bend, the resting-link counts, the starter's
time, the end guide's follow rate, the carts' tracks, gravity, ...) was run only at its
preset's value, and a start from rest is admitted only there. :func:`off_build` names the
first field that differs.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from chainfountain.fields import get_value

if TYPE_CHECKING:
    from chainfountain.sim.config import SimConfig

Value = float | int | str | bool

_CART = {"x": 0.0, "y": 0.0, "track_length": 2.0, "width": 0.05, "height": 0.02}

GRIPPED_FOLD: dict[str, Value] = {
    "gravity": 9.81, "chain.linear_density": 0.05, "chain.link_radius": 0.002,
    "chain.self_collision": False, "chain.bend_limit": 0.0, "apparatus.end_tension": 0.17,
    "apparatus.duration": 3.0, "apparatus.roller_mass": 0.02,
    "apparatus.carriage_mass": 0.02, "apparatus.table_friction": 5.0,
    "apparatus.channel_radius": 0.15, "apparatus.floor_width": 4.0,
    "apparatus.end": "absorbing", "apparatus.floor_depth": 0.0, "apparatus.plate": "groove",
    "apparatus.end_pull": 0.0, "apparatus.rest_links": 20, "apparatus.pickup_rest_links": 8,
    "apparatus.fold_clearance": 0.0, "apparatus.end_follow": 2.0, "apparatus.starter": 3.0,
    "apparatus.upper_guide": "joints", "initial.stub_length": 0.1, "initial.jitter": 0.001,
    **{f"carts[{i}].{k}": v for i in (0, 1) for k, v in _CART.items()},
}
"""``apparatus_fold_gripped``'s (and ``apparatus_special_gripped``'s) build: the fields a
gripped fold from rest is admitted only at."""

FLOOR: dict[str, Value] = {
    "gravity": 9.81, "chain.linear_density": 0.05, "chain.link_radius": 0.002,
    "chain.self_collision": False, "chain.bend_limit": 0.0, "apparatus.end_tension": 0.0,
    "apparatus.xi3": 0.5, "apparatus.duration": 6.5, "apparatus.roller_mass": 0.02,
    "apparatus.carriage_mass": 0.02, "apparatus.table_friction": 5.0,
    "apparatus.channel_radius": 0.15, "apparatus.floor_width": 4.0,
    "apparatus.end": "absorbing", "apparatus.plate": "groove", "apparatus.end_pull": 0.0,
    "apparatus.rest_links": 20, "apparatus.pickup_rest_links": 0,
    "apparatus.fold_clearance": 0.0, "apparatus.fold_roller_radius": 0.0,
    "apparatus.fold_brake": 0.0, "apparatus.end_follow": 0.0, "apparatus.swing_damper": 0.0,
    "apparatus.starter": 3.0, "apparatus.upper_guide": "joints",
    "initial.stub_length": 0.1, "initial.jitter": 0.001,
    **{f"carts[0].{k}": v for k, v in _CART.items()},
}
"""``apparatus_floor``'s (and ``apparatus_floor_heavy``'s) build: the fields a floor
machine from rest is admitted only at."""

CARTS = {"fold": 2, "floor": 1}
"""How many carts each machine was built and measured with."""


def build_of(cfg: SimConfig) -> tuple[str, dict[str, Value]] | None:
    """``(preset, build)`` of a contact machine from rest (``None`` for other machines)."""
    variant = cfg.apparatus.variant
    if variant == "fold" and cfg.apparatus.fold_roller == "gripped":
        return "apparatus_fold_gripped", GRIPPED_FOLD
    if variant == "floor":
        return "apparatus_floor", FLOOR
    return None


def _same(value: Value, want: Value) -> bool:
    if isinstance(want, bool) or isinstance(want, str):
        return value == want
    return abs(float(value) - float(want)) <= 1e-9 * max(1.0, abs(float(want)))


def off_build(cfg: SimConfig) -> tuple[str, str] | None:
    """``(field, message)`` for the first field of ``cfg`` off its machine's build
    (:func:`build_of`), or ``None`` when every one is on it (or no build applies)."""
    found = build_of(cfg)
    if found is None:
        return None
    preset, build = found
    machine = ("a gripped fold" if cfg.apparatus.variant == "fold"
               else "the floor machine")
    count = CARTS[cfg.apparatus.variant]
    if len(cfg.carts) != count:
        return ("carts", f"{len(cfg.carts)} carts: {machine} was measured to form from rest "
                f"and hold with {count} ({preset}); allowed: {count}, or initial.mode = "
                "'catenary' (laid on its path)")
    for path, want in build.items():
        value = get_value(cfg, path)
        if not _same(value, want):
            return (path, f"{value!r}: {machine} from rest was measured to form and hold "
                    f"only with this field as built ({preset}); allowed: {want!r}, or "
                    "initial.mode = 'catenary' (laid on its path)")
    return None


def pinned(cfg: SimConfig) -> dict[str, Value]:
    """The fields ``cfg``'s machine from rest is admitted only at, with their values."""
    found = build_of(cfg)
    return dict(found[1]) if found is not None else {}
