"""The settings a level runs with: the named step between its checks and its run.

A level with ``solver.accuracy`` above 0 asks for its link length, step and iterations to
be chosen for that accuracy (:mod:`chainfountain.sim.accuracy`'s error model, for a
motor-fed fountain or an ideal machine's flight at the speed its laws select; joint springs
and dampers are scaled to the chosen links so that the chain is the same,
:func:`chainfountain.sim.joints.same_chain`, with the sub-steps their spring needs);
:func:`resolve` returns the level with them, which is what runs and what is recorded.
"""

from __future__ import annotations

import copy
import math

from chainfountain.level.model import Level, _fail
from chainfountain.sim import accuracy, joints
from chainfountain.sim.accuracy import Estimate
from chainfountain.sim.kinds import kind_of
from chainfountain.sim.reference import LaunchReference

CHOSEN = frozenset({"chain.link_length", "solver.dt", "solver.iterations",
                    "solver.substeps"})
"""The fields ``solver.accuracy`` chooses. A change that sets one of them to another value
(the window's slider, a sweep's grid, ``FIELD=VALUE``) takes it over: the accuracy is
turned off for that level (:func:`chainfountain.level.paths.changed`), since otherwise
the accuracy would choose it again and the change would silently do nothing."""


def resolve(level: Level, where: str) -> tuple[Level, Estimate | None]:
    """The level that runs: ``level`` itself when ``solver.accuracy`` is 0, else a copy
    whose link length, step and iterations are the cheapest the error model gives for
    the accuracy asked, with the model's estimate for them (``level`` is not changed).

    A fountain the model cannot reach the accuracy for is refused with the best bound it
    can reach (:func:`chainfountain.sim.accuracy.choose`)."""
    acc = level.sim.solver.accuracy
    if acc == 0.0 or kind_of(level.sim).accuracy_refusal(level.sim) is not None:
        return level, None
    level = copy.deepcopy(level)
    sim = level.sim
    ref = LaunchReference.of_level(sim)  # an ideal machine's: at the speed its laws select
    try:
        est = accuracy.choose(ref, acc, sim.chain, machine=sim.feed.drive != "motor")
    except accuracy.OutOfReach as exc:
        least = (f"at least {math.ceil(exc.best * 1e4) / 1e4:g}, or 0" if math.isfinite(exc.best)
                 else "0")
        _fail(where, "solver.accuracy", f"{acc!r}: {exc}; allowed: {least} (0: the level's own "
              "settings, with `chainfountain converge LEVEL` for their error)")
    s = est.settings
    joints.same_chain(sim.chain, s.link_length)
    sim.chain.link_radius = min(sim.chain.link_radius, 0.4 * s.link_length)
    sim.solver.dt = s.dt
    sim.solver.substeps = 1
    sim.solver.substeps = joints.substeps_for_spring(sim.chain, sim.solver)
    sim.solver.iterations = s.iterations
    return level, est
