"""What a level kind is: the :class:`Kind` record every kind module fills in.

A kind (a motor-fed fountain, an ideal machine, the contact apparatus, the beaker, a
scene) is one package under :mod:`chainfountain.sim.kinds` that declares one ``KIND``:
the table of the level file it reads, how it is checked, how it is built, how long it
runs when no duration is given and what can change while it runs. The registry
(:mod:`chainfountain.sim.kinds`) looks kinds up; nothing else asks which kind a level is.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from chainfountain.sim.config import SimConfig

DEFAULT_DURATION = 8.0
"""Simulated seconds of a headless fountain run started on its fountain, when none is given."""

FORMING_DURATION = 20.0
"""Simulated seconds of a headless run that starts from a stub or from rest: it forms,
then is averaged."""

MACHINE_FORMING_DURATION = 40.0
"""Simulated seconds of a headless run of an ideal machine from its stub: it settles on its
laws' speed after its starter."""

Setter = Callable[[Any, int | None, float], None]
"""A live change: ``setter(simulation, index, value)`` (``index``: the list item of a path
such as ``carts[1].mass``, else ``None``), called after the value is written into the
simulation's configuration."""


@dataclass(frozen=True)
class Kind:
    """One level kind (see the module docstring)."""

    name: str
    """The registry's name: ``feed``, ``ideal``, ``apparatus``, ``beaker`` or ``scene``."""
    table: str
    """The level file's table the kind reads (``kind = "<table>"`` in the file)."""
    title: str
    """What the kind is, in a few words."""
    check: Callable[[SimConfig, str], None]
    """Cross-field checks (``check(config, where)``): raise a one-line
    :class:`~chainfountain.errors.LevelError`; never change the configuration."""
    default_duration: Callable[[SimConfig], float]
    """Simulated seconds of a headless run when none is given."""
    reach: Callable[[SimConfig], tuple[float, float]]
    """``(speed, size)``: the fastest chain speed (m/s) and the size (m) of the scene the
    divergence watchdog allows (:func:`chainfountain.sim.kinds.limits_for`)."""
    build: Callable[[Any], None] | None = None
    """Fills a :class:`~chainfountain.sim.world.Simulation` being built (its space made):
    the chain, the ends (:class:`~chainfountain.sim.ends.Ends`) and the parts; ``None``
    for a kind that is not a fountain (the scene runs as a
    :class:`~chainfountain.sim.scene_sim.SceneSimulation`)."""
    live: Mapping[str, Setter] = field(default_factory=dict)
    """The kind's own live fields (``"carts[].mass"`` for every list item) and their
    setters; the fields every fountain shares are :data:`chainfountain.sim.live.COMMON`."""
    seeded: Callable[[SimConfig], bool] = lambda cfg: True
    """Whether ``initial.seed`` (or ``--seed``) picks another run of this level."""
    accuracy_refusal: Callable[[SimConfig], str | None] = lambda cfg: "its kind"
    """Why ``solver.accuracy`` cannot choose this level's settings (``None``: it can)."""
    style: Callable[[SimConfig], str] = lambda cfg: ""
    """The finer style of the kind a level has (a feed's drive, an apparatus's variant),
    for the window's defaults."""
    fountain: bool = True
    """Whether it runs as a :class:`~chainfountain.sim.world.Simulation` (the window
    shows it); a scene runs headless only."""
