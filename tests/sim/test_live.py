"""Every field declared ``live`` in the config can be changed on a running simulation."""

import dataclasses

import pytest

from chainfountain.sim import Simulation
from chainfountain.sim.config import RollerConfig, SimConfig


def _live_paths(cls, prefix=""):
    for f in dataclasses.fields(cls):
        sub = f.default_factory if f.default_factory is not dataclasses.MISSING else None
        if sub is not None and isinstance(sub, type) and dataclasses.is_dataclass(sub):
            yield from _live_paths(sub, prefix + f.name + ".")
        elif f.metadata.get("live"):
            yield prefix + f.name


LIVE = sorted(_live_paths(SimConfig))


def _value(meta_path):
    return {"feed.speed": 5.5, "solver.iterations": 12}.get(meta_path, 0.3)


@pytest.fixture()
def sim():
    return Simulation(SimConfig(rollers=(RollerConfig(x=5.0, y=5.0),)))


@pytest.mark.parametrize("path", LIVE + ["rollers[0].angular_speed"])
def test_live_fields_apply_without_rebuild(sim, path):
    sim.advance(0.01)
    steps = sim.steps
    sim.set_param(path, _value(path))
    obj = sim.config
    for part in path.replace("[", ".").replace("]", "").split("."):
        obj = obj[int(part)] if part.isdigit() else getattr(obj, part)
    assert obj == pytest.approx(_value(path))
    assert sim.steps == steps  # not rebuilt
    sim.advance(0.01)


def test_live_paths_found():
    assert {"feed.speed", "chain.friction", "solver.iterations"} <= set(LIVE)


def test_rebuild_fields_refused(sim):
    with pytest.raises(KeyError, match="cannot be changed while running"):
        sim.set_param("chain.link_length", 0.01)
