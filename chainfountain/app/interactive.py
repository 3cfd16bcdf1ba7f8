"""The settings the window runs a level at, so that it stays interactive.

A level's ``solver.accuracy`` chooses its link length, step and iterations when it is
loaded (:mod:`chainfountain.level.resolve`), and ``chainfountain run`` runs those. Where
they cost more than one core can simulate at real time (the error model's estimate,
:func:`chainfountain.app.cost.cost`, above :data:`REAL_TIME_COST`), the window runs the
settings of the finest coarser accuracy of :data:`LADDER` that costs at most
:data:`~chainfountain.app.cost.WINDOW_COST`, and says so; its readout then gives the bar
those settings have. The level itself (what is saved, what ``run`` runs) keeps the
accuracy asked for, and the window's budget for changes (:func:`over_budget`) reads
what it would run. No pygame here.
"""

from __future__ import annotations

from dataclasses import dataclass

from chainfountain.app import cost
from chainfountain.sim import accuracy
from chainfountain.sim.config import SimConfig
from chainfountain.sim.kinds import kind_of

REAL_TIME_COST = 1.0
"""Estimated wall seconds per simulated second above which a level's chosen settings
cannot be held at real time in the window: the physics alone would take longer than the
time it simulates. Measured: ``paper_tall`` (estimate 0.94) runs at 0.96x in the window
(``docs/benchmarks.md``, ``bench_app.py``), so it keeps its settings."""

LADDER = (0.0075, 0.01, 0.015, 0.02, 0.03, 0.05)
"""The coarser accuracies the window tries, finest first."""


@dataclass(frozen=True)
class WindowSettings:
    """What the window runs (:func:`window_settings`)."""

    config: SimConfig
    """The configuration to build: the level's own, or a copy at coarser settings."""
    asked: float
    """The level's ``solver.accuracy``."""
    asked_cost: float | None = None
    """When coarsened: the estimated wall seconds per simulated second of the level's own
    settings (``None``: not coarsened)."""

    @property
    def coarsened(self) -> bool:
        return self.asked_cost is not None

    @property
    def ran(self) -> float:
        """The accuracy the settings that run were chosen for."""
        return self.config.solver.accuracy


def window_settings(sim: SimConfig) -> WindowSettings:
    """The settings the window runs ``sim`` at (see the module docstring): ``sim`` itself
    unless its accuracy's settings cost more than :data:`REAL_TIME_COST` and a coarser
    accuracy's cost at most :data:`~chainfountain.app.cost.WINDOW_COST`."""
    asked = sim.solver.accuracy
    kind = kind_of(sim)
    if asked <= 0.0 or kind.choose_settings is None or kind.accuracy_refusal(sim) is not None:
        return WindowSettings(sim, asked)
    own = cost.cost(sim)
    if own is None or own[1] <= REAL_TIME_COST:
        return WindowSettings(sim, asked)
    for acc in (a for a in LADDER if a > asked):
        try:
            trial = kind.choose_settings(sim, acc)
        except accuracy.OutOfReach:
            continue
        c = cost.cost(trial)
        if c is not None and c[1] <= cost.WINDOW_COST:
            trial.solver.accuracy = acc  # choose_settings gave a copy
            return WindowSettings(trial, asked, own[1])
    return WindowSettings(sim, asked)


def over_budget(sim: SimConfig, origin: SimConfig) -> str | None:
    """:func:`chainfountain.app.cost.over_budget` of what the window would run: ``sim`` (a
    change of the level ``origin``) and ``origin``, each at :func:`window_settings`."""
    return cost.over_budget(window_settings(sim).config, window_settings(origin).config)


def coarsened_message(ws: WindowSettings) -> str:
    """What the window says when it runs coarser settings than the level asks for."""
    s, c = ws.config, ws.asked_cost
    assert c is not None
    return (f"solver.accuracy {100 * ws.asked:g} % would run at about {1.0 / c:.2g}x real "
            f"time here; the window runs the settings of {100 * ws.ran:g} % "
            f"({1e3 * s.chain.link_length:g}-mm links, {1e6 * s.solver.dt:g} us, "
            f"{s.solver.iterations} iterations; `chainfountain run` meets "
            f"{100 * ws.asked:g} %)")
