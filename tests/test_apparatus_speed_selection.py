"""Speed selection of the free-ended apparatus: a heavier upper cart, a slower chain.

``levels/apparatus_floor_heavy.toml`` (15 g cart) against ``apparatus_floor``
(9 g, about 2.91 m/s, ``tests/test_apparatus_floor.py``). Paper (section
"Generating Steady-State Chain Fountains", free end ``Tbar_E = 0``):
``v**2 = (g*H*(1 - xi2) - F_uc/lambda)/p``. What is asserted is what the
simulation does (``docs/apparatus.md``): the heavy cart selects a clearly lower
speed, but 7-11 % above the prediction with the rig's pick-up force
(2.39 m/s) -- the in-situ mechanism force ``Tbar_0 - xi2*k*H`` is below the
rig's ``p + Tbar_uc`` (as if the cart force reached the chain at 75-90 %).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus import report

LEVEL = Path(__file__).resolve().parents[1] / "levels" / "apparatus_floor_heavy.toml"
RUN = 3.0


@pytest.fixture(scope="module")
def rep():
    sim = Simulation(io.load(LEVEL).sim)
    rec = Recorder(sim, profiles=False)
    sim.advance(RUN)
    return report(sim, rec, 1.5, RUN)


def test_heavier_cart_selects_a_lower_speed(rep) -> None:
    sel = rep["speed_selection"]
    assert sel["v_measured"] < 2.91 - 0.25  # light preset: 2.91 m/s
    assert sel["v_measured"] > sel["v_paper_p_half"] * 1.2  # paper p = 1/2: far too slow


def test_heavy_cart_disagreement_with_rig_law(rep) -> None:
    """Measured law: 7-11 % above the rig-law prediction in runs (2 sigma would be 5 %)."""
    assert 0.04 < rep["speed_selection"]["rel_error_rig_2cm"] < 0.14


def test_heavy_cart_free_end(rep) -> None:
    m = rep["measured"]
    assert 0.0 <= m["TE_bar"] < 0.05
    assert 0.5 < m["T0_bar"] < 1.0
    # not as steady as the 9 g preset: the low fountain breathes (vertex 15-40 % above
    # the catenary through the ends) and Tbar_0 - Tbar_E falls about 0.05 short of k*H
    assert m["T0_bar"] - m["TE_bar"] == pytest.approx(m["kH"], abs=0.08)
