"""The readout's steadiness keeps its word: once steady it stays so while the vertex and
the speed stay within twice the level's tolerance (no flicker), and a new run starts not
steady (:data:`chainfountain.app.readout.STEADY_HYSTERESIS`)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from chainfountain.app.readout import STEADY_HYSTERESIS, is_steady
from chainfountain.sim.config import RecordingConfig


def _wandering(amplitude: float) -> tuple[SimpleNamespace, dict[str, np.ndarray]]:
    """10 s of a flat speed and a vertex wandering by ``amplitude`` (relative) with a 3-s
    period, as a contact machine's does."""
    rc = RecordingConfig()
    t = np.arange(0.0, 10.0, 0.05)
    hist = {"t": t, "speed": np.full_like(t, 2.79),
            "vertex_y": 0.3 * (1.0 + amplitude * np.sin(2 * np.pi * t / 3.0))}
    return SimpleNamespace(config=SimpleNamespace(recording=rc), dragging=False), hist


def test_a_steady_readout_stays_steady_within_twice_its_tolerance() -> None:
    sim, hist = _wandering(1.5 * RecordingConfig().steady_tolerance)
    assert not is_steady(sim, hist)  # a new run: the tight test, not yet steady
    assert is_steady(sim, hist, STEADY_HYSTERESIS)  # was steady: it stays so
    sim, hist = _wandering(2.5 * RecordingConfig().steady_tolerance)
    assert not is_steady(sim, hist, STEADY_HYSTERESIS)  # beyond twice: no longer
    sim, hist = _wandering(0.5 * RecordingConfig().steady_tolerance)
    assert is_steady(sim, hist)
