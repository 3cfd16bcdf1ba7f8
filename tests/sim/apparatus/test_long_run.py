"""The special preset run long: without its swing damper the landing swing grows until the
fold fails (issue 4); with it (as shipped) the swing stays bounded and the run goes on.

The undamped machine (:data:`tests.sim.apparatus.runs.UNDAMPED_SPECIAL`: no damper, no fold
clearance, a 58 g lower cart) is the contact fold's own behaviour, read below.

``apparatus_special`` runs with both plates as treadmills, so nothing in the machine
runs out. Without its damper it still does not go on for ever (docs/apparatus.md, "The
landing swing"): the chain speed carries an oscillation of period about 2.1 s (the
landing swing: the fountain stores and gives back up to 12 links) whose amplitude grows
until the folding roller loses the chain. The collapse message says how long the fold
held and how large the swing had grown; it does not blame a missing push ("raise the
lower cart mass", as the run-away speed suggests).

Measured (this module's run, ``apparatus_special`` without its damper at
:data:`tests.sim.apparatus.runs.STUDY_STEP`): 3.024 m/s over 0.5-8 s, the swing +-0.064 m/s over
0.5-3.5 s and +-0.164 m/s in its largest later 4-s window; the last link to enter the end
guide through its mouth did so at 26.93 s, 5.9 cm inside the first turn's radius (the
catch takes links within 6 cm: the fountain had widened), and the folding roller rolled
back at 27.95 s, having held the chain at ``v/2`` for 26.8 s. Nudged starts (seeds 1
and 2) failed at 20.85 and 19.25 s, their swing growing from +-0.073 to +-0.190 and
+-0.173 m/s.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from chainfountain.level import io
from chainfountain.sim import Simulation
from chainfountain.sim.apparatus import FoldCollapsed
from tests import shipped
from tests.sim.apparatus.runs import load_undamped

LEVEL = shipped.path("apparatus_special")
pytestmark = [pytest.mark.slow, pytest.mark.xdist_group("apparatus_long_run")]


UNDAMPED_RUN = 40.0
"""The undamped run's longest time (s): its fold failed at 19.3-27.9 s in three starts."""


@pytest.fixture(scope="module")
def long_run() -> tuple[np.ndarray, np.ndarray, str | None]:
    """Strand speed every 0.01 s until the run ends (at most :data:`UNDAMPED_RUN`) and the
    message."""
    sim = Simulation(load_undamped(LEVEL).sim)
    app = sim.apparatus
    t, v = [], []
    message = None
    try:
        while sim.time < UNDAMPED_RUN - 1e-9:
            sim.advance(0.01)
            t.append(sim.time)
            v.append(app.strand_speed)
    except FoldCollapsed as exc:
        message = str(exc)
    return np.array(t), np.array(v), message


DAMPED_RUN = 30.0


@pytest.fixture(scope="module")
def damped_run() -> tuple[np.ndarray, np.ndarray]:
    """The shipped preset (swing damper 0.5 N s/m): strand speed every 0.01 s for 30 s."""
    sim = Simulation(io.load(LEVEL).sim)
    app = sim.apparatus
    t, v = [], []
    while sim.time < DAMPED_RUN - 1e-9:
        sim.advance(0.01)
        t.append(sim.time)
        v.append(app.strand_speed)
    return np.array(t), np.array(v)


def _swing(t: np.ndarray, v: np.ndarray, a: float, b: float) -> float:
    """Half the peak-to-peak strand speed about its linear trend over ``[a, b)`` (m/s)."""
    m = (t >= a) & (t < b)
    d = v[m] - np.polyval(np.polyfit(t[m], v[m], 1), t[m])
    return 0.5 * float(d.max() - d.min())


def test_special_preset_holds_its_described_speed_for_8_seconds(long_run) -> None:
    t, v, _ = long_run
    # the preset's description promises about 3.02 m/s (measured 3.020 over 0.5-8 s)
    assert t[-1] > 8.0
    m = (t >= 0.5) & (t < 8.0)
    assert float(np.mean(v[m])) == pytest.approx(3.02, rel=0.02)


def test_special_landing_swing_grows(long_run) -> None:
    t, v, _ = long_run
    # measured: +-0.064 m/s over 0.5-3.5 s, +-0.164 m/s in the largest later 4-s window
    # (nudged starts: 0.073 -> 0.190, 0.073 -> 0.173); a bounded swing (what the paper's
    # steady fountain implies) would fail this
    early = _swing(t, v, 0.5, 3.5)
    late = max(_swing(t, v, a, a + 4.0) for a in np.arange(8.5, t[-1] - 3.99, 4.0))
    assert late > 2.0 * early


def test_special_late_collapse_names_the_swing_not_the_cart(long_run) -> None:
    t, _, message = long_run
    # measured: the folding roller lost the chain at 27.95 s (nudged starts: 20.85, 19.25 s)
    assert message is not None and 10.0 < t[-1] < UNDAMPED_RUN
    assert "after holding it at v/2 for" in message and "landing swing" in message
    assert "raise the lower cart mass" not in message
    held = float(message.split("for ")[1].split(" s")[0])
    assert held > 10.0


def test_special_collapse_says_when_the_catch_was_lost(long_run) -> None:
    t, _, message = long_run
    # measured: last entry through the mouth at 26.93 s, 5.9 cm inside the turn's radius
    # (the band's edge is 6 cm), the folding roller rolling back from 27.95 s. A fold that
    # failed at the roller while the chain still landed in the mouth would fail this.
    assert message is not None
    m = re.search(r"mouth at t = ([0-9.]+) s, ([0-9.]+) cm (outside|inside)", message)
    assert m is not None, message
    t_mouth, offset = float(m.group(1)), float(m.group(2))
    assert t[-1] - t_mouth > 0.5
    assert offset > 4.5  # it left through the band's edge, not from near the radius


def test_the_swing_damper_holds_the_fold(damped_run) -> None:
    """With the damper between the carriages (``apparatus.swing_damper``) the shipped preset
    runs the 30 s without the fold failing (undamped: 19-28 s), its swing stays bounded,
    below +-0.1 m/s in every 4-s window (damped: +-0.039 ... +-0.074 m/s over 60 s from 3.0
    and 2.97 m/s, no trend; undamped it passes +-0.13 m/s by 12 s, above), and every 10-s
    window after the first drifts less than issue 36's 0.2 %/s."""
    t, v = damped_run
    assert t[-1] == pytest.approx(DAMPED_RUN)
    swings = [_swing(t, v, a, a + 4.0) for a in np.arange(1.0, DAMPED_RUN - 3.9, 4.0)]
    assert max(swings) < 0.1, swings
    for a in (10.0, 20.0):
        m = (t >= a) & (t < a + 10.0)
        slope = np.polyfit(t[m], v[m], 1)[0]
        assert abs(slope / np.mean(v[m])) < 0.002
