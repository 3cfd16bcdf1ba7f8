"""The apparatus level kind, variant 'open' (paper: no deceleration after landing).

What is asserted is what the simulation does (``docs/apparatus.md``, "Open
variant"). The turn after landing is a frictionless joint guide (slide joints to
the centre of the end channel's bend, then plate grooves), the tail slides away
horizontally. Over the first 0.8 s (the run later loses its catch, see the docs):

- the falling chain is caught and turned cleanly: the tension at the mouth is
  the weight of the chain hanging in the turn, ``Tbar_E = g*R*(1 - cos alphaE)/v**2``
  (+ the end pull, zero here): a steady chain along a frictionless path, the
  paper's Eq. for the tension along the fountain continued into the guide;
- the fountain carries ``Tbar_0 - Tbar_E = k*H``;
- the moving mass grows at ``lambda*v/2`` (the roller rolls up resting chain at
  ``v_R = v/2``; the tail grows at ``v``, the plate strand shrinks at ``v/2``),
  and the speed does not change: ``M(t) dv/dt = lambda g (y_up - y_lo) - T_exit(v)``
  vanishes at the selected speed, which depends on the drop and the cart only,
  so it is the floor preset's (same drop 0.35 m, same cart).
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus_report import report

LEVEL = Path(__file__).resolve().parents[1] / "levels" / "apparatus_floor.toml"
RUN = 2.2
FLOOR_SPEED = 2.929
"""Measured speed of ``apparatus_floor`` with the channel's walls (same chain, cart and
drop; docs/apparatus.md)."""


pytestmark = pytest.mark.xdist_group("apparatus_open")
"""The module-scoped run is computed once, on one worker (``--dist loadgroup``)."""


@pytest.fixture(scope="module")
def run():
    cfg = io.load(LEVEL).sim
    # xi2 raised so that the drop to the guide's exit equals the floor preset's drop to
    # its floor (0.35 m): same driving, same cart, same speed
    # (measured with the channel's walls and the 2.92 m/s start, as FLOOR_SPEED: the
    # floor preset now uses the joint guide, which runs 2 % faster, and starts at 2.98)
    a = dataclasses.replace(cfg.apparatus, variant="open", xi2=0.546, end_tension=0.144,
                            plate_links=0, upper_guide="walls", speed=2.92,
                            duration=2.6)
    sim = Simulation(dataclasses.replace(cfg, apparatus=a))
    rec = Recorder(sim, profiles=False)
    masses = []
    while sim.time < RUN - 1e-9:
        sim.advance(0.1)
        masses.append((sim.time, sim.apparatus.moving_mass(0.5)))
    return sim, rec, np.array(masses)


def test_open_guide_catches_the_chain(run) -> None:
    sim, _, _ = run
    app = sim.apparatus
    assert app.variant == "open" and app.guided and app.lower is None
    assert app._lo_n >= 25 and app.tail_mass > 0.05  # the tail slides away (lumped)


def test_open_end_tension_is_the_weight_in_the_turn(run) -> None:
    sim, rec, _ = run
    app = sim.apparatus
    rep = report(sim, rec, 0.1, RUN)
    m = rep["measured"]
    drop = app.guide_radius * (1.0 - math.cos(app.alphaE))
    expected = sim.config.gravity * drop / m["v"] ** 2
    # measured 0.151 against 0.146 (0.1-2.2 s)
    assert m["TE_bar"] == pytest.approx(expected, abs=0.04)


@pytest.mark.xfail(strict=True, reason="Tbar_0 - Tbar_E = 0.47 against k*H = 0.58 over "
                   "0.1-2.2 s (0.58 against 0.56 over 0.1-0.8 s; docs/apparatus.md)")
def test_open_fountain_carries_kH(run) -> None:
    sim, rec, _ = run
    m = report(sim, rec, 0.1, RUN)["measured"]
    assert m["T0_bar"] - m["TE_bar"] == pytest.approx(m["kH"], abs=0.06)


def test_open_moving_mass_grows_at_half_the_chain_speed(run) -> None:
    sim, rec, masses = run
    lam = sim.config.chain.linear_density
    v = float(np.mean([s.v for s in rec.apparatus_samples if s.t >= 0.1]))
    rate = float(np.polyfit(masses[:, 0], masses[:, 1], 1)[0])
    assert rate == pytest.approx(0.5 * lam * v, rel=0.05)


def test_open_speed_is_the_floor_presets(run) -> None:
    sim, rec, _ = run
    m = report(sim, rec, 0.1, RUN)["measured"]
    assert m["v"] == pytest.approx(FLOOR_SPEED, rel=0.02)  # measured 2.898 (-1.0 %)


@pytest.mark.xfail(strict=True, reason="speed drift -1.7 %/s (the momentum balance with the "
                   "measured exit tension predicts +2.2 %/s; docs/apparatus.md)")
def test_open_speed_steady(run) -> None:
    sim, rec, _ = run
    m = report(sim, rec, 0.1, RUN)["measured"]
    assert abs(m["speed_drift_per_s"]) <= 0.01
