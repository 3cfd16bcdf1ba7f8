"""The fold is not converged in the time step (issue 4; measured in the twelfth session).

A physical result must not depend on the solver step once the step is small enough.
The put-down rig alone (:mod:`chainfountain.sim.pickup`, 2 cm links, 3 m/s, push
``0.4 lambda v^2``) is converged: entry tension 0.489, 0.467, 0.459, 0.451 at dt 0.5,
0.25, 0.1, 0.03 ms, the roller at ``v_R/v`` 0.503-0.509. The apparatus's fold is not:
``apparatus_special`` (3 s, window 0.5-3 s) holds at dt 0.5, 0.4 and 0.35 ms (lower
``v_R/v`` 0.50), but at 0.25 ms its folding roller falls behind (``v_R/v`` 0.30) and the
run ends at 2.1 s, and at 0.1 ms it ends at 0.16 s; ``apparatus_fold`` behaves the same
(holds at 0.35-0.5 ms, ends at 2.08 s at 0.25 ms). So the fold presets' balances (the
58 g and 41 g lower carts) hold at their 0.5 ms step only. The passing test pins that a
collapse at a small step says so (instead of advising a heavier cart); the strict
expected failure is the converged fold. docs/apparatus.md, "Twelfth session".
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus import FoldCollapsed
from chainfountain.sim.apparatus_report import report
from chainfountain.sim.config import SimConfig

LEVEL = Path(__file__).resolve().parents[1] / "levels" / "apparatus_special.toml"
pytestmark = pytest.mark.xdist_group("apparatus_fold_step")


def _special(dt: float) -> SimConfig:
    cfg = io.load(LEVEL).sim
    return dataclasses.replace(cfg, solver=dataclasses.replace(cfg.solver, dt=dt))


def test_collapse_at_a_small_step_names_the_step():
    """At dt 0.1 ms the special preset's fold collapses within its first 0.5 s (measured
    0.16 s); the message blames the step, not the cart, and says what step holds."""
    sim = Simulation(_special(1e-4))
    with pytest.raises(FoldCollapsed) as info:
        sim.advance(0.5)
    msg = str(info.value)
    assert "solver.dt = 0.0001 s" in msg and "set solver.dt = 0.0005" in msg
    assert "raise the lower cart mass" not in msg


@pytest.mark.xfail(strict=True, raises=(FoldCollapsed, AssertionError),
                   reason="the apparatus's fold is not converged in the step: at dt 0.25 ms "
                   "the special preset's folding roller falls behind and the run ends at "
                   "about 2.1 s (docs/apparatus.md, 'Twelfth session')")
def test_special_fold_holds_at_half_the_step():
    """The special preset at half its step (0.25 ms) should run as at 0.5 ms: no
    collapse in 2.5 s, the folding roller at ``v/2``, the speed steady."""
    sim = Simulation(_special(2.5e-4))
    rec = Recorder(sim, profiles=False)
    sim.advance(2.5)
    m = report(sim, rec, 0.5, 2.5)["measured"]
    assert m["roller_ratio_lo"] == pytest.approx(0.5, abs=0.02)
    assert abs(m["speed_drift_per_s"]) <= 0.01
