"""Live changes: one table from a level field to what changes it in a running simulation.

A field is live when :func:`setter_for` finds it: in :data:`COMMON` (every fountain) or
in its kind's ``live`` table (:class:`~chainfountain.sim.kinds.base.Kind`). A change is
first planned (:func:`plan`: the field and whatever follows it, such as the loss-free
full machine's upper cart, :func:`~chainfountain.sim.machine_rules.follow`), then the
planned values are written into the configuration and each field's setter runs once
(:meth:`~chainfountain.sim.world.Simulation.apply`). The window, the Python API and a
sweep's changes all go this way; the fields' ``live`` flags in
:mod:`chainfountain.sim.config` agree with the table (a test checks both).
"""

from __future__ import annotations

import copy
import re
from typing import Any

from chainfountain.sim.config import SimConfig
from chainfountain.sim.kinds import kind_of
from chainfountain.sim.kinds.base import Setter
from chainfountain.sim.machine_rules import follow

_ITEM = re.compile(r"^([a-z_]+)\[(\d+)\](\..+)$")


def _bending_stiffness(sim: Any, index: int | None, v: float) -> None:
    sim.chain.set_bending(stiffness=v)
    sim.joints_changed()  # a motor-fed chain's stiff theory follows


def _bending_damping(sim: Any, index: int | None, v: float) -> None:
    sim.chain.set_bending(damping=v)
    sim.joints_changed()


def _friction(sim: Any, index: int | None, v: float) -> None:
    sim.chain.set_friction(v)


def _iterations(sim: Any, index: int | None, v: float) -> None:
    sim.space.iterations = int(v)


def _error_bias(sim: Any, index: int | None, v: float) -> None:
    sim.chain.set_error_bias(v)


def _slop(sim: Any, index: int | None, v: float) -> None:
    sim.space.collision_slop = v


def _roller_speed(sim: Any, index: int | None, v: float) -> None:
    sim.rollers[int(index or 0)].set_angular_speed(v)


COMMON: dict[str, Setter] = {
    "chain.bending_stiffness": _bending_stiffness,
    "chain.bending_damping": _bending_damping,
    "chain.friction": _friction,
    "solver.iterations": _iterations,
    "solver.joint_error_bias": _error_bias,
    "solver.collision_slop": _slop,
    "rollers[].angular_speed": _roller_speed,
}
"""Live fields of every fountain kind, and their setters."""

INTEGER = frozenset({"solver.iterations"})
"""Live fields that hold whole numbers."""


def split(path: str) -> tuple[str, int | None]:
    """``"carts[1].mass"`` -> ``("carts[].mass", 1)``; ``"feed.speed"`` -> ``(path, None)``."""
    m = _ITEM.match(path)
    if m is None:
        return path, None
    return f"{m.group(1)}[]{m.group(3)}", int(m.group(2))


def setter_for(config: SimConfig, path: str) -> Setter | None:
    """The setter of ``path`` in a running level of ``config``'s kind; ``None``: the field
    needs a rebuild."""
    key, _ = split(path)
    kind = kind_of(config)
    return kind.live.get(key) or COMMON.get(key)


def is_live(config: SimConfig, path: str) -> bool:
    """Whether ``path`` can change while a level of ``config``'s kind runs."""
    return setter_for(config, path) is not None


def number(path: str, value: Any) -> float:
    """``value`` as the live field ``path`` holds it (a whole number for :data:`INTEGER`)."""
    return int(value) if path in INTEGER else float(value)


def plan(config: SimConfig, path: str, value: Any) -> dict[str, Any]:
    """The field writes a change of ``path`` to ``value`` makes in ``config``: the field
    itself, and the loss-free full machine's upper cart where it follows the balance
    (``config`` is not changed)."""
    from chainfountain.fields import set_value

    changes: dict[str, Any] = {path: value}
    cand = copy.deepcopy(config)
    set_value(cand, path, value)
    followed = follow(cand, path)
    if followed is not None:
        changes["feed.cart_force"] = followed
    return changes
