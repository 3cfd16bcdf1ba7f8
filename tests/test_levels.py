"""Level files: round trip, validation messages, shipped levels, generated docs."""

import dataclasses
import subprocess
import sys
from pathlib import Path

import pytest

from chainfountain.level import io

ROOT = Path(__file__).resolve().parents[1]
LEVELS = sorted((ROOT / "levels").glob("*.toml"))


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


BAD = [
    ("link_length = 0.02", "link_length = -0.02", "chain.link_length", "-0.02"),
    ("link_length = 0.02", "link_length = nan", "chain.link_length", "nan"),
    ("link_length = 0.02", 'link_length = "short"', "chain.link_length", "'short'"),
    ("linear_density = 0.05", "linear_density = 0.0", "chain.linear_density", "0.0"),
    ("iterations = 40", "iterations = 4.5", "solver.iterations", "4.5"),
    ("floor = \"absorbing\"", "floor = \"lava\"", "feed.floor", "'lava'"),
    ("speed = 5.0", "sped = 5.0", "feed.sped", "unknown key"),
    ("speed = 5.0", "speed = 1.0", "feed.speed", "sqrt(g*H)"),
    ("self_collision = false", "self_collision = 1", "chain.self_collision", "1"),
    ("schema_version = 1", "schema_version = 7", "schema_version", "7"),
    ('name = "t"', "", "meta.name", "missing"),
    ("[chain]", "[chain\n", "not valid TOML", "line"),
]


@pytest.mark.parametrize("old, new, field, shown", BAD, ids=[b[2] + ":" + b[1][:12] for b in BAD])
def test_bad_files_one_clear_line(tmp_path, old, new, field, shown):
    text = io.dumps(io.make_level("t", "d"))
    assert old in text
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace(old, new, 1))
    with pytest.raises(io.LevelError) as exc:
        io.load(bad)
    msg = str(exc.value)
    assert str(bad) in msg and field in msg and shown in msg
    assert "\n" not in msg


def test_check_command(tmp_path):
    good = io.save(io.make_level("t", "d"), tmp_path / "good.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text(good.read_text().replace("dt = 0.0005", "dt = -1.0"))
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
