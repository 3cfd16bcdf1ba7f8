"""The paper's fountain D presets (issue 4, "Paper presets").

Fountain D (Fig. "schematic_chain_fountain"): ``H = 2 m``, ``xi = h/H = 0.14``,
``kappa = l/H = 0.165``, at ``k = 0.377`` (`levels/fountain_d.toml`) and at
``k = k_max`` (`levels/fountain_d_kmax.toml`, the limit case: ``Tbar_E = 0``,
``Tbar_0 = k*H``). Both are fed levels written by ``chainfountain design`` (4 mm
links, a step of 15 / 18 us: the vertex is near-critical, ``k/q`` = 0.017 /
0.019). The ``k = 0.377`` level is run by ``tests/cli/test_design_levels.py``
(``paper_D``); this file runs the ``k_max`` one.

Measured (1.5-s run, window 0.5-1.5 s): ``Tbar_E`` 0.0033, ``Tbar_0`` 0.8594
against ``k H`` = 0.8601, vertex +0.55 %, landing +0.07 %, speed 4.7750 m/s
(fed at 4.7761), stretch 0.012 %.
"""

from __future__ import annotations

import dataclasses

import pytest

from chainfountain.design_level import design_sim_config
from chainfountain.sim import Recorder, Simulation
from chainfountain.theory import Fountain
from chainfountain.theory.design import design
from tests import shipped

L_D, H_D, H = 0.33, 0.28, 2.0  # the paper's fountain D: l = kappa*H, h = xi*H
SETTLE, WINDOW = 0.5, 1.0

pytestmark = pytest.mark.xdist_group("fountain_d_kmax_run")
"""One worker runs this module (``--dist loadgroup``), so its 20-s run is made once."""


def _fountain(k: float | None = None) -> Fountain:
    base = Fountain(l=L_D, h=H_D, H=H, k=1.0)
    return base.with_k(k if k is not None else base.k_max)


def test_fountain_d_presets_are_the_designed_levels(level) -> None:
    # the presets are exactly what `chainfountain design` writes for fountain D today
    for name, f in (("fountain_d", _fountain(0.377)), ("fountain_d_kmax", _fountain())):
        cfg = level(name).sim
        want = design_sim_config(design(f, cfg.chain.linear_density))
        assert cfg == dataclasses.replace(want, name=name), name


def test_fountain_d_kmax_is_the_limit_case(level) -> None:
    f = _fountain()
    assert f.k == pytest.approx(0.4301, abs=5e-5)  # physics notes: k_max = 0.4301 1/m
    assert f.TE_bar == pytest.approx(0.0, abs=1e-12)
    assert f.T0_bar == pytest.approx(f.k * H, abs=1e-12)
    cfg = level("fountain_d_kmax").sim
    assert cfg.feed.end_tension == 0.0 and cfg.feed.floor == "absorbing"  # a free end


@pytest.fixture(scope="module")
def kmax_run():
    cfg = shipped.level("fountain_d_kmax").sim
    sim = Simulation(cfg)
    sim.advance(SETTLE)
    rec = Recorder(sim)
    sim.advance(WINDOW)
    return rec.summary(window=WINDOW), _fountain()


@pytest.mark.slow
def test_fountain_d_kmax_end_force_vanishes(kmax_run) -> None:
    s, _ = kmax_run
    # issue 4: "The k_max preset ends with Tbar_E within 0.05 of zero" (measured 0.003)
    assert abs(float(s.extras["tension_bar"][-1])) <= 0.05


@pytest.mark.slow
def test_fountain_d_kmax_start_force_is_kH(kmax_run) -> None:
    s, f = kmax_run
    # Tbar_0 = k*H at k_max; 0.01 is about ten times the run's tension noise (RMS 0.0013)
    assert s.T0_bar == pytest.approx(f.k * H, abs=0.01)


@pytest.mark.slow
def test_fountain_d_kmax_shape(kmax_run) -> None:
    s, f = kmax_run
    assert s.vertex_y == pytest.approx(H_D, rel=0.02)
    assert s.landing_x == pytest.approx(L_D, rel=0.02)
    assert s.speed_mean == pytest.approx(f.v, rel=0.005)
    assert s.stretch_max <= 1e-3
    # the fed fountains' criteria (tests/sim/test_feed.py leaves fountain D to this run)
    assert s.speed_uniformity < 0.01
    assert s.tension_rms < 0.03 and s.extras["tension_bar"].min() > -0.03
