"""The full machine with a gripped folding roller and a brake on it (``apparatus_fold_gripped``):
its speed is selected and converged in the step.

The paper's machine is balanced at every speed, so it keeps whatever speed it drifts to;
a brake on the folding roller's carriage (``apparatus.fold_brake`` c, a force ``-c*u``)
makes the balance hold at one speed, set by the lower cart's push beyond it. Asserted on
the preset (treadmills, swing damper, 100-mm gripped folding roller, brake
1 N s/m, the end guide following the landing), laid on its path at 3 m/s, means over
2-5 s (10-ms samples):

- at half the pymunk step (0.25 ms) the speed is the same within 1 % (the issue's
  target): 3.0016 / 3.0210 m/s (+0.65 %; nudged starts +0.50 and +0.65 %; over 600 s from
  rest +0.87 %); the special case built this way, ``apparatus_special_gripped``
  (19 / 328 g): 2.9847 / 2.9982 m/s (+0.45 %; nudged +0.50 and +0.52 %; 600 s: +0.71 %);
- the lower cart sets the speed: 5 g more or less (0.0245 N) moves it by +0.040 / -0.040
  m/s, together 0.82 of the paper's ``4*dF/c`` (0.80-0.81 from three nudged starts;
  0.64-0.65 from two starts with the end guide fixed; the paper's laws with the brake,
  :func:`~chainfountain.sim.apparatus.laws.braked_fold_speed`; docs/apparatus.md),
  asserted within 0.5-0.85;
- a cart that takes the fountain out of the end guide's catch ends the run within
  :data:`~chainfountain.sim.apparatus.tuning.CATCH_STOP` of the last link caught (or
  sooner, once the chain runs away, :data:`~chainfountain.sim.apparatus.tuning.RUNAWAY`),
  with one plain sentence naming the cart (a 360 g lower cart).

docs/apparatus.md, "The gripped folding roller".
"""

from __future__ import annotations

import math

import pytest

from chainfountain.errors import RunEnded
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus.laws import braked_fold_speed
from chainfountain.sim.apparatus.tuning import CATCH_STOP
from chainfountain.sim.apparatus_report import report
from chainfountain.study.changes import laid_on_path, with_changes
from tests import shipped

WINDOW = (2.0, 5.0)
pytestmark = [pytest.mark.slow, pytest.mark.xdist_group("apparatus_braked")]


def _speed(name: str, changes: dict) -> float:
    """Mean chain speed (m/s) over :data:`WINDOW` of preset ``name`` with ``changes``."""
    level = with_changes(laid_on_path(shipped.level(name)), changes)
    sim = Simulation(level.sim)
    rec = Recorder(sim, profiles=False)
    sim.advance(WINDOW[1])
    return report(sim, rec, *WINDOW)["measured"]["v"]


@pytest.mark.parametrize("name", ["apparatus_fold_gripped", "apparatus_special_gripped"])
def test_the_speed_is_the_same_at_half_the_step(level, name: str) -> None:
    dt = level(name).sim.solver.dt
    v, v_half = _speed(name, {}), _speed(name, {"solver.dt": 0.5 * dt})
    assert v == pytest.approx(3.0, rel=0.02)  # built for 3 m/s
    assert v_half == pytest.approx(v, rel=0.01)


def test_the_lower_cart_sets_the_speed(level) -> None:
    name = "apparatus_fold_gripped"
    base = level(name).sim
    m, cart = base.carts[1].mass, base.carts[1]
    dm = 0.005
    fast = _speed(name, {"carts[1].mass": m + dm})
    slow = _speed(name, {"carts[1].mass": m - dm})
    dF = dm * base.gravity * math.sin(cart.incline)
    paper = 4.0 * dF / base.apparatus.fold_brake  # 2*dF/c each way
    lvl = with_changes(level(name), {"carts[1].mass": m + dm})
    assert braked_fold_speed(lvl.sim) - braked_fold_speed(base) == pytest.approx(
        0.5 * paper, rel=1e-9)
    assert 0.5 <= (fast - slow) / paper <= 0.85


def test_a_lost_catch_ends_the_run_in_one_sentence() -> None:
    # laid first: from rest, the region refuses this cart before it runs
    level = with_changes(laid_on_path(shipped.level("apparatus_fold_gripped")),
                         {"carts[1].mass": 0.36})
    sim = Simulation(level.sim)
    with pytest.raises(RunEnded) as err:
        sim.advance(6.0)
    app = sim.apparatus
    # it ends on the lost catch or, sooner, on the chain running away (tuning.RUNAWAY)
    assert 0.0 < sim.time - app.last_mouth_entry <= CATCH_STOP + 0.01
    plain = err.value.plain
    assert plain.startswith("At ") and "lighter lower cart" in plain
    assert "\n" not in plain
