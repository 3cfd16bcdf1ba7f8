"""The checks every level shares (:mod:`chainfountain.level.checks`): here the joints'
spring, refused where pymunk's explicit spring diverges."""

from __future__ import annotations

import copy
import math

import pytest

from chainfountain.errors import LevelError
from chainfountain.sim import Simulation, joints
from chainfountain.sim.watchdog import Diverged
from chainfountain.study.changes import with_changes


def _limit(cfg) -> float:
    """The stiffness at omega*h = SPRING_STABILITY for ``cfg``'s links and step."""
    moment = cfg.chain.linear_density * cfg.chain.link_length**3 / 12.0
    h = cfg.solver.dt / cfg.solver.substeps
    return moment * (joints.SPRING_STABILITY / h) ** 2 / 4.0


@pytest.mark.parametrize("name", ["wide_low", "apparatus_fold", "beaker"])
def test_a_spring_beyond_the_stability_limit_is_refused_in_one_line(level, name):
    lvl = level(name)
    c = 1.01 * _limit(lvl.sim)
    with pytest.raises(LevelError) as err:
        with_changes(lvl, {"chain.bending_stiffness": c}, where=name)
    msg = str(err.value)
    assert "chain.bending_stiffness" in msg and "allowed: less than" in msg
    assert "\n" not in msg
    with_changes(lvl, {"chain.bending_stiffness": 0.99 * _limit(lvl.sim)}, where=name)


def _run(cfg, c: float, seconds: float) -> bool:
    """Whether ``cfg`` with the spring ``c`` runs ``seconds`` without diverging."""
    cfg = copy.deepcopy(cfg)
    cfg.chain.bending_stiffness = c
    sim = Simulation(cfg)  # built directly: the level check would refuse the stiff one
    try:
        sim.advance(seconds)
    except Diverged:
        return False
    return True


def test_the_limit_is_where_the_spring_diverges(level):
    """omega*h = 1.8 holds, 2.2 blows up within half a second (wide_low): the limit is
    the explicit spring's, not a margin chosen to pass."""
    cfg = level("wide_low").sim
    c_max = _limit(cfg)
    assert _run(cfg, (0.9**2) * c_max, 0.5)
    assert not _run(cfg, (1.1**2) * c_max, 0.5)
    assert math.isclose(2.0 * math.sqrt(c_max * 12.0 / (cfg.chain.linear_density
                                                         * cfg.chain.link_length**3))
                        * cfg.solver.dt / cfg.solver.substeps, joints.SPRING_STABILITY)
