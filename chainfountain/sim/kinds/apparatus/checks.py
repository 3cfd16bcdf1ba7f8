"""Cross-field checks of an apparatus level (``kind = "apparatus"``): the machine can be
built, its fountain exists and fits, it starts as it can, and nothing is set that it ignores."""

from __future__ import annotations

import dataclasses
import math

from chainfountain.errors import fail
from chainfountain.sim.apparatus import region as start_region
from chainfountain.sim.config import SimConfig
from chainfountain.sim.kinds.sizing import (
    MAX_LINKS,
    check_size,
    fastest_fitting,
    fountain_or_fail,
)


def _check_apparatus_start(sim: SimConfig, where: str) -> None:
    """How an apparatus starts: laid along its path, moving (``initial`` at its defaults,
    no starter), or from rest with a starter (``initial.mode = "stub"``, the 'floor'
    variant or the gripped 'fold', with the upper joint guide)."""
    a = sim.apparatus
    default_initial = type(sim.initial)()
    from_rest = sim.initial.mode == "stub"
    for f in dataclasses.fields(sim.initial):
        value, default = getattr(sim.initial, f.name), getattr(default_initial, f.name)
        if value == default or f.name == "seed" or (
                from_rest and f.name in ("mode", "stub_length")):
            continue
        fail(where, f"initial.{f.name}",
              f"{value!r} has no effect in an 'apparatus' level: the apparatus lays its "
              "chain along its own path, moving at apparatus.speed, or from rest with "
              "initial.mode = 'stub' (to start a perturbed run, set initial.seed above 0: "
              f"a 1e-12 nudge); allowed: {default!r}" + (", or 'stub'" if f.name == "mode" else ""))
    if not from_rest:
        if a.start_region != "checked":
            fail(where, "apparatus.start_region",
                  f"{a.start_region!r} has no effect with initial.mode = 'catenary' (the "
                  "region is where a machine forms from rest); allowed: 'checked'")
        if a.starter:
            fail(where, "apparatus.starter",
                  f"{a.starter!r} s has no effect with initial.mode = 'catenary' (the chain "
                  "starts laid along its path at apparatus.speed); allowed: 0, or "
                  "initial.mode = 'stub'")
        return
    threads = a.variant == "fold" and a.plate == "groove" and a.fold_roller == "gripped"
    if a.variant not in ("floor", "fold") or a.upper_guide != "joints":
        field, value = (("apparatus.variant", a.variant) if a.variant not in ("floor", "fold")
                        else ("apparatus.upper_guide", a.upper_guide))
        fail(where, field,
              f"{value!r} cannot start from rest (initial.mode = 'stub'): the starter runs the "
              "chain in the upper joint guide, and only the floor or the gripped fold takes "
              "in a forming fountain; allowed: variant = 'floor' or 'fold' with upper_guide "
              "= 'joints', or initial.mode = 'catenary'")
    if a.variant == "fold" and not threads:
        field, value = (("apparatus.fold_roller", a.fold_roller) if a.plate == "groove"
                        else ("apparatus.plate", a.plate))
        fail(where, field,
              f"{value!r} cannot start from rest (initial.mode = 'stub'): the starter threads "
              "the chain's head through the end guide's joints and the gripped folding "
              "roller; allowed: fold_roller = 'gripped' with plate = 'groove', or "
              "initial.mode = 'catenary'")
    if a.variant == "fold" and sim.initial.stub_length != default_initial.stub_length:
        fail(where, "initial.stub_length",
              f"{sim.initial.stub_length!r} m has no effect in 'fold': its head waits inside "
              "the upper guide until the starter launches it; allowed: "
              f"{default_initial.stub_length!r}")
    if a.starter <= 0.0:
        fail(where, "apparatus.starter",
              f"{a.starter!r} s with initial.mode = 'stub': at rest the cart holds the chain "
              "and nothing falls, so the machine needs a starter; allowed: a time > 0 "
              "(seconds the starter runs on after the chain lands, e.g. 3)")


