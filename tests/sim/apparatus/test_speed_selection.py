"""Speed selection of the free-ended apparatus: a heavier upper cart, a slower chain.

``levels/apparatus_floor_heavy.toml`` (15 g cart, a 0.25 ms step) against
``apparatus_floor`` (9 g, about 2.93 m/s, ``tests/sim/apparatus/test_floor.py``).
Paper (section "Generating Steady-State Chain Fountains", free end ``Tbar_E = 0``):
``v**2 = (g*H*(1 - xi2) - G*F_uc/lambda)/p``. What is asserted is what the simulation
does (``docs/apparatus.md``): the heavy cart selects a clearly lower speed, steady; the
paper's ``p = 1/2, G = 1`` gives 1.98 m/s. The rig law for these links
(:data:`~chainfountain.sim.apparatus.PICKUP_RIG_2CM`, ``CART_GAIN_2CM``) predicts 2.876
+- 0.014 m/s and the chain runs at 2.78 (-3.4 %, a strict expected failure): the energy
budget finds about 0.014 ``lambda v**3`` lost between the plate and the free end (the
guide's arc, the flight, the grooves); with it the law gives 2.80-2.81 m/s, and the runs
of three nudged starts lie 0.8-0.95 % (1.6-1.8 sigma) below it. At a 0.5 ms step the
preset runs at 2.752, 2.5 sigma below, as if its pick-up needed more than the rig's: the
step's error, which is why the preset steps at 0.25 ms.
"""

from __future__ import annotations

import pytest

from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus_report import report
from chainfountain.sim.budget import EnergyBudget, rig_law_speed
from tests import shipped
from tests.sim.apparatus.runs import load_on_path

LEVEL = shipped.path("apparatus_floor_heavy")
RUN = 5.0


pytestmark = pytest.mark.xdist_group("apparatus_speed_selection")
"""The module-scoped run is computed once, on one worker (``--dist loadgroup``)."""


SEEDS = (0, 1, 2)
"""Starts of the ensemble: 0 the level's own, above 0 nudged by 1e-12
(``initial.seed``)."""


@pytest.fixture(scope="module")
def runs() -> list[dict]:
    out = []
    for seed in SEEDS:
        level = load_on_path(LEVEL)
        level.sim.initial.seed = seed
        sim = Simulation(level.sim)
        rec = Recorder(sim, profiles=False)
        budget = EnergyBudget(sim, start=3.0, every=2)
        sim.advance(RUN)
        rep = report(sim, rec, 3.0, RUN)
        rep["energy_budget"] = budget.result()
        out.append(rep)
    return out


@pytest.fixture(scope="module")
def rep(runs):
    return runs[0]


@pytest.mark.slow
def test_heavier_cart_selects_a_lower_speed(rep) -> None:
    sel = rep["speed_selection"]
    assert sel["v_measured"] < 2.93 - 0.1  # light preset: 2.93 m/s; measured 2.78
    assert sel["v_measured"] > sel["v_paper_p_half"] * 1.2  # paper p = 1/2: far too slow


@pytest.mark.slow
def test_heavy_cart_steady(rep) -> None:
    assert abs(rep["measured"]["speed_drift_per_s"]) <= 0.01


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="measured 2.78 m/s against the rig law's 2.876 +- "
                   "0.014 (-3.4 %): the law assumes an ideal guide; the energy budget finds "
                   "0.014 lambda v^3 lost in the discrete guide, grooves and flight (next "
                   "test); docs/apparatus.md, 'Energy budget'")
def test_heavy_cart_within_two_sigma_of_the_rig_law(rep) -> None:
    sel = rep["speed_selection"]
    assert abs(sel["v_measured"] - sel["v_rig_2cm"]) <= 2.0 * sel["v_rig_2cm_sigma"]


@pytest.mark.slow
def test_heavy_cart_within_two_sigma_of_the_rig_law_with_the_losses(runs) -> None:
    """Over three starts the chain runs within 2 sigma of the rig law with the guide's
    measured loss (measured: 1.6-1.8 sigma below, the starts within 0.1 sigma of each
    other)."""
    off = []
    for r in runs:
        sel, b = r["speed_selection"], r["energy_budget"]
        v = rig_law_speed(load_on_path(LEVEL).sim, b.total)
        off.append((sel["v_measured"] - v) / sel["v_rig_2cm_sigma"])
    assert abs(sum(off) / len(off)) <= 2.0, off


@pytest.mark.slow
def test_heavy_cart_free_end(runs) -> None:
    """A free end: ``Tbar_0 = k*H`` with ``Tbar_E`` near 0, as means over the three starts
    (3-5 s). ``Tbar_0 - Tbar_E`` falls short of ``k*H`` by about 0.03 (one start at a time
    -0.021 ... -0.043 over seven measured starts; the starts' spread is 0.01), the end
    tension the floor reads that the launch does not carry; a short fall of more than
    0.05 fails."""
    def mean(key: str) -> float:
        return sum(r["measured"][key] for r in runs) / len(runs)

    t0, te, kh = mean("T0_bar"), mean("TE_bar"), mean("kH")
    assert 0.0 <= te < 0.05
    assert t0 == pytest.approx(kh, abs=0.03)
    assert -0.05 < t0 - te - kh < 0.0


def test_selected_speed_closes_the_balance_or_is_nan() -> None:
    """With the rig law the selected speed is where the pick-up's exit tension plus the
    rise equals the fountain's ``Tbar_0 = k*H``: ``p(v) + G*Tbar_uc + xi2*k*H = k*H``
    (fountain D's drop, the k_max preset's 132.4 g cart). Where the cart and the rolling
    resistance outweigh the drop there is no speed: nan, not a crash (a 110 g cart crashed
    the report with the old, extrapolated law)."""
    import math

    from chainfountain.sim.apparatus import CART_GAIN_2CM, pickup_rig_2cm, selected_speed

    lam, g, H, xi2 = 0.05, 9.81, 2.0, 0.3
    F = 0.1324 * g * 0.5
    v = selected_speed(g, H, xi2, F, lam, gain=CART_GAIN_2CM)
    k = g / v**2
    assert pickup_rig_2cm(v) + CART_GAIN_2CM * F / (lam * v * v) + xi2 * k * H == \
        pytest.approx(k * H, rel=1e-12)
    assert math.isnan(selected_speed(g, H, xi2, 0.26 * g * 0.5, lam, gain=CART_GAIN_2CM))
    assert math.isnan(selected_speed(g, 2.0, 0.3, 0.0, lam, p=0.0))
