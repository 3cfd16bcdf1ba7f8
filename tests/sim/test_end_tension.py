"""A floor that pulls on the chain end: fountains with Tbar_E > 0 (the paper's floor reaction)."""

import pytest

from chainfountain.sim import Recorder, Simulation
from tests import shipped


@pytest.fixture(scope="module")
def run():
    cfg = shipped.level("wide_low").sim
    cfg.feed.end_tension = 0.2
    cfg.initial.mode = "catenary"
    sim = Simulation(cfg)
    sim.advance(1.5)
    rec = Recorder(sim)
    sim.advance(2.0)
    return sim, rec.summary(window=2.0)


@pytest.mark.slow
def test_end_tension_fountain_matches_theory(run):
    sim, s = run
    ref = sim.reference
    assert ref.TE_bar == 0.2
    assert ref.T0_bar == pytest.approx(0.2 + ref.k * ref.H)
    e = s.errors(ref)
    assert abs(e["h"]) < 0.01, e
    assert abs(e["vertex_x"]) < 0.03, e
    assert abs(e["l"]) < 0.03, e
    assert s.tension_rms < 0.03
    # Measured at the ends, from the momentum balance with the floor's pull as external force.
    assert s.extras["tension_bar"][-1] == pytest.approx(0.2, abs=0.03)
    assert s.T0_bar == pytest.approx(ref.T0_bar, abs=0.03)


def test_end_tension_is_live(level):
    sim = Simulation(level("wide_low").sim)
    sim.set_param("feed.end_tension", 0.1)
    assert sim.reference.TE_bar == 0.1
    sim.advance(0.05)
    assert sim.feed.end_force is None  # the stub's end is in the air: nothing pulls it yet
    while sim.feed.absorbed == 0 and sim.time < 5.0:
        sim.advance(0.05)
    sim.advance(0.05)
    assert sim.feed.absorbed > 0 and sim.feed.end_force is not None  # landed: the floor pulls
