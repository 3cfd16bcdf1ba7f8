"""Design acceptance (issue 6): a designed level, run headless, gives the target fountain.

Each target ``(l, h, H, v)`` goes through ``chainfountain design --out``; the
written level is simulated (settle, then average) and must reproduce the target
vertex height within 3 % and the target speed within 2 %.
"""

import math

import pytest

from chainfountain.cli import main
from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation

SETTLE, WINDOW = 1.5, 2.0

TARGETS = [
    # (l, h, H, v): admissible speeds from `chainfountain theory` (v(k_max) <= v < v_max)
    pytest.param(1.5, 0.6, 1.5, 5.1, id="broad_TE0.08"),
    pytest.param(1.0, 0.6, 1.0, 4.25, id="mid_TE0.02"),
    pytest.param(0.8, 0.3, 1.2, 4.6, id="narrow_TE0.22"),
    # the paper's fountain D: near-critical (k/q = 0.017), designed with dt = 15 us
    pytest.param(0.33, 0.28, 2.0, math.sqrt(9.81 / 0.377), id="paper_D"),
]


@pytest.mark.slow
@pytest.mark.parametrize("l, h, H, v", TARGETS)
def test_designed_level_reproduces_target(tmp_path, capsys, l, h, H, v):  # noqa: E741
    path = tmp_path / "designed.toml"
    assert main(["design", "--l", str(l), "--h", str(h), "--H", str(H), "--v", str(v),
                 "--out", str(path)]) == 0
    assert "wrote" in capsys.readouterr().out
    level = io.load(path)
    sim = Simulation(level.sim)
    sim.advance(SETTLE)
    rec = Recorder(sim)
    sim.advance(WINDOW)
    s = rec.summary(window=WINDOW)
    assert s.stretch_max <= 1e-3
    assert s.vertex_y == pytest.approx(h, rel=0.03)
    assert s.speed_mean == pytest.approx(v, rel=0.02)
    assert s.landing_x == pytest.approx(l, rel=0.03)
