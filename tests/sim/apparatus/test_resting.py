"""Resting chain in the solver: ``apparatus.rest_links`` behind the folding roller,
``apparatus.pickup_rest_links`` ahead of the pick-up roller (docs/apparatus.md,
"Level fields worth knowing")."""

from __future__ import annotations

import pytest

from chainfountain.level import io
from chainfountain.sim import Simulation
from tests import shipped
from tests.sim.apparatus.runs import load_undamped

LEVEL = shipped.path("apparatus_special")


def _resting(sim: Simulation) -> tuple[int, int]:
    """Links lying on the upper table ahead of the pick-up roller and on the lower
    table behind the folding roller."""
    app = sim.apparatus
    ahead = behind = 0
    for lk in app.chain.links:
        p = lk.body.position
        if abs(p.y - (app.y_table_up + app.rho)) < 0.003 and \
                app.upper.x + app.r < p.x < app.x_plate_up_end:
            ahead += 1
        if abs(p.y - (app.y_table_lo + app.rho)) < 0.003 and \
                app.x_plate_lo_start < p.x < app.lower.x - app.r:
            behind += 1
    return ahead, behind


def test_pickup_side_keeps_its_own_count() -> None:
    cfg = load_undamped(LEVEL).sim
    a = cfg.apparatus
    assert (a.pickup_rest_links, a.rest_links) == (8, 20)
    sim = Simulation(cfg)
    sim.advance(0.5)  # the folding roller has laid more than 20 links by now
    ahead, behind = _resting(sim)
    # a link enters when the roller comes within 8 link lengths; the one under the
    # roller (within r of its axis) is not counted
    assert 7 <= ahead <= 9
    assert 20 <= behind <= 23  # popped once 20 links lie beyond the roller's wrap


@pytest.mark.parametrize("value", [1, 4])
def test_too_few_resting_links_is_one_clear_error(tmp_path, value) -> None:
    text = LEVEL.read_text().replace("pickup_rest_links = 8", f"pickup_rest_links = {value}")
    p = tmp_path / "bad.toml"
    p.write_text(text)
    with pytest.raises(io.LevelError, match=rf"apparatus\.pickup_rest_links: {value} .*"
                       r"allowed: 0 .* or at least 5"):
        io.load(p)