def check_apparatus(sim: SimConfig, where: str) -> None:
    """Apparatus cross-field checks (paper: ``Tbar_E + k*H < 1`` for the launch)."""
    a = sim.apparatus
    g = sim.gravity
    if a.floor_depth > 0:
        if a.variant != "floor" or a.end != "absorbing":
            fail(where, "apparatus.floor_depth",
                  f"{a.floor_depth!r} m needs apparatus.variant = 'floor' with end = "
                  f"'absorbing' (it is {a.variant!r} with end {a.end!r}); allowed: 0")
        if a.end_tension != 0:
            fail(where, "apparatus.end_tension",
                  f"{a.end_tension!r} conflicts with apparatus.floor_depth = {a.floor_depth:g} m, "
                  "which sets Tbar_E = g*floor_depth/speed**2; allowed: 0 with a floor_depth")
        v_need = math.sqrt(g * (a.drop + a.floor_depth))
        if a.speed <= v_need:
            fail(where, "apparatus.speed",
                  f"{a.speed!r} m/s cannot launch a fountain that reaches a free end "
                  f"{a.drop + a.floor_depth:g} m lower (drop + floor_depth); allowed: a speed > "
                  f"sqrt(g*(H + floor_depth)) = {v_need:.4g} m/s")
    v_need = math.sqrt(g * a.drop / (1.0 - a.end_tension))
    if a.speed <= v_need:
        kH = g * a.drop / a.speed**2
        if a.end_tension > 0 and kH < 1.0:
            fail(where, "apparatus.end_tension",
                  f"{a.end_tension!r} leaves no fountain at apparatus.speed = {a.speed:g} m/s "
                  f"and apparatus.drop = {a.drop:g} m (Tbar_E + k*H = {a.end_tension + kH:.4g}, "
                  f"k = g/v^2; the paper needs < 1); allowed: Tbar_E < 1 - k*H = {1.0 - kH:.4g} "
                  f"at this speed and drop (this end tension needs a speed > "
                  f"sqrt(g*H/(1 - Tbar_E)) = {v_need:.4g} m/s)")
        fail(where, "apparatus.speed",
              f"{a.speed!r} m/s cannot launch a fountain that ends {a.drop:g} m lower with "
              f"Tbar_E = {a.end_tension:g}; allowed: a speed > sqrt(g*H/(1 - Tbar_E)) = "
              f"{v_need:.4g} m/s")
    if sim.chain.link_length > 0.1 * a.drop:
        fail(where, "chain.link_length",
              f"{sim.chain.link_length!r} m is too coarse for a drop of {a.drop:g} m; "
              f"allowed: at most a tenth of apparatus.drop ({0.1 * a.drop:.4g} m)")
    if a.plate_links and a.plate != "groove":
        fail(where, "apparatus.plate_links",
              f"{a.plate_links!r} needs apparatus.plate = 'groove' (it is {a.plate!r}); "
              "allowed: 0 with a 'contact' plate")
    if a.end_follow and a.plate != "groove":
        fail(where, "apparatus.end_follow",
              f"{a.end_follow!r} needs the end guide of joints, apparatus.plate = 'groove' "
              f"(it is {a.plate!r}); allowed: 0 with a 'contact' plate")
    if a.plate_links and a.plate_links < 4:
        fail(where, "apparatus.plate_links",
              f"{a.plate_links!r} is too short a plate strand to cut or extend in the middle; "
              "allowed: 0 (off) or at least 4")
    if 0 < a.pickup_rest_links < 5:
        fail(where, "apparatus.pickup_rest_links",
              f"{a.pickup_rest_links!r} leaves the pick-up roller too little resting chain to "
              "roll on; allowed: 0 (as apparatus.rest_links) or at least 5")
    _check_apparatus_start(sim, where)
    if a.swing_damper and a.variant != "fold":
        fail(where, "apparatus.swing_damper",
              f"{a.swing_damper!r} N*s/m only applies to variant = 'fold' (it acts between the "
              f"pick-up and the folding roller; here variant {a.variant!r}); allowed: 0")
    if a.fold_clearance and (a.variant != "fold" or a.plate != "groove"):
        fail(where, "apparatus.fold_clearance",
              f"{a.fold_clearance!r} m only applies to variant = 'fold' with plate = 'groove' "
              f"(here variant {a.variant!r}, plate {a.plate!r}); allowed: 0")
    if 0.0 < a.fold_roller_radius < 0.005:
        fail(where, "apparatus.fold_roller_radius",
              f"{a.fold_roller_radius!r} m is too small a roller; allowed: 0 (as "
              "apparatus.roller_radius) or 0.005-0.5 m")
    if a.fold_roller == "gripped":
        _check_gripped_fold(sim, where)
    if a.upper_guide == "joints" and a.plate != "groove":
        fail(where, "apparatus.upper_guide",
              f"'joints' needs apparatus.plate = 'groove' (it is {a.plate!r}): the joint guide "
              "takes the links from the plate's grooves; allowed: 'walls' with a 'contact' plate")
    _check_apparatus_unused(sim, where)
    _check_apparatus_size(sim, where)
    _check_end_channel(sim, where)
    # last: a machine that can exist, started from rest where it was not measured to hold
    found = start_region.problem(sim) or start_region.floor_problem(sim)
    if found is not None:
        fail(where, *found)


