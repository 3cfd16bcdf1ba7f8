"""Bad level files never give a traceback or a wrong run (mutants from ``levelfuzz.py``).

Each mutant is either accepted or refused with one line naming the file and a field;
accepted mutants build and run 0.3 s, stopping themselves at most (RunEnded). The
examples are derandomized, so every machine runs the same mutants;
``benchmarks/fuzz_levels.py`` runs ten thousand and more.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, assume, given, settings

from chainfountain.level import io
from tests.level import levelfuzz as lf

SETTINGS = settings(derandomize=True, database=None, deadline=None,
                    suppress_health_check=list(HealthCheck))


@pytest.fixture(scope="module")
def level_file(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("fuzz") / "mutant.toml"


@settings(SETTINGS, max_examples=400)
@given(mutant=lf.mutants())
def test_mutated_levels_are_accepted_or_refused_in_one_line(mutant, level_file):
    how, data = mutant
    lf.check_text(data, level_file)  # raises on any other exception or a bad message


@settings(SETTINGS, max_examples=12)
@given(mutant=lf.near_valid())
def test_accepted_mutants_run_or_stop_themselves(mutant, level_file):
    how, data = mutant
    verdict = lf.check_text(data, level_file)
    assume(verdict.accepted)
    assert verdict.level is not None
    result = lf.run_briefly(verdict.level, 0.3, wall_limit=5.0)
    assert result.status in ("ran", "stopped", "cut"), how
    if verdict.level.sim.kind == "feed":
        from chainfountain.sim import Simulation

        assert Simulation(verdict.level.sim).reference is not None, how


def _classroom(**changes: str) -> str:
    text = lf.SHIPPED["classroom"]
    for key, value in changes.items():
        text, n = re.subn(rf"^{key} = .*$", f"{key} = {value}", text, count=1, flags=re.M)
        assert n == 1, key
    return text


IMPOSSIBLE = [  # (level text, field, words in the message)
    (_classroom(speed="5.0", drop="1.5", end_tension="0.45"), "feed.end_tension",
     ["0.45", "Tbar_E < 1 - k*H = 0.4114", "5.172 m/s"]),
    (_classroom(end_tension="0.2", floor='"solid"', floor_width="20.0"), "feed.end_tension",
     ["0.2", "allowed: 0 with a solid floor"]),
    (_classroom(floor='"solid"'), "feed.floor_width", ["6.0", "allowed: a width > 2*l"]),
    (_classroom(mode='"catenary"', stub_length="0.5"), "initial.stub_length",
     ["0.5", "initial.mode = 'stub'"]),
    (_classroom(gravity="0.02", speed="30.0"), "feed.speed",
     ["30.0", "at most 20000 links"]),
    (_classroom(link_length="0.001", speed="12.0"), "chain.link_length",
     ["0.001", "at most 20000 links"]),
    (_classroom(gravity="0.0"), "gravity", ["0.0", "[0.01, 1000]"]),
    (_classroom(carts="[]\n[apparatus]\nspeed = 4.0"), "apparatus.speed",
     ["has no effect in a 'feed' level"]),
    (_classroom(carts="[{ x = 99.0, y = -99.0 }]"), "carts[0].x", ["outside this level's scene"]),
    (_classroom(speed="1" + "0" * 400), "feed.speed", ["out of range"]),
    (_classroom(chain_length="9" * 5000), "", ["not valid TOML"]),
    (lf.SHIPPED["apparatus_floor"].replace("xi3 = 0.5", "xi3 = 0.7"), "apparatus.xi3",
     ["only 'fold' uses it"]),
    (lf.SHIPPED["apparatus_floor"].replace("rollers = []", "rollers = [{}]"), "rollers",
     ["no effect"]),
    (re.sub(r"^speed = .*$", "speed = 30.0", re.sub(r"^duration = .*$", "duration = 600.0",
            lf.SHIPPED["apparatus_limit"], flags=re.M), flags=re.M),
     "apparatus.duration", ["treadmill"]),
    (re.sub(r"^xi3 = .*$", "xi3 = 6.89e-07", lf.SHIPPED["apparatus_limit"], flags=re.M),
     "apparatus.xi3", ["too little for the end channel", "allowed: 0 or at least"]),
    (lf.SHIPPED["apparatus_fold"].replace("end_tension = 0.17", "end_tension = 0.6"),
     "apparatus.end_tension", ["Tbar_E < 1 - k*H"]),
]


@pytest.mark.parametrize("text, field, words", IMPOSSIBLE,
                         ids=[f"{i}:{c[1] or 'toml'}" for i, c in enumerate(IMPOSSIBLE)])
def test_impossible_combinations_one_clear_line(tmp_path, text, field, words):
    """Levels no fountain can satisfy, or with settings that would have no effect, are
    refused with one line naming the file, the field, the value and what is allowed."""
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(io.LevelError) as exc:
        io.load(path)
    msg = str(exc.value)
    assert "\n" not in msg and msg.startswith(f"{path}: {field}"), msg
    for w in words:
        assert w in msg, (w, msg)
    assert lf.message_problem(msg, str(path)) is None
