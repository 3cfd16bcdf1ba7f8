"""Unbalanced upper cart: the chain decelerates (issue 4, step 2; ``docs/apparatus.md``,
"Unbalanced carts").

``levels/apparatus_floor.toml`` (without its treadmill, ``plate_links = 0``) runs near
its selected speed; at ``t = 1 s`` the upper cart is made heavier live (9 g -> 60 g,
``Delta F_uc = 0.25 N``) and the chain's speed (the rigid strand in the plate grooves)
is compared with an unswitched run over the next 0.6 s.

What the runs show (twenty-first session):

- The chain in flight does not take part. The tension at the fountain start (pivot
  impulses of the 4 joints there) rises by only 0.005 N, against 0.117 N at the pick-up's
  exit, and the strand between the two, ``M_up`` = 0.44 -> 0.39 kg of moving links,
  obeys ``M_up * Delta a = Delta T_launch - Delta T_exit`` (an effective mass of 0.407 kg
  against the counted 0.415, 2 %).
- The pick-up passes the step on as an ideal rolling pulley does: the exit tension rises
  by 0.53 of ``Delta F`` once the roller unit's inertia and the pick-up's own speed
  dependence are taken out (energy balance: 1/2; the rig's steady gain
  :data:`~chainfountain.sim.apparatus.CART_GAIN_2CM`: 0.68).

So the prediction is the energy balance of the strand and roller unit
(:func:`chainfountain.theory.apparatus.cart_step_speed` with ``gain = 1/2``, the mass of
:func:`~chainfountain.theory.apparatus.referred_mass` and the rig's ``d(p lambda v^2)/dv``
as ``drag``): measured/predicted 1.017 over the 0.6-s window (0.3 s: 1.09, the first 0.2 s
carry axial waves along the 8-m strand; 1.0 s: 0.99). The rig's gain instead gives 0.75.
Until the twenty-first session the prediction counted the chain in flight as moving
mass and used the rig's gain; its two errors nearly cancelled (0.87).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from chainfountain.level import io
from chainfountain.sim import Simulation
from chainfountain.sim.apparatus import CART_GAIN_2CM, PICKUP_RIG_2CM, pickup_rig_2cm
from chainfountain.theory.apparatus import cart_step_speed, referred_mass

LEVEL = Path(__file__).resolve().parents[1] / "levels" / "apparatus_floor.toml"
T_SWITCH, WINDOW, HEAVY = 1.0, 0.6, 0.06
EVERY = 2
"""Read the tensions every 2 steps (1 ms)."""

pytestmark = pytest.mark.xdist_group("apparatus_carts")
"""The module-scoped runs are computed once, on one worker (``--dist loadgroup``)."""


def _upstream_mass(sim: Simulation) -> float:
    """Mass of the moving links upstream of the fountain start (the origin), kg."""
    st = sim.state()
    i0 = int(np.argmin(np.hypot(st.position[:, 0], st.position[:, 1])))
    speed = np.hypot(st.velocity[i0 + 1:, 0], st.velocity[i0 + 1:, 1])
    return float(np.count_nonzero(speed > 1.0)) * sim.chain.mass


def _run(mass: float | None) -> dict:
    """The floor preset on its long strand to ``T_SWITCH``, the cart set to ``mass`` (or
    left), then ``WINDOW`` s: strand speed, pick-up exit tension (pivots of the grooved
    links 2-5 from the roller) and launch tension (pivots of the 4 joints nearest the
    fountain start), all in N."""
    cfg = io.load(LEVEL).sim
    cfg = dataclasses.replace(cfg, apparatus=dataclasses.replace(cfg.apparatus, plate_links=0))
    sim = Simulation(cfg)
    app = sim.apparatus
    sim.advance(T_SWITCH)
    F0, m_up0 = app.upper.force, _upstream_mass(sim)
    if mass is not None:
        sim.set_param("carts[0].mass", mass)
    dt, links = sim.dt, sim.chain.links
    t, v, T_exit, T_launch = [], [], [], []
    for k in range(int(round(WINDOW / dt))):
        sim.step()
        if (k + 1) % EVERY:
            continue
        g = app._grooves  # upstream end (newest, at the roller) last
        pos = sim.state().position
        i0 = int(np.argmin(np.hypot(pos[:, 0], pos[:, 1])))
        t.append(sim.time)
        v.append(app.strand_speed)
        T_exit.append(np.mean([abs(g[-i][0].up_joint.impulse) for i in range(3, 7)]) / dt)
        T_launch.append(np.mean([abs(links[i].up_joint.impulse) for i in range(i0 - 3, i0 + 1)])
                        / dt)
    return {"t": np.array(t), "v": np.array(v), "T_exit": np.array(T_exit),
            "T_launch": np.array(T_launch), "dF": app.upper.force - F0,
            "m_up": 0.5 * (m_up0 + _upstream_mass(sim)), "m_carriage": app.upper.carriage.mass,
            "m_roller": cfg.apparatus.roller_mass, "v0": app.strand_speed}


@pytest.fixture(scope="module")
def step() -> dict:
    base, heavy = _run(None), _run(HEAVY)
    t = heavy["t"] - T_SWITCH
    dv = heavy["v"] - base["v"]
    lam = io.load(LEVEL).sim.chain.linear_density
    v0 = float(base["v"][0])
    (va, pa), (vb, pb) = PICKUP_RIG_2CM
    drag = lam * ((pb - pa) / (vb - va) * v0**2 + 2.0 * pickup_rig_2cm(v0) * v0)
    M = referred_mass(heavy["m_up"], heavy["m_carriage"], heavy["m_roller"])
    return {"t": t, "dv": dv, "dF": heavy["dF"], "m_up": heavy["m_up"], "M": M, "drag": drag,
            "dT_exit": float(np.mean(heavy["T_exit"] - base["T_exit"])),
            "dT_launch": float(np.mean(heavy["T_launch"] - base["T_launch"])),
            "m_unit": M - heavy["m_up"]}


def _slope(t: np.ndarray, y: np.ndarray) -> float:
    return float(np.polyfit(t, y, 1)[0])


def test_strand_between_pickup_and_launch_carries_the_step(step: dict) -> None:
    """Momentum of the strand on its fixed path: ``M_up * Delta a = Delta T_launch -
    Delta T_exit`` within 10 % (measured 2 %); the launch tension barely moves, so the
    chain in flight is not part of the decelerated mass."""
    da = _slope(step["t"], step["dv"])
    force = step["dT_launch"] - step["dT_exit"]
    assert force / da == pytest.approx(step["m_up"], rel=0.10)
    assert abs(step["dT_launch"]) < 0.1 * step["dT_exit"]


def test_pickup_passes_the_step_as_a_rolling_pulley(step: dict) -> None:
    """The exit tension's rise, less the pick-up's speed dependence (``drag * dv``) and
    the roller unit's inertia, over ``Delta F``: closer to the energy balance's 1/2 than
    to the rig's steady gain 0.68 (measured 0.53)."""
    da = _slope(step["t"], step["dv"])
    gain = (step["dT_exit"] - step["drag"] * float(np.mean(step["dv"]))
            - step["m_unit"] * da) / step["dF"]
    assert abs(gain - 0.5) < abs(gain - CART_GAIN_2CM)


def test_heavier_cart_decelerates_as_the_energy_balance_predicts(step: dict) -> None:
    """Issue 4: within 5 % of the energy balance (measured 1.017)."""
    t = step["t"]
    pred = cart_step_speed(t, step["dF"], step["M"], gain=0.5, drag=step["drag"])
    assert _slope(t, step["dv"]) / _slope(t, pred) == pytest.approx(1.0, abs=0.05)


def test_rig_gain_overpredicts_the_step(step: dict) -> None:
    """The rig's steady cart gain (0.68) with the same mass and drag predicts a
    deceleration about a third too large (measured/predicted 0.75): the step is not
    passed on as the steady rig passes a cart force on."""
    t = step["t"]
    pred = cart_step_speed(t, step["dF"], step["M"], gain=CART_GAIN_2CM, drag=step["drag"])
    assert _slope(t, step["dv"]) / _slope(t, pred) < 0.85
