"""Level files: round trip, validation messages, shipped levels, generated docs."""

import dataclasses
import re
import subprocess
import sys
from pathlib import Path

import pytest

from chainfountain.level import io, library, paths
from chainfountain.level.model import LevelError
from tests import shipped

ROOT = Path(__file__).resolve().parents[2]
LEVELS = shipped.PATHS


def test_round_trip_exact(tmp_path):
    sim = io.make_level("x", "y").sim
    sim = dataclasses.replace(sim, chain=dataclasses.replace(sim.chain, link_length=0.0123456789))
    lvl = io.make_level("x", "a description", sim)
    p = io.save(lvl, tmp_path / "x.toml")
    back = io.load(p)
    assert back == lvl
    assert io.dumps(back) == p.read_text()


@pytest.mark.parametrize("path", LEVELS, ids=[p.stem for p in LEVELS])
def test_shipped_levels_load_and_round_trip(path):
    lvl = io.load(path)
    assert lvl.meta.description.strip(), "every shipped level says what the user should see"
    assert io.loads(io.dumps(lvl)) == lvl


@pytest.mark.parametrize("path", LEVELS, ids=[p.stem for p in LEVELS])
def test_shipped_level_files_show_the_settings_they_run(path):
    """A level with ``solver.accuracy`` writes the settings the error model chooses for it,
    so that what its file (and its description) says is what runs."""
    import tomllib

    raw = tomllib.loads(path.read_text())
    if raw.get("solver", {}).get("accuracy", 0.0) == 0.0:
        return
    sim = io.load(path).sim
    assert raw["chain"]["link_length"] == sim.chain.link_length
    assert raw["solver"]["dt"] == sim.solver.dt
    assert raw["solver"]["iterations"] == sim.solver.iterations


BAD = [
    ("link_length", "link_length = -0.02", "chain.link_length", "-0.02"),
    ("link_length", "link_length = nan", "chain.link_length", "nan"),
    ("link_length", 'link_length = "short"', "chain.link_length", "'short'"),
    ("linear_density", "linear_density = 0.0", "chain.linear_density", "0.0"),
    ("iterations", "iterations = 4.5", "solver.iterations", "4.5"),
    ("floor", "floor = \"lava\"", "feed.floor", "'lava'"),
    ("speed", "sped = 5.0", "feed.sped", "unknown key"),
    ("speed", "speed = 1.0", "feed.speed", "sqrt(g*H)"),
    ("self_collision", "self_collision = 1", "chain.self_collision", "1"),
    ("schema_version", "schema_version = 7", "schema_version", "7"),
    ("name", "", "meta.name", "missing"),
]


def _replace_key(text: str, key: str, new: str) -> str:
    """Replace the first line that sets ``key`` (whatever its default value is)."""
    out, n = re.subn(rf"^{key} = .*$", new, text, count=1, flags=re.M)
    assert n == 1, key
    return out


@pytest.mark.parametrize("key, new, field, shown", BAD, ids=[b[2] + ":" + b[1][:12] for b in BAD])
def test_bad_files_one_clear_line(tmp_path, key, new, field, shown):
    text = io.dumps(io.make_level("t", "d"))
    bad = tmp_path / "bad.toml"
    bad.write_text(_replace_key(text, key, new))
    with pytest.raises(io.LevelError) as exc:
        io.load(bad)
    msg = str(exc.value)
    assert str(bad) in msg and field in msg and shown in msg
    assert "\n" not in msg


