"""The beaker's step error model (:mod:`chainfountain.sim.beaker_error`) against the
refinement it was fitted on, and where it does not apply."""

from __future__ import annotations

import dataclasses

import pytest

from chainfountain.sim import beaker_error
from chainfountain.sim.config import ChainConfig, SolverConfig
from tests import shipped

REFINED = {  # research/beaker_refinement.py, docs/beaker.md: mean and sd over the seeds
    "speed": {2.5e-4: (4.388, 0.024), 1.25e-4: (4.523, 0.004), 6.25e-5: (4.588, 0.008)},
    "rise_above_rim": {2.5e-4: (0.278, 0.008), 1.25e-4: (0.313, 0.001),
                       6.25e-5: (0.328, 0.003)},
    "alpha_from_speed": {2.5e-4: (0.507, 0.006), 1.25e-4: (0.536, 0.001),
                         6.25e-5: (0.549, 0.002)},
}


@pytest.mark.parametrize("figure", sorted(REFINED))
def test_the_model_reproduces_the_refinement_it_was_measured_by(figure) -> None:
    """One zero-step value explains all three steps: each measured figure times
    ``1 + shortfall`` at its step gives the same value, within the seeds' spread (three
    standard deviations, the zero-step value's share of them)."""
    runs = REFINED[figure]
    zero = {dt: v * (1.0 + beaker_error.shortfalls(dt)[figure]) for dt, (v, _) in runs.items()}
    mean = sum(zero.values()) / len(zero)
    for dt, (v, sd) in runs.items():
        assert abs(zero[dt] - mean) <= 3.0 * sd * zero[dt] / v + 1e-3 * mean, (dt, zero)


def test_the_shipped_beaker_gets_bars_and_another_chain_a_reason() -> None:
    cfg = shipped.level("beaker").sim
    figures = {"speed": 4.39, "rise_above_rim": 0.28, "alpha_from_speed": 0.507}
    bars = beaker_error.error_bars(figures, cfg.chain, cfg.solver, cfg.beaker)
    assert bars["method"] == "error model" and bars["one_sided"] is True
    assert bars["shortfall"]["speed"] == pytest.approx(0.06, abs=0.005)
    assert bars["zero_step"]["rise_above_rim"] == pytest.approx(0.34, abs=0.01)
    other = beaker_error.error_bars(figures, ChainConfig(link_length=0.01),
                                    SolverConfig(dt=2.5e-4, iterations=6), cfg.beaker)
    assert other["method"] is None and "chain.link_length = 0.01" in other["how"]
    assert "research.beaker_refinement" in other["how"]
    # a longer step than refined: no extrapolation beyond the measured steps
    longer = beaker_error.error_bars(figures, cfg.chain, SolverConfig(dt=5e-4, iterations=6),
                                     cfg.beaker)
    assert longer["method"] is None and "solver.dt = 0.0005" in longer["how"]
    assert beaker_error.error_bars({}, cfg.chain, cfg.solver, cfg.beaker)["method"] is None
    # another drop: the shortfall was measured to differ (REFINED_BEAKER's docstring)
    taller = dataclasses.replace(cfg.beaker, drop=1.5)
    far = beaker_error.error_bars(figures, cfg.chain, cfg.solver, taller)
    assert far["method"] is None and "beaker.drop = 1.5 (refined at 1)" in far["how"]


def test_solver_accuracy_chooses_a_beaker_s_step_from_the_model() -> None:
    """``solver.accuracy`` on a beaker chooses the longest step (to three digits) whose
    every shortfall is within it (the top's, 0.19 per 250 us, is the largest), refuses an
    accuracy the smallest refined step (62.5 us, 4.99 %) does not reach with the best it
    reaches, and a chain unlike the refined one in one line naming the field."""
    from chainfountain.level.model import LevelError
    from chainfountain.study import with_changes

    lvl = shipped.level("beaker")
    for acc in (0.1, 0.06, 0.05):
        dt = with_changes(lvl, {"solver.accuracy": acc}).sim.solver.dt
        assert max(beaker_error.shortfalls(dt).values()) <= acc
        assert max(beaker_error.shortfalls(dt * 1.01).values()) > acc  # the longest
    with pytest.raises(LevelError, match=r"solver\.accuracy: 0\.04: the beaker's step model "
                       r"reaches 4\.99 % .*allowed: at least 0\.0499, or 0"):
        with_changes(lvl, {"solver.accuracy": 0.04})
    with pytest.raises(LevelError, match=r"solver\.accuracy: 0\.1 with chain\.link_length = "
                       r"0\.01 \(the beaker's step error was refined at 0\.02\)"):
        with_changes(lvl, {"solver.accuracy": 0.1, "chain.link_length": 0.01})
    with pytest.raises(LevelError, match=r"with beaker\.drop = 1\.5 \(the beaker's step "):
        with_changes(lvl, {"solver.accuracy": 0.1, "beaker.drop": 1.5})
