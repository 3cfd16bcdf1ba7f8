"""The error model of fed fountains (:mod:`chainfountain.sim.accuracy`) and
``solver.accuracy``: settings chosen for an accuracy, and runs at them inside the bounds.

The model's promise is checked on runs from the catenary (settled 1.5 s, averaged 3 s, as
the model was fitted): a fountain run at the settings chosen for an accuracy lands within
the model's bound for vertex height, vertex x and landing. The window mean's statistical
error on these runs is 0.01-0.04 % (four block means), far below the bounds' margins
(0.15-0.34 %), so the assertions do not flip with run-to-run scatter.
"""

from __future__ import annotations

import dataclasses
import math

import pytest

from chainfountain.level import io
from chainfountain.level.model import LevelError
from chainfountain.refine import measure
from chainfountain.sim import accuracy
from chainfountain.sim.reference import LaunchReference
from tests import shipped

WIDE_LOW = LaunchReference.from_launch(4.0, math.radians(60.0), 0.5)
PULL = LaunchReference.from_launch(5.0, math.radians(75.0), 1.0, TE_bar=0.15)
D = LaunchReference.from_launch(math.sqrt(9.81 / 0.377), math.radians(82.0), 2.0,
                                TE_bar=0.123)


def test_iterations_grow_with_links_and_shrink_with_the_step():
    assert accuracy.iterations_needed(100, 2.5e-4) == accuracy.MIN_ITERATIONS
    assert accuracy.iterations_needed(170, 2.5e-4) == 10
    assert accuracy.iterations_needed(340, 2.5e-4) == 40  # links squared
    assert accuracy.iterations_needed(340, 6.25e-5) < accuracy.iterations_needed(340, 1.25e-4)


@pytest.mark.parametrize("ref", [WIDE_LOW, PULL], ids=["wide_low", "pull"])
@pytest.mark.parametrize("acc", [0.01, 0.005])
def test_choose_is_the_cheapest_candidate_within_the_accuracy(ref, acc):
    est = accuracy.choose(ref, acc)
    assert est.converged and est.worst <= acc
    ok = [e for e in accuracy.candidates(ref) if e.worst <= acc]
    assert est.cost == min(e.cost for e in ok)
    # a tighter accuracy never costs less
    assert accuracy.choose(ref, 0.004).cost >= est.cost


def test_out_of_reach_says_the_best_bound():
    with pytest.raises(accuracy.OutOfReach, match=r"best: 0\.\d\d%") as exc:
        accuracy.choose(WIDE_LOW, 0.001)
    assert 0.001 < exc.value.best < 0.005


def test_near_critical_fountain_is_outside_the_model():
    assert accuracy.in_domain(D) is not None
    with pytest.raises(accuracy.OutOfReach, match="near-critical"):
        accuracy.choose(D, 0.01)


def test_unconverged_solver_has_no_bound():
    # the classroom fountain at 2-cm links needs 59 iterations at 250 us
    ref = LaunchReference.from_launch(7.5, math.radians(70.0), 3.0)
    est = accuracy.estimate(ref, accuracy.Settings(0.02, 2.5e-4, 10))
    assert not est.converged and est.worst == math.inf


def _level_text(name: str, solver_extra: str) -> str:
    text = shipped.path(name).read_text()
    return text.replace("[solver]\n", f"[solver]\n{solver_extra}\n", 1)


def test_level_accuracy_sets_link_length_step_and_iterations():
    text = _level_text("wide_low", "").replace("accuracy = 0.005", "accuracy = 0.01")
    level = io.loads(text)
    want = accuracy.choose(WIDE_LOW, 0.01).settings
    assert (level.sim.chain.link_length, level.sim.solver.dt,
            level.sim.solver.iterations) == (want.link_length, want.dt, want.iterations)


def test_an_ideal_machines_accuracy_is_chosen_for_the_fountain_its_laws_select():
    """An ideal machine's flight is a fed fountain at the speed it runs
    (tests/sim/test_ideal_fold.py); ``solver.accuracy`` chooses for the laws' fountain."""
    level = io.loads(_level_text("ideal_fold", "accuracy = 0.01"))
    ref = LaunchReference.of_level(shipped.level("ideal_fold").sim)
    assert ref.v == pytest.approx(5.0)
    want = accuracy.choose(ref, 0.01, machine=True).settings
    assert (level.sim.chain.link_length, level.sim.solver.dt,
            level.sim.solver.iterations) == (want.link_length, want.dt, want.iterations)
    # a machine's flight carries the margins measured on the ideal presets besides
    s = accuracy.Settings(0.02, 2.5e-4, 10)
    fed, flight = accuracy.estimate(ref, s), accuracy.estimate(ref, s, machine=True)
    assert flight.bounds["vertex_y"] == pytest.approx(
        fed.bounds["vertex_y"] + accuracy.IDEAL_STEP["vertex_y"])
    assert flight.bounds["vertex_x"] == pytest.approx(
        fed.bounds["vertex_x"] + accuracy.IDEAL_MARGIN["vertex_x"])


@pytest.mark.parametrize("text, field, words", [
    (lambda: _level_text("wide_low", "").replace("accuracy = 0.005", "accuracy = 0.001"),
     "solver.accuracy", "at least 0.00"),
    (lambda: _level_text("apparatus_special", "accuracy = 0.01"), "solver.accuracy",
     "kind = 'apparatus'"),
    (lambda: _level_text("fountain_d", "accuracy = 0.01"), "solver.accuracy", "near-critical"),
], ids=["too_tight", "apparatus", "near_critical"])
def test_level_accuracy_refusals_name_the_field(text, field, words):
    with pytest.raises(LevelError) as exc:
        io.loads(text())
    msg = str(exc.value)
    assert field in msg and words in msg and "allowed" in msg


