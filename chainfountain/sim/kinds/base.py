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
"""Simulated seconds of a headless run when none is given."""
FORMING_DURATION = 20.0
"""... of a fed level that starts from its stub (the shipped ones are steady after 4-12 s),
and of an apparatus started from rest (its starter lets go about 4 s in)."""
MACHINE_FORMING_DURATION = 40.0
"""... of an ideal machine started from its stub: the starter hands over 5 s after landing,
and the presets settle on their laws' speed 10-15 s after that (``ideal_fold`` from 4.7
to within 0.5 % of 5.0 m/s by about 15 s)."""

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
    config: type
    """The dataclass of its table (:attr:`table`), in :mod:`chainfountain.sim.config`."""
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
    accuracy_refusal: Callable[[SimConfig], str | None] = lambda cfg: f"kind = {cfg.kind!r}"
    """Why ``solver.accuracy`` cannot choose this level's settings (``None``: it can)."""
    choose_settings: Callable[[SimConfig, float], SimConfig] | None = None
    """The settings ``solver.accuracy`` chooses (``choose_settings(config, accuracy)``: a
    copy of the configuration at the cheapest settings the kind's error model gives for
    the accuracy; raises :class:`~chainfountain.sim.accuracy.OutOfReach` with the best
    bound it reaches); ``None``: the kind has no such model."""
    default_accuracy: float = 0.0
    """The ``solver.accuracy`` a level file of this kind gets when it sets none of the
    fields the accuracy chooses (``chain.link_length``, ``solver.dt``,
    ``solver.iterations``, ``solver.substeps``) nor the accuracy itself, where the error
    model reaches it (else the schema's settings, with the bound the model gives them or
    why it gives none); 0: none."""
    style: Callable[[SimConfig], str] = lambda cfg: ""
    """The finer style of the kind a level has (a feed's drive, an apparatus's variant),
    for the window's defaults."""
    start_region: Callable[[SimConfig], bool] = lambda cfg: False
    """Whether the level starts from rest where a measured start region admits it (the
    contact machines: :func:`chainfountain.sim.apparatus.region.from_rest`), so that the
    window's sliders span that region."""
    seed_field: str = "initial.seed"
    """The field ``--seed`` sets."""
    solver_defaults: Mapping[str, Any] = field(default_factory=dict)
    """The kind's own defaults for ``[solver]`` fields a level file leaves out (measured
    where the schema's, the fed fountains', are wrong for it); the level loader fills
    them in before the table is read."""
    unseeded: Callable[[SimConfig], str | None] = lambda cfg: None
    """Why a seed has no effect on this level (``None``: it picks another run)."""
    sections: tuple[str, ...] = ()
    """The sections of ``summary.json`` the kind adds besides ``theory``
    (:data:`chainfountain.headless.summary.SECTIONS` builds them)."""
    predicted: bool = False
    """Whether the paper predicts the fountain from the level's settings (a fed level):
    its runs are compared with that prediction and can be refined."""
    half_step_bars: bool = False
    """Whether ``run --error-bars`` gives the step's error of its figures by running it
    again at half its step (:mod:`chainfountain.headless.apparatus_refine`: a kind with
    no error model whose fountain the paper does not predict from its settings)."""
    paper_curve: bool = True
    """Whether the window draws the paper's curve when the level opens."""
    stiff_theory: bool = False
    """Whether a chain with joint springs or dampers is compared with the steady stiff
    fountain (:mod:`chainfountain.sim.stiff_reference`) instead of the paper's catenary
    (the motor-fed fountain; the machines' laws are the paper's string model's)."""
    study_start: Callable[[SimConfig], dict[str, Any]] = lambda cfg: {}
    """The changes that start a study of the level on its steady state (the apparatus
    laid along its path instead of forming from rest)."""
    fountain: bool = True
    """Whether it runs as a :class:`~chainfountain.sim.world.Simulation` (the window
    shows it); a scene runs headless only."""
