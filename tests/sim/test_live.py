"""Every field declared ``live`` in the config can be changed on a running simulation of
each kind that uses it, through one table (:mod:`chainfountain.sim.live`)."""

import copy
import dataclasses

import pytest

from chainfountain.fields import get_value
from chainfountain.level import io, library
from chainfountain.sim import Simulation, live
from chainfountain.sim.config import CartConfig, RollerConfig, SimConfig
from chainfountain.sim.kinds import REGISTRY


def _live_paths(cls, prefix=""):
    for f in dataclasses.fields(cls):
        sub = f.default_factory if f.default_factory is not dataclasses.MISSING else None
        if sub is not None and isinstance(sub, type) and dataclasses.is_dataclass(sub):
            yield from _live_paths(sub, prefix + f.name + ".")
        elif f.metadata.get("live"):
            yield prefix + f.name


DECLARED = sorted(set(_live_paths(SimConfig)) | {f"carts[].{p}" for p in _live_paths(CartConfig)}
                  | {f"rollers[].{p}" for p in _live_paths(RollerConfig)})
"""Every field whose ``param(live=True)`` says it is live."""


def _value(path):
    return {"feed.speed": 5.5, "solver.iterations": 12}.get(path, 0.3)


def _motor() -> SimConfig:
    return SimConfig(rollers=(RollerConfig(x=5.0, y=5.0),))


def _config(kind: str) -> SimConfig:
    name = {"ideal": "ideal_fold", "apparatus": "apparatus_fold"}.get(kind)
    return _motor() if name is None else copy.deepcopy(io.load(library.resolve(name)).sim)


def test_the_table_is_what_the_fields_declare():
    tables = set(live.COMMON)
    for kind in REGISTRY.values():
        tables |= set(kind.live)
    assert tables == set(DECLARED)


CASES = [(kind, path) for kind in ("feed", "ideal", "apparatus")
         for path in sorted(set(live.COMMON) | set(REGISTRY[kind].live))
         if not (path.startswith("rollers[]") and kind != "feed")]


@pytest.mark.parametrize(("kind", "path"), CASES)
def test_live_fields_apply_without_rebuild(kind, path):
    sim = Simulation(_config(kind))
    sim.advance(0.01)
    steps = sim.steps
    concrete = path.replace("[]", "[0]")
    written = sim.set_param(concrete, _value(path))
    assert written[concrete] == pytest.approx(_value(path))
    assert get_value(sim.config, concrete) == pytest.approx(_value(path))
    assert sim.steps == steps  # not rebuilt
    sim.advance(0.01)


def test_another_kinds_field_needs_a_rebuild():
    sim = Simulation(_motor())
    for path in ("feed.xi2", "apparatus.bearing_drag", "carts[0].mass", "chain.link_length"):
        with pytest.raises(KeyError, match="cannot be changed while running"):
            sim.set_param(path, 0.1)
    assert sim.config.feed.xi2 == SimConfig().feed.xi2  # nothing was written


def test_the_full_machine_s_upper_cart_follows_once():
    cfg = _config("ideal")  # made loss-free and balanced: it keeps any speed
    cfg.feed.bearing_drag = 0.0
    cfg.feed.cart_force = live.plan(cfg, "feed.bearing_drag", 0.0)["feed.cart_force"]
    changes = live.plan(cfg, "feed.xi2", 0.3)
    assert set(changes) == {"feed.xi2", "feed.cart_force"}
    assert cfg.feed.xi2 != 0.3  # planning changes nothing
    sim = Simulation(cfg)
    assert sim.set_param("feed.xi2", 0.3) == changes
    assert sim.config.feed.cart_force == changes["feed.cart_force"]


def test_carts_are_rebuilt_in_a_fed_level():
    cfg = dataclasses.replace(_motor(), carts=(CartConfig(x=1.0, y=-0.5),))
    with pytest.raises(KeyError):
        Simulation(cfg).set_param("carts[0].mass", 0.5)
