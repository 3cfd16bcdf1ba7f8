"""Cross-field checks of a level: it must describe a fountain that can exist, in a scene
the simulation can hold, and every setting must have an effect (:func:`check_consistency`).

The checks of each kind are its own (:attr:`chainfountain.sim.kinds.base.Kind.check`);
here are those of every level. No check changes the level: the settings
``solver.accuracy`` chooses are :mod:`chainfountain.level.resolve`'s."""

from __future__ import annotations

import dataclasses
import math

from chainfountain.fields import iter_numeric_fields
from chainfountain.level.model import Level, _fail
from chainfountain.sim import joints
from chainfountain.sim.config import KINDS, SimConfig
from chainfountain.sim.kinds import kind_of
from chainfountain.sim.kinds.fed import DRIVE_FIELDS, IDEAL_DRIVES
from chainfountain.sim.kinds.sizing import MAX_LINKS

__all__ = ["DRIVE_FIELDS", "IDEAL_DRIVES", "MAX_LINKS", "check_consistency"]



def check_consistency(level: Level, where: str) -> None:
    """Cross-field checks: the configured fountain must exist, fit the simulator, and
    every setting given must have an effect in this kind of level."""
    sim = level.sim
    g = sim.gravity
    if not g > 0:
        _fail(where, "gravity", f"{g!r} is out of range; allowed: a number > 0 (m/s^2)")
    _check_other_kind(sim, where)
    _check_joint_spring(sim, where)
    kind_of(sim).check(sim, where)
    _check_accuracy_scope(sim, where)
    _check_controls(level, where)


def _check_joint_spring(sim: SimConfig, where: str) -> None:
    """``chain.bending_stiffness`` below the explicit spring's stability limit
    (:data:`chainfountain.sim.joints.SPRING_STABILITY`) at the level's link and step, and
    ``chain.bending_damping`` within the damper's (:func:`_check_joint_damper`)."""
    h = sim.solver.dt / sim.solver.substeps
    _check_joint_damper(sim, where, h)
    c = sim.chain.bending_stiffness
    if c <= 0.0:
        return
    c_max = joints.stiffness_limit(sim.chain, h)
    if c < c_max:
        return
    L = sim.chain.link_length
    _fail(where, "chain.bending_stiffness",
          f"{c!r} N*m/rad makes linked links ring at omega*h = "
          f"{joints.omega_h(sim.chain, h):.3g} with {L:g} m links and a {h:g} s pymunk step, "
          f"and the spring diverges beyond {joints.SPRING_STABILITY:g}; allowed: less than "
          f"{c_max:.3g} N*m/rad here (or a smaller solver.dt, more solver.substeps or longer "
          "links)")


def _check_joint_damper(sim: SimConfig, where: str, h: float) -> None:
    """``chain.bending_damping`` within the step the damper is the damper at
    (:data:`chainfountain.sim.joints.DAMPER_X`)."""
    d = sim.chain.bending_damping
    if d <= 0.0 or joints.damper_x(sim.chain, h) <= joints.DAMPER_X:
        return
    x = joints.damper_x(sim.chain, h)
    need = math.ceil(sim.solver.substeps * x / joints.DAMPER_X - 1e-12)
    _fail(where, "chain.bending_damping",
          f"{d!r} N*m*s/rad takes 1 - exp(-{x:.3g}) of a joint's relative spin each "
          f"{h:g} s pymunk step with {sim.chain.link_length:g} m links, and so damps less "
          f"than it says; allowed: at most {joints.damping_limit(sim.chain, h):.3g} N*m*s/rad "
          f"here (or solver.substeps >= {need})")


def _check_controls(level: Level, where: str) -> None:
    """``meta.controls`` names numeric fields this level has (each becomes a slider)."""
    other = tuple(f"{table}." for table in KINDS if table != level.sim.kind)
    known = [path for path, _, _ in iter_numeric_fields(level.sim)
             if not path.startswith(other)]
    for path in level.meta.control_paths():
        if path not in known:
            shown = ", ".join(known[:6])
            _fail(where, "meta.controls", f"{path!r} is not a number field of this level; "
                  f"allowed: its number fields, separated by commas (such as {shown})")


def _check_other_kind(sim: SimConfig, where: str) -> None:
    """The table of the other level kind is left out or at its defaults (it has no effect)."""
    defaults = SimConfig()
    for name in KINDS:  # the level file's kind tables
        if name == sim.kind:
            continue
        table, default = getattr(sim, name), getattr(defaults, name)
        for f in dataclasses.fields(table):
            value = getattr(table, f.name)
            if value != getattr(default, f.name):
                _fail(where, f"{name}.{f.name}",
                      f"{value!r} has no effect in a {sim.kind!r} level (the [{name}] table "
                      f"belongs to kind {name!r}); allowed: {getattr(default, f.name)!r} or "
                      f"no [{name}] table")


def _check_accuracy_scope(sim: SimConfig, where: str) -> None:
    """``solver.accuracy`` only where its error model was measured
    (:attr:`~chainfountain.sim.kinds.base.Kind.accuracy_refusal`: a fed fountain, motor-fed
    or an ideal machine's, landing on an absorbing floor, without blocks in the scene or
    self-collision; a beaker at the chain and solver its step error was refined at)."""
    if sim.solver.accuracy == 0.0:
        return
    why = kind_of(sim).accuracy_refusal(sim)
    if why is not None:
        _fail(where, "solver.accuracy",
              f"{sim.solver.accuracy!r} with {why}: no error model chooses the settings there "
              "(solver.accuracy covers fed fountains, motor-fed or ideal machines, on an "
              "absorbing floor, and the shipped beaker, whose step error was refined); allowed: 0 "
              "(use the level's own link length, step and iterations)")
