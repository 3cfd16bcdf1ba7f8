"""Beaker levels (``kind = "beaker"``): the shipped level loads, and a beaker that cannot
be built or would not pile is refused in one line naming the field."""

from __future__ import annotations

import pytest

from chainfountain.level.model import LevelError
from chainfountain.study import with_changes
from tests import shipped


def _beaker():
    return shipped.level("beaker")


def test_shipped_beaker_loads():
    lv = _beaker()
    assert lv.sim.kind == "beaker"
    assert lv.sim.chain.self_collision and lv.sim.chain.bend_limit > 0


@pytest.mark.parametrize("change, field", [
    ({"chain.self_collision": False}, "chain.self_collision"),
    ({"beaker.pot_width": 0.06}, "beaker.pot_width"),
    ({"beaker.pot_depth": 0.06, "beaker.pile_rows": 10}, "beaker.pot_depth"),
    ({"beaker.hang": 1.5}, "beaker.hang"),
    ({"chain.link_radius": 0.009}, "chain.link_radius"),
    ({"initial.mode": "stub"}, "initial"),
    ({"feed.speed": 3.0}, "feed.speed"),
    ({"solver.accuracy": 0.005}, "solver.accuracy"),
])
def test_bad_beaker_is_refused_naming_the_field(change, field):
    with pytest.raises(LevelError) as exc:
        with_changes(_beaker(), change)
    msg = str(exc.value)
    assert f": {field}:" in msg and "allowed" in msg
    assert "\n" not in msg


def test_a_seed_alone_is_accepted():
    lv = with_changes(_beaker(), {"initial.seed": 3})
    assert lv.sim.initial.seed == 3
