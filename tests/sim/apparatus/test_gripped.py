"""The gripped folding roller (``apparatus.fold_roller = "gripped"``,
:mod:`chainfountain.sim.apparatus.grip`): chain joints welded to the roller as they reach
it and pinned to the table where they come down, no friction and no contact.

Asserted on ``apparatus_fold`` with a 100-mm gripped folding roller (five link lengths,
where its rig is converged in the step: ``research/joint_putdown_weld.py``), carts 19 g
and 2 g (the contact roller's 41 g lower cart pushed this loss-free one faster and
faster), laid on its path at 3 m/s, real tables (no treadmill), 2 s:

- the chain is laid at rest (each joint as it is pinned), the roller rolls at half the
  chain speed and about half its circle carries welded links;
- the arriving strand pulls as the loss-free law with gravity says,
  ``Tbar = 1/4 + Tbar_lc/2 + k R`` (the chain descends ``2R`` through the roller):
  0.367-0.369 against 0.372 from nudged starts (-1.0 %; asserted within 0.01);
- the joints are pinned to the table at rest: at most 0.028 m/s at 0.5 ms and 0.014 m/s
  at 0.25 ms (a joint is pinned up to one bookkeeping step after its lowest point);
- at half the pymunk step (0.25 ms) the machine still runs, at 3.019 m/s against 3.005
  (+0.5 %), where the contact fold collapses within 0.65-2.1 s ("The fold depends on the
  time step");
- the tensions are converged in the step: the strand's pull, ``Tbar_E`` and ``Tbar_0``
  differ by at most 0.006 between 0.5 and 0.25 ms (asserted within 0.02), and
  ``Tbar_0 - Tbar_E = k H`` at both. They are
  read from the joint forces' components (:func:`chainfountain.sim.fastbody.pivot_impulse`)
  every 2 ms: the joint forces ring at the laying rate, 75 Hz, and their sizes read
  0.46 at 0.25 ms against 0.38.

docs/apparatus.md, "The gripped folding roller".
"""

from __future__ import annotations

import math

import pytest

from chainfountain.errors import RunEnded
from chainfountain.level import io
from chainfountain.level.model import LevelError
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus import gripped_putdown
from chainfountain.sim.apparatus_report import report
from chainfountain.study.changes import laid_on_path, with_changes
from tests import shipped

LEVEL = shipped.path("apparatus_fold")
GRIPPED = {"apparatus.fold_roller": "gripped", "apparatus.fold_roller_radius": 0.1,
           "carts[0].mass": 0.019, "carts[1].mass": 0.002, "apparatus.plate_links": 0}
SAMPLE = 0.002
"""Sampled every 2 ms: the joint forces at the folding roller ring at the laying rate
``v/(2L)`` (75 Hz) and its harmonics, which the presets' 10-ms samples alias."""
pytestmark = pytest.mark.xdist_group("apparatus_gripped")


def _run(dt: float) -> tuple[Simulation, dict]:
    """``apparatus_fold`` gripped, laid on its path, 2 s at ``solver.dt = dt`` (2 pymunk
    steps each); the report over 0.5-2 s."""
    level = laid_on_path(with_changes(io.load(LEVEL), {**GRIPPED, "solver.dt": dt,
                                                       "recording.sample_interval": SAMPLE}))
    sim = Simulation(level.sim)
    rec = Recorder(sim, profiles=False)
    sim.advance(2.0)
    return sim, report(sim, rec, 0.5, 2.0)


@pytest.fixture(scope="module")
def step() -> tuple[Simulation, dict]:
    return _run(1e-3)


@pytest.fixture(scope="module")
def half_step() -> tuple[Simulation, dict]:
    return _run(5e-4)


def test_the_gripped_roller_lays_the_chain_down_at_rest(step) -> None:
    sim, rep = step
    app, m = sim.apparatus, rep["measured"]
    assert app.landing_speed < 0.02 * m["v"], "a joint was pinned moving"
    assert m["roller_ratio_lo"] == pytest.approx(0.5, abs=0.005)
    half_turn = math.pi * app.R_lo / app.L  # links on half the circle
    assert abs(app.n_welded - half_turn) <= 2.0
    assert app.gripped_links > 0.9 * (m["v"] / 2.0) * 2.0 / app.L


