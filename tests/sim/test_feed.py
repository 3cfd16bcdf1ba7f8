"""Fed fountains (every shipped ``kind = "feed"`` level) against the paper's inverted catenary.

Each preset starts on the predicted curve (``initial.mode = "catenary"``; the demo
levels themselves start from a stub and form), settles for ``SETTLE`` s and is then
time-averaged over ``WINDOW`` s. Tolerances are the project's acceptance
criteria (issue 3); measured values are in ``docs/convergence.md``.
"""

from __future__ import annotations

import functools
from pathlib import Path

import pytest

from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.measure import Summary
from tests import shipped

NEAR_CRITICAL = {"fountain_d", "fountain_d_kmax"}
"""The paper's fountain D presets: near-critical (``k/q`` = 0.017 / 0.019), at 15 / 18 us
steps the costliest runs of the suite. Over a window like this one their vertex is
+1.2 % high and 2.6 / 2.8 % short of the predicted x (the first-order creep of
docs/convergence.md, "Near-critical fountains"), outside these criteria; they are held to
the design (3 %) and the paper's figures by tests/cli/test_design_levels.py (``paper_D``,
the same run as ``fountain_d``: test_fountain_d.py checks the preset is what ``design``
writes) and tests/sim/test_fountain_d.py (``fountain_d_kmax``), and not run again here."""

FEED_LEVELS = [p for p in shipped.PATHS
               if io.load(p).sim.kind == "feed" and io.load(p).sim.feed.drive == "motor"
               and p.stem not in NEAR_CRITICAL]
"""The motor-driven fed levels (the ideal floor machine selects its own speed:
tests/sim/test_ideal_floor.py) but fountain D's (:data:`NEAR_CRITICAL`)."""

SETTLE = 1.5
WINDOW = 2.0


@pytest.fixture(scope="module", params=[
    # one worker runs all of a level's tests (``--dist loadgroup``): the run is made once
    pytest.param(p, id=p.stem, marks=pytest.mark.xdist_group(f"feed_{p.stem}"))
    for p in FEED_LEVELS])
def run(request) -> tuple[Simulation, Summary]:
    return _steady_run(request.param)


@functools.lru_cache(maxsize=len(FEED_LEVELS))
def _steady_run(path: Path) -> tuple[Simulation, Summary]:
    """A level's run, made once per worker even if its tests do not follow each other
    there (pytest 9.2 stopped xdist's grouping, pytest-xdist issue 1386, and fountain D's
    50-s run was made on both workers)."""
    cfg = io.load(path).sim
    cfg.initial.mode = "catenary"  # the demo levels form from a stub; this window studies
    sim = Simulation(cfg)         # the fountain itself (the long self-formed runs:
    # research/long_runs.py)
    sim.advance(SETTLE)
    rec = Recorder(sim)
    sim.advance(WINDOW)
    return sim, rec.summary(window=WINDOW)


# The stiff chain is compared with the stiff-chain theory (chainfountain.sim.stiff_reference):
# at its 4-cm links and 4 sub-steps its vertex sits 2.7 % below it (1.9 % at 16 sub-steps,
# where pymunk's exponential damper takes 98 % of d a step instead of 93 %; the same links
# without springs and dampers sit 1.2 % above the catenary), the landing 0.9 % beyond.
HEIGHT_TOLERANCE = {"stiff_chain": 0.035}


@pytest.mark.slow
def test_geometry_matches_catenary(run, request) -> None:
    sim, s = run
    e = s.errors(sim.reference)
    assert abs(e["h"]) < HEIGHT_TOLERANCE.get(request.node.callspec.id, 0.01), e
    assert abs(e["vertex_x"]) < 0.03, e
    assert abs(e["l"]) < 0.03, e


@pytest.mark.slow
def test_speed_uniform_and_chain_inextensible(run) -> None:
    sim, s = run
    assert s.speed_uniformity < 0.01
    assert abs(s.speed_mean / sim.feed.speed - 1.0) < 0.01
    assert s.stretch_max <= 1e-3


@pytest.mark.slow
def test_tension_follows_paper(run) -> None:
    """Scaled tension along the free chain vs ``Tbar = 1 - k/q + k*y`` (RMS)."""
    sim, s = run
    assert s.tension_rms < 0.03
    assert s.extras["tension_bar"].min() > -0.03  # no pushing anywhere on average


@pytest.mark.slow
def test_stub_start_becomes_the_same_steady_fountain() -> None:
    """From a short stub the default fountain settles (about 9-13 s) onto the catenary."""
    from chainfountain.sim import SimConfig

    cfg = SimConfig()
    cfg.initial.mode = "stub"
    sim = Simulation(cfg)
    rec = Recorder(sim)
    sim.advance(16.0)
    s = rec.summary(window=2.0)
    assert s.steady_from is not None and s.steady_from < 14.0
    e = s.errors(sim.reference)
    assert abs(e["h"]) < 0.01, e
    assert abs(e["l"]) < 0.03, e
