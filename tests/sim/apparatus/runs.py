"""Shared run for the fold-variant tests (imported by the test modules, not collected)."""

from __future__ import annotations

from pathlib import Path

from chainfountain.level import io
from chainfountain.level.model import Level
from chainfountain.sim import Recorder, SimConfig, Simulation
from chainfountain.sim.apparatus_report import report
from chainfountain.study.changes import laid_on_path, with_changes


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
        held.append(len(sim.apparatus.fold_held[0]))
    return sim, report(sim, rec, *clean), held, [report(sim, rec, *w) for w in windows]


DESIGN_RIG_2CM = ((2.6, 0.331), (2.9, 0.315), 0.68)
"""The 2 cm rig law the fountain D and limit presets' upper carts were sized with: pick-up
``p`` linear in ``v`` through the two points, cart gain 0.68, read through the rig's
contacts with their stale impulses left in. The presets keep those
carts (their runs are measured with them); the report predicts with
:data:`chainfountain.sim.apparatus.PICKUP_RIG_2CM`."""


def design_pickup(v: float) -> float:
    """``p(v)`` of :data:`DESIGN_RIG_2CM`."""
    (v0, p0), (v1, p1), _ = DESIGN_RIG_2CM
    return p0 + (p1 - p0) * (v - v0) / (v1 - v0)


def design_speed(g: float, H: float, xi2: float, F_uc: float, lam: float) -> float:
    """The speed :data:`DESIGN_RIG_2CM` selects for a free end (fixed point of
    ``v**2 = (g*H*(1 - xi2) - G*F_uc/lambda)/p(v)``)."""
    num = g * H * (1.0 - xi2) - DESIGN_RIG_2CM[2] * F_uc / lam
    v = (num / 0.3) ** 0.5
    for _ in range(200):
        v = (num / design_pickup(v)) ** 0.5
    return v


def load_on_path(path: Path) -> Level:
    """The level at ``path`` started the study way, laid along its path at
    ``apparatus.speed`` (:func:`~chainfountain.study.changes.laid_on_path`), so that a test
    reads the machine's steady state without waiting for it to form from rest."""
    return laid_on_path(io.load(path))


STUDY_STEP = {"solver.dt": 0.0005, "solver.substeps": 1}
"""The fold studies' step: pymunk's 0.5 ms with the bookkeeping in every step, where the
fold's own behaviour was measured (the shipped presets do their bookkeeping every second
step, ``substeps = 2``; docs/apparatus.md, "Step and bookkeeping")."""


def load_undamped(path: Path) -> Level:
    """The fold level at ``path`` without its swing damper (``apparatus.swing_damper = 0``)
    at :data:`STUDY_STEP`: the contact fold's own behaviour, whose landing swing grows until
    the fold fails (``apparatus_special`` at 19-28 s; docs/apparatus.md, "The landing
    swing"), which the tests of the fold's laws read."""
    return with_changes(io.load(path), {"apparatus.swing_damper": 0.0, **STUDY_STEP})


def load_real_geometry(path: Path) -> Level:
    """The fold level at ``path`` in the real geometry without its swing damper: tables
    sized by ``apparatus.duration`` (no treadmills), the rollers travelling at ``v/2``
    (``apparatus_fold`` as the tests of the full arrangement read it), at
    :data:`STUDY_STEP`."""
    return with_changes(io.load(path), {"apparatus.plate_links": 0,
                                        "apparatus.swing_damper": 0.0, **STUDY_STEP})
