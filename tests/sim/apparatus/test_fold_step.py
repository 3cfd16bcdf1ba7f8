"""The fold is not converged in the time step (issue 4).

A physical result must not depend on the solver step once the step is small enough.
The put-down rig alone (:mod:`research.rigs.pickup`, 2 cm links, 3 m/s, push
``0.4 lambda v^2``) is converged: entry tension 0.489, 0.467, 0.459, 0.451 at dt 0.5,
0.25, 0.1, 0.03 ms, the roller at ``v_R/v`` 0.503-0.509. The apparatus's fold is not:
``apparatus_special`` (3 s, window 0.5-3 s) with the channel's walls holds at dt 0.5,
0.4 and 0.35 ms (lower ``v_R/v`` 0.50), but at 0.25 ms its folding roller falls behind
(``v_R/v`` 0.30) and the run ends at 2.1 s, and at 0.1 ms it ends at 0.16 s (with the
preset's joint guide: holds at 0.35-0.5 ms with ``v_R/v`` 0.501, ends at 0.65 s at
0.25 ms and at 0.16 s at 0.1 ms; ``fold_step_study.py --only special --dt 0.5 0.4 0.35
0.25 0.1 --seconds 3``); ``apparatus_fold`` behaves the same (walls: holds at
0.35-0.5 ms, ends at 2.08 s at 0.25 ms; joint guide: holds at 0.35 ms, ends at 1.96 s
at 0.25 ms). So the fold presets' balances (the 58 g and 41 g lower carts) hold at
their 0.5 ms step only. The passing test pins that a collapse at a small step says so
(instead of advising a heavier cart); the strict expected failure is the converged fold.
docs/apparatus.md, "The fold depends on the time step".

The cause is a clamp. The lower plate's groove line sits exactly on the folding roller's
top, so the roller is held between that rigid line and the chain on the table; at small
steps the clamp locks (mean vertical contact force from the links on the roller's top
over the first 0.15 s: 0.49 N at 0.5 ms, 21 N at 0.1 ms; the roller weighs 0.2 N).
``apparatus.fold_clearance = 0.002`` (the lower table 2 mm lower) removes
it: 0.15-0.52 N at 0.1-0.5 ms, and with a 46 g lower cart no run at 0.1, 0.25, 0.35 or
0.5 ms collapsed in 3 s. It does not make the fold converged: at 0.1 ms the roller
still slips part of the time (window 0.5-3 s: ``v_R/v`` 0.472, drift +4.1 %/s; 0.5 ms:
0.501, +0.09 %/s). ``research/fold_step_study.py --only special --clearance 0.002
--lower-cart 0.046``.

With the channel's walls, 2 mm and a 44 g lower cart (``fold_step_study.py --seconds 6
--speeds 2.94 2.97 3.0 3.03 3.06``), 9 of 10 runs at 0.5 and 0.25 ms hold cleanly for 6 s
(the preset: 5 of 5 at 0.5 ms, 0 of 5 at 0.25 ms), and the same start gives the same
speed at both steps within 0.6 %. At 0.1 ms it still collapses, after 2.9-4.4 s: the
landing swing (a speed oscillation of period 2.4-3 s with the folding roller lagging)
grows there instead of staying bounded.
"""

from __future__ import annotations

import dataclasses

import pytest

from chainfountain.level.library import shipped_dir
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus import FoldCollapsed
from chainfountain.sim.apparatus_report import report
from chainfountain.sim.config import SimConfig
from tests.sim.apparatus.runs import load_undamped

LEVEL = shipped_dir() / "apparatus_special.toml"
pytestmark = [pytest.mark.xdist_group("apparatus_fold_step"), pytest.mark.slow]  # minutes of runs


def _special(dt: float, clearance: float = 0.0, lower_cart: float = 0.058) -> SimConfig:
    cfg = load_undamped(LEVEL).sim
    assert cfg.apparatus.fold_clearance == 0.0 and cfg.carts[1].mass == 0.058
    carts = [cfg.carts[0], dataclasses.replace(cfg.carts[1], mass=lower_cart)]
    return dataclasses.replace(
        cfg, solver=dataclasses.replace(cfg.solver, dt=dt, substeps=1), carts=carts,
        apparatus=dataclasses.replace(cfg.apparatus, fold_clearance=clearance))


def test_collapse_at_a_small_step_names_the_step():
    """At dt 0.1 ms the special preset's fold collapses within its first 0.5 s (measured
    0.16 s); the message blames the step, not the cart, and says what step holds."""
    sim = Simulation(_special(1e-4))
    with pytest.raises(FoldCollapsed) as info:
        sim.advance(0.5)
    msg = str(info.value)
    assert "solver.substeps = 0.0001 s" in msg and "a pymunk step of 0.0005 s" in msg
    assert "set apparatus.fold_clearance = 0.002" in msg
    assert "raise the lower cart mass" not in msg


