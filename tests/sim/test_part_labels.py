"""The machine's parts are named in the paper's words where they are (the window writes
them beside the apparatus)."""

from __future__ import annotations

import pytest

from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim import Simulation

LEVELS = shipped_dir()


@pytest.fixture(scope="module")
def special() -> Simulation:
    return Simulation(io.load(LEVELS / "apparatus_special.toml").sim)


def test_every_part_of_the_full_machine_is_named(special) -> None:
    texts = [lb.text for lb in special.part_labels()]
    for part in ("pick-up roller", "folding roller", "upper table (beaker)",
                 "lower table (bottom)", "upper cart 17.5 g", "lower cart 58 g",
                 "guide up xi2*H = 0.25 m", "end guide up xi3*H = 0.25 m"):
        assert part in texts


def test_labels_sit_on_their_parts(special) -> None:
    labels = {lb.text: lb for lb in special.part_labels()}
    (x0, y0, r, _), (x1, y1, _, _) = special.roller_geometry()
    assert labels["pick-up roller"].x == pytest.approx(x0)
    assert labels["folding roller"].y == pytest.approx(y1 + r)
    for rope, name in zip(special.rope_geometry(), ("upper cart", "lower cart"), strict=True):
        lb = next(v for k, v in labels.items() if k.startswith(name))
        assert (lb.x, lb.y) == pytest.approx(tuple(rope[-1]))  # the rope ends at the cart


def test_a_cart_changed_live_is_named_with_its_new_mass(special) -> None:
    special.set_param("carts[1].mass", 0.06)
    assert "lower cart 60 g" in [lb.text for lb in special.part_labels()]


def test_other_kinds_have_no_machine_labels() -> None:
    assert Simulation(io.load(LEVELS / "classroom.toml").sim).part_labels() == []
