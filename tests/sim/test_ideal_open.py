"""The paper's open arrangement with ideal rollers (``feed.drive = "ideal_open"``): the
landed chain runs down a loss-free turn onto a frictionless plate and slides away, so the
moving mass grows while the machine selects
``v^2 = 2 g (H (1 - xi2) + d) - 2 F_uc/lambda`` and the plate's reaction grows at
``lambda g v`` (Fig. "pulley_experiment_equiv_ground", right).

Measured (``python -m research.ideal_open``, from the stub until the table is empty): the
speed 0.18 % below the laws' (0.15 % at half the step), the reaction's rate within 0.07 %
of ``lambda g v`` in every 2-s window; from the fountain (the runs here) the speed stays
within 0.05 % of the laws' for 12 s; and a 5 % push decays
as ``M(t) dv/dt = lambda (v_eq^2 - v^2)/2`` with the moving mass ``M`` growing by the
landed chain (without it the push is gone within a second).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from chainfountain.level import io
from chainfountain.level.io import LevelError
from chainfountain.sim import Recorder, Simulation, placement
from chainfountain.sim.slide_away_report import report
from chainfountain.theory.apparatus import ideal_open_speed
from tests import shipped


def _level():
    lvl = shipped.level("ideal_open")
    lvl.sim.initial.mode, lvl.sim.feed.starter = "catenary", 0.0  # from the fountain on
    return lvl


def test_the_selected_speed_meets_both_halves() -> None:
    """At the selected speed the upper half's ``Tbar_0 = 1/2 + Tbar_uc + xi2 k H`` is the
    fountain's ``Tbar_E + k H`` with the turn's ``Tbar_E = k d``."""
    H, xi2, F, d, lam, g = 1.0, 0.3, 0.02, 0.1, 0.05, 9.81
    v = ideal_open_speed(H, xi2, F, d, lam, g)
    k = g / v**2
    assert 0.5 + F / (lam * v * v) + xi2 * k * H == pytest.approx(k * d + k * H, rel=1e-12)
    assert math.isnan(ideal_open_speed(H, xi2, 10.0, d, lam, g))  # the cart holds it


@pytest.mark.slow
def test_the_plate_reaction_grows_at_lambda_g_v_while_the_speed_holds() -> None:
    """12 s from the fountain: the speed stays within 0.5 % of the laws' (measured +0.03 %),
    the landed chain moves with the machine, and the plate's reaction grows at ``lambda g
    v`` within 0.5 % in every 2-s window (measured 0.07 %). The reaction is counted from
    the links the floor takes, so its rate checks the bookkeeping (the chain lands at the
    speed it runs), not the machine's physics: the speed and the push test do that."""
    lvl = _level()
    sim = Simulation(lvl.sim)
    rec = Recorder(sim, profiles=False)
    sim.advance(12.0)
    lam, g = lvl.sim.chain.linear_density, lvl.sim.gravity
    f = lvl.sim.feed
    v_law = ideal_open_speed(f.drop, f.xi2, f.cart_force, f.turn_drop, lam, g)
    o = report(rec.samples, sim.piston.hand_over, lam, g, v_law)
    assert o is not None and len(o["chunks"]) == 5  # 0-10 s; the last 2 s are not whole
    assert o["worst_chunk_rel"] < 0.005, o["chunks"]
    v = rec.series("speed_mean")[rec.series("t") >= 2.0]
    assert abs(np.mean(v) / v_law - 1.0) < 0.005
    tail = sim.slide_away
    assert tail.links == sim.feed.absorbed > 12.0 * v_law / lvl.sim.chain.link_length * 0.9
    assert sim.piston.carried == pytest.approx(tail.mass)
    share = (f.machine_mass + tail.mass) / sim.piston.n_nominal
    for link in sim.piston.held_links():
        assert link.body.mass == pytest.approx(sim.chain.mass + share)
    assert o["moving_mass_kg"] == pytest.approx(tail.mass, rel=0.01)
    # the picture of the parts the laws stand for: from the chain's end down the turn
    path, slid = placement.slide(sim)
    assert path[0, 0] == pytest.approx(sim.chain.links[0].body.position.x)
    assert path[0, 1] == pytest.approx(sim.feed.floor_y)
    assert path[-1, 1] == pytest.approx(sim.feed.floor_y - f.turn_drop)
    assert slid == pytest.approx(tail.links * lvl.sim.chain.link_length)