def test_fold_clearance_unlocks_the_fold_at_a_small_step():
    """The same step with the lower table 2 mm below the groove line (and the lighter
    cart that clearance needs): the folding roller keeps rolling at ``v/2`` for 1 s
    (measured over 0.2-1.0 s: ``v_R/v`` 0.501; without the clearance the run ends at
    0.16 s), and the table really is lower."""
    sim = Simulation(_special(1e-4, clearance=0.002, lower_cart=0.046))
    app = sim.apparatus
    assert app.y_lo - app.y_table_lo == pytest.approx(
        3 * app.rho + 2 * app.r + 0.002, abs=1e-12)
    rec = Recorder(sim, profiles=False)
    sim.advance(1.0)
    m = report(sim, rec, 0.2, 1.0)["measured"]
    assert m["roller_ratio_lo"] == pytest.approx(0.5, abs=0.02)


def _held(cfg: SimConfig, seconds: float = 6.0) -> dict:
    sim = Simulation(cfg)
    rec = Recorder(sim, profiles=False)
    sim.advance(seconds)
    return report(sim, rec, 0.5, seconds)["measured"]


def test_fold_with_clearance_agrees_at_half_the_step():
    """With 2 mm of clearance and a 44 g lower cart the fold gives the same run at 0.5
    and 0.25 ms. From the preset's 3.0 m/s start, both hold for 6 s with the folding
    roller at ``v/2`` and the speed steady (window 0.5-6 s; measured 2.991 and 3.000 m/s,
    drift -0.02 and -0.10 %/s, ``v_R/v`` 0.501 both). With the preset's upper channel, a
    joint guide (``fold_step_study.py --only special --clearance 0.002 --lower-cart 0.044
    --dt 0.5 0.25 --speeds 2.94 2.97 3.0 3.03 3.06``): all five starts hold at 0.5 ms,
    three at 0.25 ms (3.0, 3.03, 3.06; the 2.94 and 2.97 starts end at 5.7 and 5.5 s),
    8 of 10; a 40 g cart holds 1 of 10. With the channel's walls: 9 of 10 (from 2.97 m/s:
    2.963 and 2.961 m/s; the 3.0 m/s start slipped at 0.5 ms, ``v_R/v`` 0.480); the
    preset without clearance holds all five at 0.5 ms and none at 0.25 ms. At 0.1 ms this
    configuration still collapses after 3-4 s (docs/apparatus.md, 'The fold depends on
    the time step')."""
    runs = [_held(_special(dt, clearance=0.002, lower_cart=0.044)) for dt in (5e-4, 2.5e-4)]
    for m in runs:
        assert m["roller_ratio_lo"] == pytest.approx(0.5, abs=0.02)
    # Over 6 nudged starts (1e-12, tests/conftest.py --perturb) the 0.5-ms run drifts
    # -0.03 ... +0.14 %/s and holds 2.996-3.005 m/s; the 0.25-ms run drifts -0.10 ...
    # +0.84 %/s and holds 3.001-3.046 m/s (one start in six moves up by 1.5 %): the
    # issue's 1 %/s at 0.5 ms, three of the smaller step's standard deviations (0.34 %/s
    # and 0.55 %) at 0.25 ms
    assert abs(runs[0]["speed_drift_per_s"]) <= 0.01
    assert abs(runs[1]["speed_drift_per_s"]) <= 0.015
    assert runs[1]["v"] == pytest.approx(runs[0]["v"], rel=0.025)


@pytest.mark.xfail(strict=True, raises=(FoldCollapsed, AssertionError),
                   reason="the apparatus's fold is not converged in the step: at dt 0.25 ms "
                   "the special preset's folding roller falls behind and the run ends at "
                   "0.65 s (2.1 s with the channel's walls; docs/apparatus.md, 'The fold "
                   "depends on the time step')")
def test_special_fold_holds_at_half_the_step():
    """The special preset at half its step (0.25 ms) should run as at 0.5 ms: no
    collapse in 2.5 s, the folding roller at ``v/2``, the speed steady."""
    sim = Simulation(_special(2.5e-4))
    rec = Recorder(sim, profiles=False)
    sim.advance(2.5)
    m = report(sim, rec, 0.5, 2.5)["measured"]
    assert m["roller_ratio_lo"] == pytest.approx(0.5, abs=0.02)
    assert abs(m["speed_drift_per_s"]) <= 0.01