def _check_gripped_fold(sim: SimConfig, where: str) -> None:
    """The gripped folding roller takes the chain from the lower plate's grooves, lays it
    where its circle meets the table (no clearance) and needs a circle of at least one
    link length round the chain's centre line (:mod:`chainfountain.sim.apparatus.grip`)."""
    a, L = sim.apparatus, sim.chain.link_length
    if a.plate != "groove":
        fail(where, "apparatus.fold_roller",
              f"'gripped' needs apparatus.plate = 'groove' (it is {a.plate!r}): the roller "
              "takes the chain from the lower plate's grooves; allowed: 'contact'")
    if a.fold_clearance:
        fail(where, "apparatus.fold_clearance",
              f"{a.fold_clearance!r} m has no effect with apparatus.fold_roller = 'gripped' "
              "(the gripped roller lays the chain where its circle meets the table); "
              "allowed: 0")
    r = a.fold_roller_radius or a.roller_radius
    if r + sim.chain.link_radius < L:
        fail(where, "apparatus.fold_roller_radius",
              f"{r!r} m is too small a gripped folding roller for {L!r}-m links (the chain's "
              f"centre line must run at least one link length from its axle); allowed: at "
              f"least {L - sim.chain.link_radius:.4g} m (converged in the step from about "
              f"{5 * L:.3g} m, five link lengths; docs/apparatus.md)")


ONLY_FOR_VARIANT: dict[str, tuple[str, ...]] = {
    "xi3": ("fold",),
    "fold_roller": ("fold",),
    "fold_roller_radius": ("fold",),
    "fold_brake": ("fold",),
    "end_follow": ("fold",),
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
            fail(where, f"apparatus.{name}",
                  f"{value!r} has no effect with apparatus.variant = {a.variant!r} (only "
                  f"{only} uses it); allowed: {getattr(default, name)!r}")
    if sim.rollers:
        fail(where, "rollers",
              f"{len(sim.rollers)} [[rollers]] have no effect in an 'apparatus' level (it "
              "builds its own rollers); allowed: none (rollers = [])")
    n_carts = 2 if a.variant == "fold" else 1
    if len(sim.carts) > n_carts:
        which = ("carts[0] pulls the pick-up roller, carts[1] pushes the folding roller"
                 if n_carts == 2 else "carts[0] pulls the pick-up roller")
        fail(where, f"carts[{n_carts}]",
              f"has no effect with apparatus.variant = {a.variant!r} ({which}); allowed: at "
              f"most {n_carts} [[carts]]")


def _check_end_channel(sim: SimConfig, where: str) -> None:
    """'fold': the end channel's two bends fit into the rise ``xi3*H`` (or it is zero)."""
    from chainfountain.sim.guide import end_channel_bends, end_channel_min_rise

    a = sim.apparatus
    rise = a.xi3 * a.drop
    if a.variant != "fold" or rise <= 1e-9:
        return
    f = fountain_or_fail(where, "apparatus.speed", a.speed, a.launch_angle, a.drop,
                          a.end_tension, sim.gravity)
    try:
        end_channel_bends(f.alphaE, rise, a.channel_radius)
    except ValueError:
        least = end_channel_min_rise(f.alphaE, a.channel_radius) / a.drop
        fail(where, "apparatus.xi3",
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
    f = fountain_or_fail(where, "apparatus.speed", a.speed, a.launch_angle, a.drop, te, g)
    v_min = math.sqrt(g * (a.drop + d) / (1.0 - a.end_tension))
    check_size(where, "apparatus.speed", f.length, 0.0, L, min(0.1 * a.drop, 0.2), a.speed,
                v_min, lambda length: fastest_fitting(v_min, a.speed, a.launch_angle, a.drop,
                                                       a.end_tension, g, length, d))
    if a.plate_links > 0 and a.plate == "groove":
        return
    n = (f.length + 0.5 * a.speed * a.duration + 0.15) / L
    if n > MAX_LINKS:
        room = (MAX_LINKS * L - f.length - 0.15) / (0.5 * a.speed)
        fail(where, "apparatus.duration",
              f"{a.duration!r} s sizes the upper plate for {0.5 * a.speed * a.duration:.4g} m of "
              f"roller travel (v/2 for the duration): {n:.0f} links at the start; allowed: at "
              f"most {MAX_LINKS} links, here a duration <= {max(room, 0.0):.4g} s (or "
              "apparatus.plate_links > 0, a treadmill, for runs of any length)")
