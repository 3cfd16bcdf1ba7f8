"""Discretisation error by refinement: ``chainfountain converge`` and ``run --error-bars``."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from chainfountain.errors import UserError
from chainfountain.level import io
from chainfountain.refine import FIGURES, refine, refined_config
from tests import shipped


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "chainfountain", *args],
                          capture_output=True, text=True, timeout=600)


@pytest.fixture(scope="module")
def wide_low():
    return refine(shipped.level("wide_low").sim, "wide_low")


def test_refined_config_halves_link_and_step_and_starts_on_the_catenary(level) -> None:
    cfg = level("classroom").sim
    fine = refined_config(cfg, 2)
    assert fine.chain.link_length == cfg.chain.link_length / 2
    assert fine.solver.dt == cfg.solver.dt / 2
    assert fine.initial.mode == "catenary"
    assert cfg.chain.link_length == 0.05  # the level itself is untouched
    # twice the links at half the step: the iterations the solver needs to converge
    # (chainfountain.sim.accuracy.iterations_needed: 17 for classroom's 330 links at 125 us)
    assert fine.solver.iterations == 17 > cfg.solver.iterations
    assert fine.solver.accuracy == 0.0  # the refined run keeps its settings


@pytest.mark.slow
def test_halving_link_and_step_brings_the_fountain_closer_to_the_paper(wide_low) -> None:
    """The fountain converges on the paper's catenary: wide_low's vertex is +0.24 % high at
    20 mm and 250 us and +0.12 % at 10 mm and 125 us (`chainfountain converge wide_low`),
    so the first-order extrapolation lands on the paper (measured +0.00 %)."""
    coarse, fine = (r.errors for r in wide_low.runs)
    assert abs(fine["h"]) < abs(coarse["h"])
    stat = wide_low.statistical_error()
    est = wide_low.discretisation_error()
    # the estimate resolves the height's error: larger than its own statistical error
    assert abs(est["h"]) > 2 * stat["h"], (est, stat)
    # ... and it is the coarse run's own error: extrapolated to zero link length and step
    # the fountain is the paper's, within a quarter of the coarse error
    assert abs(wide_low.extrapolated()["h"]) < 0.25 * abs(coarse["h"])


def test_converge_on_an_apparatus_level_is_refused_in_one_line() -> None:
    r = _cli("converge", "apparatus_floor")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert "kind = 'apparatus'" in r.stderr and len(r.stderr.strip().splitlines()) == 1


def test_converge_below_the_smallest_link_is_refused(level) -> None:
    """fountain_d has 4-mm links: a fourth run (L/8 = 0.5 mm) is below the schema's 1 mm;
    refused before anything runs, in one line naming the option, the field and the limit."""
    lvl = level("fountain_d")
    with pytest.raises(UserError, match="chain.link_length"):
        refine(lvl.sim, "fountain_d", refinements=4)
    r = _cli("converge", "fountain_d", "--refinements", "4")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    for words in ("--refinements 4", "chain.link_length", "0.0005 m", "at most 3"):
        assert words in r.stderr, (words, r.stderr)
    r = _cli("converge", "fountain_d", "--refinements", "9")
    assert r.returncode == 2 and "--refinements" in r.stderr


def test_run_error_bars_only_on_fed_levels_and_contact_machines() -> None:
    """A beaker has a step model of its own and no refinement: refused in one line, which
    names the kinds that have one (a contact machine: tests/sim/apparatus/
    test_step_refine.py)."""
    r = _cli("run", "beaker", "--error-bars", "--duration", "0.1")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    for words in ("--error-bars", "kind = 'beaker'", "kind 'apparatus'", "half its step"):
        assert words in r.stderr, (words, r.stderr)


@pytest.mark.slow
def test_run_with_error_bars_writes_them_next_to_the_figures(level, tmp_path) -> None:
    lvl = level("wide_low")
    lvl.sim.solver.dt = 1e-3  # a coarse, cheap run: the estimate is about the settings
    lvl.sim.solver.accuracy = 0.0  # (else the loader chooses the step again)
    path = io.save(lvl, tmp_path / "coarse.toml")
    r = _cli("run", str(path), "--error-bars", "--duration", "0.5", "--quiet",
             "--out", str(tmp_path / "o"))
    assert r.returncode == 0, r.stderr
    s = json.loads((tmp_path / "o" / "summary.json").read_text())
    bars = s["error_bars"]
    assert bars["method"].startswith("refinement: the level at (L, dt), (L/2, dt/2)")
    assert set(bars["discretisation_error"]) == set(FIGURES)
    coarse, fine = (run["errors"] for run in bars["runs"])
    for f in FIGURES:  # the first-order estimate of the coarse run's error
        assert bars["discretisation_error"][f] == pytest.approx(2 * (coarse[f] - fine[f]))
    assert [run["dt"] for run in bars["runs"]] == [1e-3, 5e-4]
    assert "discretisation error bars" in r.stdout


def test_refinement_starts_an_ideal_machine_at_the_speed_it_selects(level):
    """A machine is refined from its own fountain: ``ideal_fold`` starts at 4.7 m/s but
    selects 5.0 m/s, and its refined runs start there."""
    from chainfountain.refine import refined_config

    cfg = level("ideal_fold").sim
    for factor in (1, 2):
        out = refined_config(cfg, factor, "ideal_fold")
        assert out.feed.speed == pytest.approx(5.0)
        assert out.initial.mode == "catenary"
    assert cfg.feed.speed == 4.7  # the level itself is left as it is
