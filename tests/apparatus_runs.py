"""Shared run for the fold-variant tests (imported by the test modules, not collected)."""

from __future__ import annotations

from chainfountain.sim import Recorder, SimConfig, Simulation
from chainfountain.sim.apparatus_report import report


def run_fold(cfg: SimConfig, until: float, clean: tuple[float, float],
             windows: list[tuple[float, float]]) -> tuple[Simulation, dict, list[int], list[dict]]:
    """Run a fold level to ``until`` s, counting the links in the first turn every 0.1 s;
    return the simulation, the report over ``clean``, the counts and the reports over
    ``windows``."""
    sim = Simulation(cfg)
    rec = Recorder(sim, profiles=False)
    held = []
    while sim.time < until - 1e-9:
        sim.advance(0.1)
        held.append(len(sim.apparatus._gq[0]))
    return sim, report(sim, rec, *clean), held, [report(sim, rec, *w) for w in windows]
