"""The settings a level runs with: the named step between its checks and its run.

A level with ``solver.accuracy`` above 0 asks for its settings to be chosen for that
accuracy by its kind's error model (:attr:`~chainfountain.sim.kinds.base.Kind.choose_settings`:
a fed fountain's link length, step and iterations from :mod:`chainfountain.sim.accuracy`,
:mod:`chainfountain.sim.kinds.fed_accuracy`; a beaker's step from
:mod:`chainfountain.sim.beaker_error`); :func:`resolve` returns the level with them,
which is what runs and what is recorded.
"""

from __future__ import annotations

import copy
import dataclasses
import math

from chainfountain.level.model import Level, _fail
from chainfountain.sim import accuracy
from chainfountain.sim.kinds import kind_of

CHOSEN = frozenset({"chain.link_length", "solver.dt", "solver.iterations",
                    "solver.substeps"})
"""The fields ``solver.accuracy`` chooses. A change that sets one of them to another value
(the window's slider, a sweep's grid, ``FIELD=VALUE``) takes it over: the accuracy is
turned off for that level (:func:`chainfountain.level.paths.changed`), since otherwise
the accuracy would choose it again and the change would silently do nothing."""


def resolve(level: Level, where: str) -> tuple[Level, bool]:
    """The level that runs, and whether its settings were chosen: ``level`` itself when
    ``solver.accuracy`` is 0, else a copy at the cheapest settings its kind's error model
    gives for the accuracy asked (``level`` is not changed).

    A level the model cannot reach the accuracy for is refused with the best bound it
    can reach (:class:`chainfountain.sim.accuracy.OutOfReach`)."""
    acc = level.sim.solver.accuracy
    kind = kind_of(level.sim)
    if acc == 0.0 or kind.choose_settings is None \
            or kind.accuracy_refusal(level.sim) is not None:
        return level, False
    try:
        sim = kind.choose_settings(level.sim, acc)
    except accuracy.OutOfReach as exc:
        least = (f"at least {math.ceil(exc.best * 1e4) / 1e4:g}, or 0" if math.isfinite(exc.best)
                 else "0")
        hint = " (0: the level's own settings" + (
            ", with `chainfountain converge LEVEL` for their error)" if kind.predicted else ")")
        _fail(where, "solver.accuracy", f"{acc!r}: {exc}; allowed: {least}{hint}")
    return dataclasses.replace(level, meta=copy.deepcopy(level.meta), sim=sim), True
