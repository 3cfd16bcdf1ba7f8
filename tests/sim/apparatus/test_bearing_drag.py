"""The contact machine's declared loss ``apparatus.bearing_drag`` (``docs/apparatus.md``).

A drag ``c`` on each roller's carriage acts like more cart: ``c*v/2`` more holding the
pick-up back. In ``apparatus_floor`` it lowers the speed the machine selects exactly as
the rig law with that extra force says (:func:`~chainfountain.sim.apparatus.selected_speed`
with ``drag``): the measured speed's ratio to the law's is the same with and without the
drag. Measured (4-8 s of an 8-s run from the level's start; four nudged starts,
``--perturb 0..3``, spread 0.0004): 0.9752-0.9756 at ``c = 0`` (the guide's known loss)
and 0.9768-0.9769 at ``c = 0.01`` N s/m, where the law moves the speed by -3.2 %. The
tolerance, 0.5 % of the speed, is a sixth of that shift and three times the difference
measured.
"""

from __future__ import annotations

import pytest

from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus_report import report
from tests import shipped
from tests.sim.apparatus.runs import load_on_path

LEVEL = shipped.path("apparatus_floor")
RUN, STEADY = 8.0, (4.0, 8.0)

pytestmark = pytest.mark.xdist_group("apparatus_bearing_drag")


def _ratio(drag: float) -> tuple[float, float]:
    """(measured speed / rig law's speed with the drag, the law's speed) over STEADY."""
    cfg = load_on_path(LEVEL).sim
    cfg.apparatus.bearing_drag = drag
    sim = Simulation(cfg)
    rec = Recorder(sim, profiles=False)
    sim.advance(RUN)
    sel = report(sim, rec, *STEADY)["speed_selection"]
    return sel["v_measured"] / sel["v_rig_2cm"], sel["v_rig_2cm"]


@pytest.mark.slow
def test_drag_lowers_the_selected_speed_as_the_law_says() -> None:
    r0, v0 = _ratio(0.0)
    r1, v1 = _ratio(0.01)
    assert v1 / v0 - 1.0 == pytest.approx(-0.032, abs=0.002)  # the law's shift
    assert r1 == pytest.approx(r0, abs=0.005)


def test_drag_is_a_live_field() -> None:
    cfg = load_on_path(LEVEL).sim
    sim = Simulation(cfg)
    sim.set_param("apparatus.bearing_drag", 0.02)
    assert sim.apparatus.cfg.bearing_drag == 0.02
    v = 3.0
    uc0 = sim.apparatus.upper.force / (cfg.chain.linear_density * v * v)
    assert sim.apparatus.cart_bars(v, cfg.chain.linear_density)[0] == pytest.approx(
        uc0 + 0.5 * 0.02 * v / (cfg.chain.linear_density * v * v))
