"""Design acceptance (issue 6): a designed level, run headless, gives the target fountain
within the accuracy ``design`` promises.

Each target ``(l, h, H, v)`` goes through ``chainfountain design --out --json``; the written
level is simulated from the catenary (settle 1.5 s, average 2 s; fountain D, at a 15-us step,
settle 0.5 s and average 1 s as tests/sim/test_fountain_d.py runs its k_max twin). For a
target inside the
error model (:mod:`chainfountain.sim.accuracy`) the vertex height, vertex x and landing must
lie within the bounds ``design`` prints for the level's settings (``level_settings``); the
near-critical fountain D, outside the model, has height and landing within 3 %. The speed
within 0.1 %.
"""

import json
import math

import pytest

from chainfountain.cli import main
from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation

SETTLE, WINDOW = 1.5, 2.0
NEAR_CRITICAL = (0.5, 1.0)
"""Fountain D's settle and window (s): its 15-us step made 1.5 + 2 s the suite's costliest
run (57-97 s). Measured: height +0.58 %, landing +0.10 % over 0.5-1.5 s; +1.22 % and
-0.41 % over 1.5-3.5 s (the near-critical creep, docs/convergence.md); the bound is 3 %."""

TARGETS = [
    # (l, h, H, v, --accuracy): admissible speeds from `chainfountain theory`
    # (v(k_max) <= v < v_max); the narrow target at 1 %, since 0.5 % takes 3-mm links at a
    # 31-us step there (12.9 s per simulated second)
    pytest.param(1.5, 0.6, 1.5, 5.1, 0.005, id="broad_TE0.08"),
    pytest.param(1.0, 0.6, 1.0, 4.25, 0.005, id="mid_TE0.02"),
    pytest.param(0.8, 0.3, 1.2, 4.6, 0.01, id="narrow_TE0.22"),
    # the paper's fountain D: near-critical (k/q = 0.017), designed with dt = 15 us
    pytest.param(0.33, 0.28, 2.0, math.sqrt(9.81 / 0.377), 0.005, id="paper_D"),
]


@pytest.mark.slow
@pytest.mark.parametrize("l, h, H, v, accuracy", TARGETS)
def test_designed_level_reproduces_target(tmp_path, capsys, l, h, H, v,  # noqa: E741
                                          accuracy):
    path = tmp_path / "designed.toml"
    assert main(["design", "--l", str(l), "--h", str(h), "--H", str(H), "--v", str(v),
                 "--accuracy", str(accuracy), "--out", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["level"] == str(path)
    level = io.load(path)
    level.sim.initial.mode = "catenary"
    settle, window = NEAR_CRITICAL if h == 0.28 and H == 2.0 else (SETTLE, WINDOW)
    sim = Simulation(level.sim)
    sim.advance(settle)
    rec = Recorder(sim)
    sim.advance(window)
    s = rec.summary(window=window)
    ref = sim.reference
    assert s.stretch_max <= 1e-3
    assert s.speed_mean == pytest.approx(v, rel=1e-3)
    # the fed fountains' criteria (tests/sim/test_feed.py, which leaves fountain D to this
    # run): a uniform speed, and the tension along the chain as the paper's line
    assert s.speed_uniformity < 0.01
    assert s.tension_rms < 0.03 and s.extras["tension_bar"].min() > -0.03
    got = {"h": s.vertex_y / h - 1.0, "vertex_x": s.vertex_x / ref.x_rise - 1.0,
           "l": s.landing_x / l - 1.0}
    settings = out.get("level_settings")
    # fountain D: height and landing within 3 %; its vertex x is 3-4 % off over this
    # window (docs/convergence.md, "Near-critical fountains")
    bounds = settings["error_model_bounds"] if settings else {"h": 0.03, "l": 0.03}
    for fig, bound in bounds.items():
        assert abs(got[fig]) <= bound, (fig, got[fig], bound)
