"""Physics core of chainfountain: pymunk model of a fed chain fountain (no pygame here).

Main entry points::

    from chainfountain.sim import Simulation, Recorder, presets
    sim = Simulation(presets.paper_tall())
    rec = Recorder(sim)
    sim.advance(10.0)
    print(rec.summary().errors(sim.reference))
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
from chainfountain.sim.world import Simulation

__all__ = [
    "CartConfig",
    "ChainConfig",
    "FeedConfig",
    "InitialConfig",
    "LaunchReference",
    "Recorder",
    "RecordingConfig",
    "RollerConfig",
    "SimConfig",
    "Simulation",
    "SolverConfig",
]
