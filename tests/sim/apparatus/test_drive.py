"""The machine's forces are pymunk springs (``RollerUnit.drive``, the swing damper): a cart's
spring pushes with the cart's force wherever the carriage rolls, and a live change of a
cart, the bearing drag, the fold's brake or the swing damper reaches the springs."""

from __future__ import annotations

import math

import pytest

from chainfountain.sim import Simulation
from chainfountain.sim.apparatus.parts import RollerUnit
from tests import shipped


def _drive_force(unit: RollerUnit) -> float:
    """The force (N) the drive spring puts on the carriage along the unit's direction (the
    pick-up's held back in ``-x``, the fold's pushed on in ``+x``): a spring pushing the
    wrong way reads negative."""
    s = unit.drive
    a = s.a.local_to_world(s.anchor_a)
    b = unit.carriage.local_to_world(s.anchor_b)
    dist = math.hypot(b.x - a.x, b.y - a.y)
    push = s.stiffness * (s.rest_length - dist)  # > 0 pushes the carriage away from a
    return push * (b.x - a.x) / dist * unit.direction


def test_a_cart_spring_pushes_with_the_cart_force_wherever_the_carriage_rolls(level) -> None:
    sim = Simulation(level("apparatus_special").sim)
    for unit in (sim.apparatus.upper, sim.apparatus.lower):
        f0 = unit.cart.mass * 9.81 * math.sin(unit.cart.incline)
        assert _drive_force(unit) == pytest.approx(f0, abs=1e-9)
        x = unit.carriage.position
        unit.carriage.position = (x.x + 30.0 * unit.direction, x.y)  # 30 m on: a long table
        assert _drive_force(unit) == pytest.approx(f0, abs=5e-5)  # 0.01 g of cart


def test_live_changes_reach_the_springs(level) -> None:
    sim = Simulation(level("apparatus_special").sim)
    app = sim.apparatus
    sim.set_param("carts[1].mass", 0.056)
    assert _drive_force(app.lower) == pytest.approx(0.056 * 9.81 * 0.5, abs=1e-9)
    sim.set_param("apparatus.bearing_drag", 0.002)
    assert app.upper.drive.damping == app.lower.drive.damping == 0.002
    assert _drive_force(app.lower) == pytest.approx(0.056 * 9.81 * 0.5, abs=1e-9)
    sim.set_param("apparatus.swing_damper", 1.5)
    assert app.swing_spring is not None and app.swing_spring.damping == 1.5


def test_the_fold_brake_acts_on_the_folding_roller_alone() -> None:
    """``apparatus.fold_brake`` adds to the lower carriage's damper only, built and live,
    and leaves the cart's force as it is."""
    from chainfountain.study.changes import with_changes

    level = with_changes(shipped.level("apparatus_special"),
                         {"apparatus.bearing_drag": 0.002, "apparatus.fold_brake": 0.5})
    app = Simulation(level.sim).apparatus
    assert app.upper.drive.damping == 0.002
    assert app.lower.drive.damping == pytest.approx(0.502, abs=1e-15)
    sim = Simulation(shipped.level("apparatus_special").sim)
    sim.set_param("apparatus.fold_brake", 1.0)
    app = sim.apparatus
    assert app.upper.drive.damping == 0.0 and app.lower.drive.damping == 1.0
    assert _drive_force(app.lower) == pytest.approx(app.lower.force, abs=1e-9)


def test_the_fold_brake_is_refused_where_there_is_no_folding_roller(level) -> None:
    from chainfountain.level.model import LevelError
    from chainfountain.study.changes import with_changes

    with pytest.raises(LevelError, match=r"apparatus\.fold_brake.*allowed: 0"):
        with_changes(level("apparatus_floor"), {"apparatus.fold_brake": 1.0})


def test_the_swing_damper_axis_is_horizontal(level) -> None:
    """The damper's axis runs from the upper carriage to an anchor 1 km behind the lower
    one, so it damps the carriages' relative speed along ``x`` (to 1 mrad), not the
    height between their tracks."""
    sim = Simulation(level("apparatus_special").sim)
    app = sim.apparatus
    s = app.swing_spring
    up, lo = app.upper.carriage, app.lower.carriage
    a = up.local_to_world(s.anchor_a)
    b = lo.local_to_world(s.anchor_b)
    n = ((b.x - a.x), (b.y - a.y))
    assert abs(n[1]) / abs(n[0]) < 1e-3  # the axis is horizontal to 1 mrad
