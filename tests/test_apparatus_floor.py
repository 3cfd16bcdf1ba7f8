"""The apparatus level kind, variant 'floor' (paper: idealized beaker, real floor).

What is asserted is what the simulation does (``docs/apparatus.md``):

- the level loads, round-trips and builds; the chain starts at ``v0`` and the
  pick-up roller rolls at about half the chain speed (paper ``v/(1 + cos 0)``);
- the tension gained in the upper guide channel is the weight of the rise,
  ``Tbar_0 - Tbar_exit = xi2*k*H`` (frictionless channel, paper's
  ``Tbar_0 = p + Tbar_uc + xi2*k*H``), within the scatter of the readings;
- summary.json carries the measured and predicted quantities side by side;
- NOT reached yet (strict xfail): a steady fountain (speed drift <= 1 %/s).
  The pile on the floor pushes back (Tbar_E < 0) and the fountain slows down.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from chainfountain.headless import run_level
from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus import report

LEVEL = Path(__file__).resolve().parents[1] / "levels" / "apparatus_floor.toml"
RUN = 1.6


@pytest.fixture(scope="module")
def run():
    lvl = io.load(LEVEL)
    sim = Simulation(lvl.sim)
    rec = Recorder(sim, profiles=False)
    sim.advance(RUN)
    return lvl, sim, rec


def test_level_round_trips_and_is_apparatus() -> None:
    lvl = io.load(LEVEL)
    assert lvl.sim.kind == "apparatus" and lvl.sim.apparatus.variant == "floor"
    assert io.loads(io.dumps(lvl)) == lvl


def test_roller_rolls_at_half_the_chain_speed(run) -> None:
    lvl, sim, rec = run
    m = report(sim, rec, 0.4, RUN)["measured"]
    assert m["v"] == pytest.approx(lvl.sim.apparatus.speed, rel=0.15)
    # paper: v_R = v/(1 + cos alpha) = v/2; measured 0.52-0.57 while the chain slows
    assert 0.45 < m["roller_ratio_up"] < 0.6


def test_channel_adds_the_weight_of_the_rise(run) -> None:
    lvl, sim, rec = run
    m = report(sim, rec, 0.4, 1.2)["measured"]
    gain = m["T0_bar"] - m["T_pickup_exit_bar"]
    assert gain == pytest.approx(lvl.sim.apparatus.xi2 * m["kH"], abs=0.1)


@pytest.mark.xfail(strict=True, reason="the real floor pushes back in the sim: not steady "
                   "(docs/apparatus.md)")
def test_steady_speed(run) -> None:
    _, sim, rec = run
    r = report(sim, rec, 0.6, RUN)
    assert abs(r["measured"]["speed_drift_per_s"]) <= 0.01


def test_summary_has_measured_and_predicted(tmp_path) -> None:
    lvl = io.load(LEVEL)
    s = json.loads(run_level(lvl, tmp_path, 0.3, progress=False).read_text())
    a = s["apparatus"]
    for k in ("T0_bar", "TE_bar", "k", "xi2", "Tbar_uc", "pickup_p", "speed_drift_per_s"):
        assert k in a["measured"], k
    for part in ("predicted_paper", "predicted_measured_laws"):
        assert "T0_bar" in a[part] and "v_steady" in a[part]
    assert "vertex_y_through_ends" in a["catenary"]
    assert s["kind"] == "apparatus" and s["H"] == lvl.sim.apparatus.drop


def test_live_cart_mass_and_views() -> None:
    sim = Simulation(io.load(LEVEL).sim)
    sim.set_param("carts[0].mass", 0.01)
    assert sim.apparatus.upper.force == pytest.approx(0.01 * 9.81 * math.sin(math.radians(30)))
    assert len(sim.roller_geometry()) == 1 and sim.guide_geometry_segments()
    assert sim.floor_geometry()[3] == "solid" and len(sim.cart_geometry()) == 1
    with pytest.raises(KeyError):
        sim.set_param("carts[1].mass", 0.01)
