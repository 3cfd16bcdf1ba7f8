"""The settings ``solver.accuracy`` chooses for a fed fountain, motor-fed or an ideal
machine's flight at the speed its laws select (:mod:`chainfountain.sim.accuracy`'s error
model): the cheapest link length, step and iterations whose bounds are within it, with
joint springs and dampers scaled to the chosen links so that the chain is the same
(:func:`chainfountain.sim.joints.same_chain`) and the sub-steps their spring needs."""

from __future__ import annotations

import copy

from chainfountain.sim import accuracy, joints
from chainfountain.sim.config import SimConfig
from chainfountain.sim.reference import LaunchReference


def choose_settings(cfg: SimConfig, acc: float) -> SimConfig:
    """A copy of ``cfg`` at the settings chosen for ``acc``; raises
    :class:`~chainfountain.sim.accuracy.OutOfReach` (with the best bound) where the model
    does not reach it or does not apply."""
    sim = copy.deepcopy(cfg)
    ref = LaunchReference.of_level(sim)  # an ideal machine's: at the speed its laws select
    est = accuracy.choose(ref, acc, sim.chain, machine=sim.feed.drive != "motor")
    s = est.settings
    joints.same_chain(sim.chain, s.link_length)
    sim.chain.link_radius = min(sim.chain.link_radius, 0.4 * s.link_length)
    sim.solver.dt = s.dt
    sim.solver.substeps = 1
    sim.solver.substeps = joints.substeps_for_spring(sim.chain, sim.solver)
    sim.solver.iterations = s.iterations
    return sim
