"""The paper's idealized beaker with a real floor (``feed.drive = "ideal_floor"``): the
machine, not a motor, sets the speed, and it selects the one the paper predicts,
``v^2 = 2 g (H (1 - xi2) - F_uc/(lambda g))`` (section "Idealized beaker, real floor").

The selected speed is a stable equilibrium of the machine: the run's mean over a long
window is what is asserted (measured with ``research/ideal_floor.py`` and
``chainfountain run ideal_floor``: +0.01 % at ``xi2 = 0.3``, +0.05 % at ``xi2 = 0.1``,
scatter of the speed 0.04 %).
"""

from __future__ import annotations

import numpy as np
import pytest

from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation
from chainfountain.theory.apparatus import ideal_floor_speed
from tests import shipped


def _run(xi2: float | None = None, seconds: float = 8.0, push: float | None = None):
    lvl = shipped.level("ideal_floor")
    lvl.sim.initial.mode, lvl.sim.feed.starter = "catenary", 0.0  # from the fountain on
    if xi2 is not None:
        lvl.sim.feed.xi2 = xi2
    sim = Simulation(lvl.sim)
    rec = Recorder(sim, profiles=False)
    if push is not None:
        sim.advance(seconds / 2)
        sim.set_feed_speed(push)
    sim.advance(seconds - (sim.time if push is not None else 0.0))
    f = lvl.sim.feed
    v_pred = ideal_floor_speed(f.drop, f.xi2, f.cart_force, lvl.sim.chain.linear_density,
                               lvl.sim.gravity)
    return sim, rec, v_pred


@pytest.mark.slow
@pytest.mark.parametrize("xi2", [0.3, 0.1], ids=["xi2_0.3", "xi2_0.1"])
def test_the_machine_selects_the_papers_speed(xi2) -> None:
    """From 3.5 m/s the machine settles on the paper's speed (3.71 m/s at xi2 = 0.3, 4.20 m/s
    at 0.1) and the fountain on the paper's catenary for that speed."""
    sim, rec, v_pred = _run(xi2)
    t, v = rec.series("t"), rec.series("speed_mean")
    late = t >= 4.0
    assert np.mean(v[late]) == pytest.approx(v_pred, rel=0.005)
    assert sim.reference.v == pytest.approx(v_pred)
    e = rec.summary(window=4.0).errors(sim.reference)
    assert abs(e["h"]) < 0.01 and abs(e["l"]) < 0.03, e


@pytest.mark.slow
def test_pushed_it_comes_back() -> None:
    """Pushed to 4.2 m/s at 5 s, the machine brings the chain back to its own speed."""
    sim, rec, v_pred = _run(push=4.2, seconds=10.0)
    t, v = rec.series("t"), rec.series("speed_mean")
    assert np.max(v[(t > 5.0) & (t < 5.5)]) > 1.05 * v_pred  # the push took
    assert np.mean(v[t >= 8.5]) == pytest.approx(v_pred, rel=0.005)


@pytest.mark.parametrize("change, field, words", [
    (("drive", "motor"), "feed.xi2", ["has no effect with feed.drive = 'motor'"]),
    (("cart_force", 0.15), "feed.xi2", ["selects 2.781 m/s", "allowed: xi2 < 0.1942"]),
    (("floor", "solid"), "feed.floor", ["feed.drive = 'ideal_floor'"]),
])
def test_settings_the_machine_cannot_run_are_refused(level, tmp_path, change, field, words) -> None:
    lvl = level("ideal_floor")
    setattr(lvl.sim.feed, *change)
    text = io.dumps(lvl)
    with pytest.raises(io.LevelError) as exc:
        io.loads(text, "bad.toml")
    msg = str(exc.value)
    assert msg.startswith(f"bad.toml: {field}") and "\n" not in msg, msg
    for w in words:
        assert w in msg, msg