def test_the_arriving_strand_pulls_as_the_loss_free_law_says(step) -> None:
    sim, rep = step
    m = rep["measured"]
    # measured 0.3674-0.3688 against 0.3716 (three nudged starts)
    law = gripped_putdown(m["Tbar_lc"], m["k"], sim.apparatus.R_lo)
    assert m["T_putdown_entry_bar"] == pytest.approx(law, abs=0.01)


@pytest.mark.slow
def test_the_gripped_fold_runs_at_half_the_step(half_step) -> None:
    sim, rep = half_step
    m = rep["measured"]
    assert m["roller_ratio_lo"] == pytest.approx(0.5, abs=0.005)
    assert sim.apparatus.landing_speed < 0.02 * m["v"]


@pytest.mark.slow
def test_the_speed_is_the_same_at_half_the_step(step, half_step) -> None:
    """The issue's convergence target, within 1 % (measured +0.5 %)."""
    a, b = step[1]["measured"], half_step[1]["measured"]
    assert b["v"] == pytest.approx(a["v"], rel=0.01)


@pytest.mark.slow
@pytest.mark.parametrize("key", ["T_putdown_entry_bar", "TE_bar", "T0_bar"])
def test_the_tensions_are_converged_in_the_step(step, half_step, key) -> None:
    """Measured at 0.5 / 0.25 ms (three nudged starts): entry 0.367-0.369 / 0.364-0.366,
    ``Tbar_E`` 0.186-0.187 / 0.187-0.189, ``Tbar_0`` 0.722-0.723 / 0.725-0.728."""
    a, b = step[1]["measured"], half_step[1]["measured"]
    assert b[key] == pytest.approx(a[key], abs=0.02)


@pytest.mark.parametrize("which", ["step", pytest.param("half_step", marks=pytest.mark.slow)])
def test_the_fountain_takes_k_h_of_the_pull(which, request) -> None:
    """``Tbar_0 - Tbar_E = k H`` across the free fountain: 0.536 against 0.543 at 0.5 ms,
    0.538 against 0.538 at 0.25 ms."""
    m = request.getfixturevalue(which)[1]["measured"]
    assert m["T0_bar"] - m["TE_bar"] == pytest.approx(m["kH"], abs=0.02)


@pytest.mark.parametrize(("changes", "field"), [
    ({"apparatus.fold_roller": "gripped", "apparatus.fold_roller_radius": 0.005},
     "apparatus.fold_roller_radius"),
    ({"apparatus.fold_roller_radius": 0.003}, "apparatus.fold_roller_radius"),
    ({"apparatus.fold_roller": "gripped", "apparatus.fold_clearance": 0.002},
     "apparatus.fold_clearance"),
    ({"apparatus.fold_roller": "gripped", "apparatus.plate": "contact",
      "apparatus.upper_guide": "walls", "apparatus.plate_links": 0},
     "apparatus.fold_roller"),
])
def test_a_gripped_roller_that_cannot_work_is_refused_in_one_line(changes, field) -> None:
    with pytest.raises(LevelError) as err:
        with_changes(io.load(LEVEL), changes)
    msg = str(err.value)
    assert field in msg and "allowed" in msg and "\n" not in msg


def test_the_new_fields_are_off_by_default() -> None:
    """A fold level without them builds the contact roller: nothing welded, the folding
    roller as big as the pick-up."""
    level = io.load(LEVEL)
    assert level.sim.apparatus.fold_roller == "contact"
    assert level.sim.apparatus.fold_roller_radius == 0.0
    sim = Simulation(laid_on_path(level).sim)
    sim.advance(0.2)
    app = sim.apparatus
    assert app.n_welded == 0 and app.lower.radius == app.upper.radius == 0.03


@pytest.mark.slow
def test_a_gripped_fold_run_too_fast_says_to_lighten_the_lower_cart() -> None:
    """The contact roller's 41 g lower cart runs the loss-free gripped fold ever faster
    (3.0 -> 3.8 m/s in 1.5 s) until its fountain falls past the catch, at about 3 s; the
    message says what to change, in one sentence."""
    changes = {**GRIPPED, "carts[1].mass": 0.041, "carts[0].mass": 0.0175}
    sim = Simulation(laid_on_path(with_changes(io.load(LEVEL), changes)).sim)
    with pytest.raises(RunEnded) as err:
        sim.advance(10.0)
    plain = err.value.plain
    assert "lighter lower cart" in plain and "\n" not in plain
