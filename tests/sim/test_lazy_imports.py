"""A running simulation loads no slow module in its loop.

``scipy.stats`` takes 0.5-1.3 s to import on this machine; imported when an apparatus's
first sample is analysed, it stalled the window's first frames (a 0.5-s frame, 3 % of a
20-s run's real time lost). It is imported only by the summary that needs it."""

from __future__ import annotations

import subprocess
import sys
import textwrap


def test_recording_an_apparatus_does_not_import_scipy_stats() -> None:
    code = textwrap.dedent("""
        import sys
        from chainfountain.level import io, library
        from chainfountain.sim import Recorder, Simulation
        sim = Simulation(io.load(library.resolve("apparatus_floor")).sim)
        rec = Recorder(sim, profiles=False)
        sim.advance(0.1)
        assert rec.samples and rec.apparatus_samples, "nothing was recorded"
        print("scipy.stats" in sys.modules)
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, timeout=120)
    assert out.stdout.strip() == "False", out.stdout + out.stderr
