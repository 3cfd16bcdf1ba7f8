"""The level kinds' registry (:mod:`chainfountain.sim.kinds`): every level file's kind
table has its kinds, every shipped level one kind, and nothing outside the registry asks
which kind a level is."""

import dataclasses
import re
import typing
from pathlib import Path

import pytest

import chainfountain
from chainfountain.level import io, library
from chainfountain.sim.config import KINDS, FeedConfig, SimConfig
from chainfountain.sim.kinds import REGISTRY, kind_of

PACKAGE = Path(chainfountain.__file__).parent
SHIPPED = sorted(p.stem for p in library.shipped_dir().glob("*.toml"))


def test_every_table_has_a_kind_and_every_kind_its_table_s_config():
    assert {k.table for k in REGISTRY.values()} == set(KINDS)
    hints = typing.get_type_hints(SimConfig)
    for kind in REGISTRY.values():
        assert hints[kind.table] is kind.config, kind.name
        assert kind.name in REGISTRY and REGISTRY[kind.name] is kind


def test_a_fed_level_s_drive_picks_its_kind():
    assert kind_of(SimConfig()).name == "feed"
    for drive in ("ideal_floor", "ideal_fold", "ideal_open"):
        cfg = dataclasses.replace(SimConfig(), feed=FeedConfig(drive=drive))
        assert kind_of(cfg).name == "ideal"
    with pytest.raises(ValueError, match="supported: 'apparatus', 'beaker', 'feed', 'scene'"):
        kind_of(dataclasses.replace(SimConfig(), kind="piano"))


@pytest.mark.parametrize("name", SHIPPED)
def test_every_shipped_level_has_a_kind_that_runs_it(name):
    lvl = io.load(library.resolve(name))
    kind = kind_of(lvl.sim)
    assert kind.default_duration(lvl.sim) > 0
    assert (kind.build is not None) == kind.fountain
    assert kind.style(lvl.sim)  # the window's defaults key
    v, size = kind.reach(lvl.sim)
    assert v >= 0 and size >= 0


def test_checks_never_change_a_level():
    for name in SHIPPED:
        lvl = io.load(library.resolve(name))
        before = io.dumps(lvl)
        kind_of(lvl.sim).check(lvl.sim, name)
        assert io.dumps(lvl) == before, name


# a level kind named in a comparison: `cfg.kind == "feed"`, `kind != "apparatus"`, ...
KIND_TEST = re.compile(r"""(\bsim|cfg|config|level\.sim|\.sim)\.kind\s*(==|!=|in\b)|"""
                       r"""\bkind\s*(==|!=)\s*["'](feed|apparatus|beaker|scene)["']""")


def test_only_the_registry_asks_which_kind_a_level_is():
    offenders = []
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE).as_posix()
        if rel.startswith("sim/kinds/"):
            continue
        for n, line in enumerate(path.read_text().splitlines(), 1):
            if KIND_TEST.search(line.split("#", 1)[0]):
                offenders.append(f"{rel}:{n}: {line.strip()}")
    assert not offenders, "\n".join(offenders)
