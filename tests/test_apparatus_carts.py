"""Unbalanced upper cart: the chain decelerates (issue 4, step 2; ``docs/apparatus.md``).

``levels/apparatus_floor.toml`` (without its treadmill, ``plate_links = 0``) runs
near its selected speed; at ``t = 1 s``
the upper cart is made heavier live (9 g -> 60 g, ``Delta F_uc = 0.25 N``) and
the deceleration of the chain (the rigid strand in the plate grooves) is
compared with an unswitched run. Momentum balance of the whole moving chain
along its path, with the pick-up exit tension ``p*lambda*v**2 + G*F_uc`` (rig
law for these links, ``G`` = :data:`~chainfountain.sim.apparatus.CART_GAIN_2CM`)
and the carriage/roller inertia carried through the same gain::

    Delta a = -G*Delta F_uc / (M + G*((m_carriage + m_roller)/2 + m_roller/4))

(energy balance of an ideal rolling pulley instead: ``-Delta F_uc/2 / (M + ...)``).
Measured: 86-92 % of the momentum prediction (0.3-0.6-s windows), between the
two; the 5 % requirement is a strict xfail. The preset's upper channel became a joint
guide in the eighteenth session: 0.866 (the walls: 0.873, 0.6-s window).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from chainfountain.level import io
from chainfountain.sim import Simulation
from chainfountain.sim.apparatus import CART_GAIN_2CM

LEVEL = Path(__file__).resolve().parents[1] / "levels" / "apparatus_floor.toml"
T_SWITCH, WINDOW = 1.0, 0.6


def _decel(mass: float) -> tuple[float, float, float, float]:
    """Strand-speed slope after the switch, moving mass, Delta F_uc, carriage mass."""
    cfg = io.load(LEVEL).sim
    # the real geometry (the pick-up roller travels, the upper strand is long), as
    # measured; the preset's treadmill strand (M about 0.1 kg) is in docs/apparatus.md
    cfg = dataclasses.replace(cfg, apparatus=dataclasses.replace(cfg.apparatus, plate_links=0))
    sim = Simulation(cfg)
    app = sim.apparatus
    sim.advance(T_SWITCH)
    M, F0 = app.moving_mass(), app.upper.force
    sim.set_param("carts[0].mass", mass)
    t, v = [], []
    for _ in range(int(round(WINDOW / 0.005))):
        sim.advance(0.005)
        t.append(sim.time)
        v.append(app.strand_speed)
    return float(np.polyfit(t, v, 1)[0]), M, app.upper.force - F0, app.upper.carriage.mass


pytestmark = pytest.mark.xdist_group("apparatus_carts")
"""The module-scoped run is computed once, on one worker (``--dist loadgroup``)."""


@pytest.fixture(scope="module")
def ratio() -> float:
    a0, _, _, _ = _decel(io.load(LEVEL).sim.carts[0].mass)
    a1, M, dF, m_car = _decel(0.06)
    m_r = io.load(LEVEL).sim.apparatus.roller_mass
    G = CART_GAIN_2CM
    pred = -G * dF / (M + G * ((m_car + m_r) / 2 + m_r / 4))
    return (a1 - a0) / pred


def test_heavier_cart_decelerates_as_measured(ratio: float) -> None:
    assert 0.8 < ratio < 1.0


@pytest.mark.xfail(strict=True, reason="86-92 % of the momentum balance with the rig's cart "
                   "gain with the channel's walls, 87 % with the joint guide (docs/apparatus.md)")
def test_heavier_cart_decelerates_within_5_percent(ratio: float) -> None:
    assert abs(ratio - 1.0) <= 0.05