def test_not_toml(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(io.dumps(io.make_level("t", "d")).replace("[chain]", "[chain\n", 1))
    with pytest.raises(io.LevelError, match=r"bad.toml: not valid TOML \(.*line"):
        io.load(bad)


def test_check_command(tmp_path):
    good = io.save(io.make_level("t", "d"), tmp_path / "good.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text(_replace_key(good.read_text(), "dt", "dt = -1.0"))
    ok = subprocess.run([sys.executable, "-m", "chainfountain", "check", str(good)],
                        capture_output=True, text=True, timeout=60)
    assert ok.returncode == 0 and "ok" in ok.stdout
    fail = subprocess.run([sys.executable, "-m", "chainfountain", "check", str(good), str(bad)],
                          capture_output=True, text=True, timeout=60)
    assert fail.returncode != 0
    assert "Traceback" not in fail.stderr
    assert fail.stderr.count("\n") == 1 and "solver.dt" in fail.stderr


def test_missing_file_message(tmp_path):
    with pytest.raises(io.LevelError, match="no such file"):
        io.load(tmp_path / "nope.toml")


def test_save_refuses_bad_level_and_keeps_old_file(tmp_path):
    lvl = io.make_level("t", "d")
    p = io.save(lvl, tmp_path / "l.toml")
    before = p.read_text()
    bad_sim = dataclasses.replace(lvl.sim, feed=dataclasses.replace(lvl.sim.feed, speed=0.5))
    with pytest.raises(io.LevelError):
        io.save(io.Level(meta=lvl.meta, sim=bad_sim), p)
    assert p.read_text() == before
    assert [x.name for x in tmp_path.iterdir()] == ["l.toml"]


def test_docs_levels_md_is_current():
    assert (ROOT / "docs" / "levels.md").read_text() == io.schema_markdown(), (
        "regenerate with: chainfountain schema --out docs/levels.md"
    )


def test_level_name_resolves_even_if_a_folder_has_that_name(tmp_path, monkeypatch):

    monkeypatch.chdir(tmp_path)
    (tmp_path / "classroom").mkdir()  # e.g. an output folder from an earlier run
    assert library.resolve("classroom") == library.shipped_dir() / "classroom.toml"
    with pytest.raises(io.LevelError, match="known levels"):
        library.resolve("no_such_level")


APPARATUS_BAD = [  # (key, new line, field, shown, allowed) in a copy of apparatus_special
    ("jitter", "jitter = 0.01", "initial.jitter", "0.01", "allowed: 0.001"),
    ("mode", 'mode = "stub"', "apparatus.fold_roller", "'contact'",
     "allowed: fold_roller = 'gripped'"),
    ("variant", 'variant = "open"', "apparatus.swing_damper", "0.5", "allowed: 0"),
    ("fold_clearance", "fold_clearance = 0.02", "apparatus.fold_clearance", "0.02", "[0, 0.005]"),
    ("plate", 'plate = "contact"', "apparatus.upper_guide", "'joints'", "allowed: 'walls'"),
    ("upper_guide", 'upper_guide = "pipes"', "apparatus.upper_guide", "'pipes'",
     "'walls', 'joints'"),
]


@pytest.mark.parametrize("key, new, field, shown, allowed", APPARATUS_BAD,
                         ids=[b[2] + ":" + b[1] for b in APPARATUS_BAD])
def test_apparatus_bad_files_one_clear_line(tmp_path, key, new, field, shown, allowed):
    """The apparatus lays its own chain, so ``[initial]`` settings would be silently
    ignored there: they are refused instead; ``fold_clearance`` and ``upper_guide = "joints"``
    only where they apply, the swing damper only in 'fold'."""
    text = shipped.path("apparatus_special").read_text()
    if key == "fold_clearance":  # the preset leaves it at its default, 0
        text = _replace_key(text, "plate_links", "plate_links = 20\nfold_clearance = 0.002")
    if key in ("plate", "upper_guide"):  # no treadmill: a contact plate may have none
        assert 'upper_guide = "joints"' in text  # the preset's
        text = _replace_key(text, "plate_links", "plate_links = 0")
    bad = tmp_path / "bad.toml"
    bad.write_text(_replace_key(text, key, new))
    with pytest.raises(io.LevelError) as exc:
        io.load(bad)
    msg = str(exc.value)
    assert f"{field}: {shown}" in msg and allowed in msg and "\n" not in msg


def test_a_change_of_a_field_the_accuracy_chooses_takes_it_over():
    """``classroom`` has ``solver.accuracy``: a change of its link length or step (a
    sweep's grid, ``FIELD=VALUE``) is run as given with the accuracy off, instead of being
    chosen again (a sweep over ``chain.link_length`` ran every point at the accuracy's
    5 cm); the same value keeps the accuracy; both at once are refused in one line."""
    from chainfountain.study import with_changes

    lvl = shipped.level("classroom")
    acc, own = lvl.sim.solver.accuracy, lvl.sim.chain.link_length
    assert acc > 0
    for path, value in (("chain.link_length", own / 2), ("solver.dt", 1e-4),
                        ("solver.iterations", 30)):
        changed = with_changes(lvl, {path: value})
        assert changed.sim.solver.accuracy == 0.0
        assert paths.get(changed, path) == value, path
    assert with_changes(lvl, {"chain.link_length": own}).sim.solver.accuracy == acc
    assert with_changes(lvl, {"feed.speed": 6.5}).sim.solver.accuracy == acc
    # the base's link length, where the change of speed has the accuracy choose another
    faster = with_changes(lvl, {"feed.speed": 6.0})
    assert faster.sim.chain.link_length != own
    both = with_changes(lvl, {"feed.speed": 6.0, "chain.link_length": own})
    assert both.sim.chain.link_length == own and both.sim.solver.accuracy == 0.0
    with pytest.raises(LevelError, match=r"^change: chain\.link_length: 0\.01 together with "
                       r"solver\.accuracy = 0\.01, which chooses 0\.05; allowed: one of them"):
        with_changes(lvl, {"chain.link_length": 0.01, "solver.accuracy": 0.01})
    # an accuracy set by the change itself on a level without one
    manual = with_changes(lvl, {"solver.accuracy": 0.0})
    with pytest.raises(LevelError, match=r"^change: solver\.dt: 0\.0001 together with "
                       r"solver\.accuracy = 0\.005, which chooses 0\.00025"):
        with_changes(manual, {"solver.accuracy": 0.005, "solver.dt": 1e-4})