@pytest.mark.slow
def test_a_push_decays_as_slowly_as_the_moving_mass_says() -> None:
    """Pushed 5 % at 6 s (1.3 kg moving), the machine returns to its speed as ``M(t) dv/dt
    = lambda (v_eq^2 - v^2)/2`` with ``M`` growing at ``lambda v``: about 30 % of the push
    is gone 3 s later. Measured 0.664 of it left against the law's 0.707 (the same under
    ``--perturb``); ``v_eq`` is read before the push while the speed still settles by a few
    0.1 % towards the machine's own, which moves the ratio by about 0.02-0.04, so the bound
    is 0.06. Without the landed chain's mass 0.03 is left."""
    lvl = _level()
    sim = Simulation(lvl.sim)
    lam = lvl.sim.chain.linear_density
    speeds = []
    while sim.time < 6.0 - 1e-9:
        sim.step()
        if sim.time >= 5.0:
            speeds.append(sim.piston.speed)
    v_eq = float(np.mean(speeds))
    sim.set_feed_speed(1.05 * v_eq)

    def mean_speed(seconds: float) -> float:
        out = []
        end = sim.time + seconds
        while sim.time < end - 1e-9:
            sim.step()
            out.append(sim.piston.speed)
        return float(np.mean(out))

    mean_speed(0.4)
    v0, t0 = mean_speed(0.2), sim.time - 0.1
    M0 = lvl.sim.feed.machine_mass + sim.piston.carried + sim.chain.mass * len(sim.chain.links)
    mean_speed(2.8)
    v1, t1 = mean_speed(0.2), sim.time - 0.1
    # the law, integrated from t0 with the moving mass growing at lambda v
    v, t, M, h = v0, t0, M0, 1e-3
    while t < t1 - 1e-12:
        v += h * 0.5 * lam * (v_eq**2 - v**2) / M
        M += h * lam * v
        t += h
    left, predicted = (v1 - v_eq) / (v0 - v_eq), (v - v_eq) / (v0 - v_eq)
    assert v0 > 1.03 * v_eq  # the push took
    assert left == pytest.approx(predicted, abs=0.06), (left, predicted)


def test_the_run_ends_in_one_sentence_when_the_table_is_empty() -> None:
    """A finite table (``feed.chain_length``) ends the run when it is all picked up: about
    the table's extra metres over the speed after the start."""
    from chainfountain.errors import RunEnded
    from chainfountain.sim.kinds.ideal.checks import TABLE_MARGIN

    lvl = _level()
    sim = Simulation(lvl.sim)
    start = len(sim.chain.links) * lvl.sim.chain.link_length  # the fountain and the guide
    lvl.sim.feed.chain_length = start + TABLE_MARGIN + 0.2
    io.loads(io.dumps(lvl), "ideal_open (short table)")  # the check accepts it
    sim = Simulation(lvl.sim)
    with pytest.raises(RunEnded) as ended:
        sim.advance(5.0)
    assert "the upper table is empty" in str(ended.value)
    assert "feed.chain_length" in str(ended.value)
    assert sim.time == pytest.approx((TABLE_MARGIN + 0.2) / lvl.sim.feed.speed, abs=0.02)


@pytest.mark.parametrize(("changes", "field", "words"), [
    ({"xi2": 0.7}, "feed.xi2", ["too slow for a fountain", "allowed: xi2 <"]),
    ({"cart_force": 0.5}, "feed.cart_force", ["too slow for a fountain",
                                              "allowed: feed.cart_force <"]),
    ({"chain_length": 1.0}, "feed.chain_length", ["upper table", "allowed: 0"]),
    ({"end_tension": 0.1}, "feed.end_tension", ["the turn onto the plate sets the pull"]),
    ({"drive": "ideal_floor"}, "feed.turn_drop", ["has no effect with feed.drive"]),
])
def test_settings_without_an_open_fountain_are_refused(level, changes, field, words) -> None:
    """A setting that leaves no fountain, or a field the drive ignores, is refused in one
    message naming the field."""
    lvl = level("ideal_open")
    for name, value in changes.items():
        setattr(lvl.sim.feed, name, value)
    with pytest.raises(LevelError) as err:
        io.loads(io.dumps(lvl), "ideal_open (changed)")
    msg = str(err.value)
    assert field in msg and all(w in msg for w in words), msg
