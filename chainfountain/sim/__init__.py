"""Physics core of chainfountain: pymunk model of a fed chain fountain (no pygame here).

Main entry points::

    from chainfountain.level import io, library
    from chainfountain.sim import Simulation, Recorder
    sim = Simulation(io.load(library.resolve("paper_tall")).sim)
    rec = Recorder(sim)
    sim.advance(10.0)
    print(rec.summary().errors(sim.reference))

A free chain without a feed (folds, drops onto a scale)::

    from chainfountain.sim import ChainScene
    scene = ChainScene(points)        # a polyline, one link per segment
    pin = scene.pin(0)
    scene.advance(0.3)
    scene.points(), scene.velocities(), scene.tensions(), scene.pin_force(pin)
"""

from chainfountain.sim.config import (
    CartConfig,
    ChainConfig,
    FeedConfig,
    InitialConfig,
    RecordingConfig,
    RollerConfig,
    SimConfig,
    SolverConfig,
)
from chainfountain.sim.recorder import Recorder
from chainfountain.sim.reference import LaunchReference
from chainfountain.sim.scene import ChainScene, Pin
from chainfountain.sim.world import Simulation

__all__ = [
    "CartConfig",
    "ChainConfig",
    "ChainScene",
    "FeedConfig",
    "InitialConfig",
    "LaunchReference",
    "Pin",
    "Recorder",
    "RecordingConfig",
    "RollerConfig",
    "SimConfig",
    "Simulation",
    "SolverConfig",
]