@pytest.mark.slow
@pytest.mark.parametrize("ref, acc", [
    (WIDE_LOW, 0.005),
    (PULL, 0.005),
    (LaunchReference.from_launch(7.5, math.radians(70.0), 3.0), 0.005),
], ids=["wide_low_0.5%", "floor_pull_0.5%", "classroom_0.5%"])
def test_run_at_chosen_settings_is_within_the_bounds(ref, acc):
    est = accuracy.choose(ref, acc)
    run = measure(accuracy.catenary_config(ref, est.settings), settle=1.5, window=3.0)
    got = {"vertex_y": run.errors["h"], "vertex_x": run.errors["vertex_x"],
           "landing_x": run.errors["l"]}
    for f in accuracy.FIGURES:
        assert abs(got[f]) <= est.bounds[f], (f, got[f], est.bounds[f])
    assert run.spread <= 0.002  # the converged solver's link-speed spread (issue 35)


USER_PULL = """schema_version = 1
kind = "feed"

[meta]
name = "user_pull"
title = "a fed fountain with a floor pull, written without a [solver] table"

[feed]
speed = 4.6
launch_angle = 1.2
drop = 1.2
end_tension = 0.15

[initial]
mode = "catenary"
"""


@pytest.mark.slow
def test_a_level_without_solver_settings_lies_within_the_bounds_it_is_given():
    """A user's fed fountain with a floor pull, unlike the shipped ones and with no
    ``[solver]`` table, runs at the motor-fed default accuracy (1 %: 1.5-cm links, 250 us,
    10 iterations); the bounds ``summary.json`` and ``run`` give it (the model at those
    settings, within the 1 %) hold, settled 1.5 s and averaged 3 s as the model was
    fitted."""
    from chainfountain.sim.kinds.feed import DEFAULT_ACCURACY

    level = io.loads(USER_PULL)
    sim = level.sim
    assert sim.solver.accuracy == DEFAULT_ACCURACY
    ref = LaunchReference.of_level(sim)
    est = accuracy.estimate(ref, accuracy.Settings(sim.chain.link_length, sim.solver.dt,
                                                   sim.solver.iterations), sim.chain)
    assert est.converged and est.worst <= DEFAULT_ACCURACY
    run = measure(sim, settle=1.5, window=3.0)
    got = {"vertex_y": run.errors["h"], "vertex_x": run.errors["vertex_x"],
           "landing_x": run.errors["l"]}
    for f in accuracy.FIGURES:
        assert abs(got[f]) <= est.bounds[f], (f, got[f], est.bounds[f])


def test_a_fed_file_without_settings_gets_its_kind_s_default_accuracy_where_it_applies():
    """No settings in the file: the motor-fed default (1 %) chooses them and the run says
    so; a file that sets one of them, a solid floor, a link radius too thick for the
    chosen links or a near-critical fountain keeps the schema's settings (and the reason
    is printed by run); the level round-trips exactly."""
    from chainfountain.headless.section_text import error_model_lines
    from chainfountain.headless.summary import model_error
    from chainfountain.sim.config import SimConfig
    from chainfountain.sim.kinds.feed import DEFAULT_ACCURACY

    plain = io.loads(USER_PULL)
    assert plain.sim.solver.accuracy == DEFAULT_ACCURACY
    assert io.dumps(io.loads(io.dumps(plain))) == io.dumps(plain)
    schema = SimConfig().solver
    kept = {
        "a step": USER_PULL.replace("[initial]", "[solver]\ndt = 0.00025\n\n[initial]"),
        "a solid floor": USER_PULL.replace("end_tension = 0.15", "floor = \"solid\""),
        "a thick link": USER_PULL.replace("[initial]", "[chain]\nlink_radius = 0.008\n\n"
                                          "[initial]"),
    }
    for why, text in kept.items():
        sim = io.loads(text).sim
        assert sim.solver.accuracy == 0.0, why
        assert (sim.solver.dt, sim.solver.iterations) == (schema.dt, schema.iterations), why
    m = model_error(plain)
    assert m["accuracy"] == DEFAULT_ACCURACY
    lines = error_model_lines(m, type("S", (), {"link_length": 0.015, "dt": 2.5e-4})())
    assert "solver.accuracy = 1 % chose (15-mm links, 250-us step)" in lines[0]
    solid = model_error(io.loads(kept["a solid floor"]))
    assert solid["bounds"] is None and "feed.floor = 'solid'" in solid["why_none"]
    assert error_model_lines(solid, None)[0].startswith(
        "  discretisation error: no error model here: feed.floor = 'solid'")


def test_an_ideal_machine_s_links_are_chosen_no_longer_than_measured():
    """The ideal machines' margins were measured at 2-cm links: no coarser links are
    chosen for them (a motor-fed fountain of the same flight gets 4-5 cm at 3 %)."""
    lvl = shipped.level("ideal_special")
    ref = LaunchReference.of_level(lvl.sim)
    machine = [e.settings.link_length for e in accuracy.candidates(ref, lvl.sim.chain, True)]
    motor = [e.settings.link_length for e in accuracy.candidates(ref, lvl.sim.chain)]
    assert max(machine) == accuracy.MACHINE_MAX_LINK < max(motor)
    assert accuracy.choose(ref, 0.03, lvl.sim.chain, machine=True).settings.link_length <= 0.02
    coarse = dataclasses.replace(lvl.sim.chain, link_length=0.03)
    assert accuracy.in_domain(ref, coarse) is None
    assert "measured at links up to 0.02 m" in accuracy.in_domain(ref, coarse, machine=True)
