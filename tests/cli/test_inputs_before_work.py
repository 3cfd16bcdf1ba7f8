"""Input a command can check before it works is checked before it works: every output
path of every command, the FIELD=VALUE overrides of ``run``, the run's options against
the level; ``check`` says what is wrong with each file; ``levels`` lists what is
installed."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests import shipped


def _cli(*args: str, cwd: Path, env: dict | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "chainfountain", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300)


SWEEP = 'base = "wide_low"\nduration = 0.2\n[grid]\n"feed.speed" = [4.0]\n'


@pytest.mark.parametrize("bad", [pytest.param("/proc/x", marks=pytest.mark.slow), "afile/x"])
@pytest.mark.parametrize("args, flag", [
    (["converge", "wide_low", "--json", "{}.json"], "--json"),
    (["run", "wide_low", "--out", "{}"], "--out"),
    (["run", "wide_low", "--error-bars", "--out", "{}"], "--out"),
    (["sweep", "s.toml", "--out", "{}"], "--out"),
    (["figures", "--out", "{}"], "--out"),
    (["schema", "--out", "{}.md"], "--out"),
    (["design", "--l", "1", "--h", "0.6", "--H", "1", "--v", "4.25", "--out", "{}.toml"],
     "--out"),
    (["play", "wide_low", "--frames", "1", "--screenshot", "{}.png"], "--screenshot"),
])
def test_every_output_path_is_checked_before_any_work(tmp_path, args, flag, bad):
    """``converge LEVEL --json /proc/x.json`` ran both refinements, then raised; every
    command now refuses an output it cannot write at once, in one line naming the flag,
    and runs nothing (no progress line, no output written)."""
    (tmp_path / "afile").write_text("a file, not a folder\n")
    (tmp_path / "s.toml").write_text(SWEEP)
    r = _cli(*[a.replace("{}", bad) for a in args], cwd=tmp_path)
    assert r.returncode == 2, (r.returncode, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in r.stderr, r.stderr
    assert flag in lines[0] and bad in lines[0], lines[0]
    assert not r.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile", "s.toml"]


def test_run_takes_field_overrides_checked_as_a_level_file(tmp_path, capsys, monkeypatch):
    from chainfountain.cli import main

    def _cli(*args: str, cwd: Path) -> subprocess.CompletedProcess:  # in this process
        monkeypatch.chdir(cwd)
        capsys.readouterr()
        try:
            status = main(list(args))
        except SystemExit as exc:  # argparse's refusals
            status = exc.code
        out = capsys.readouterr()
        return subprocess.CompletedProcess(args, status, out.out, out.err)

    r = _cli("run", "falling_chain", "--duration", "0.06", "scene.closed_form=none",
             "scene.pins[0].release=0.02", "--quiet", "--out", "o", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    import json

    s = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert s["probes"]["fixed_end"]["columns"]["F"]["final"] == 0.0  # the pin let go
    for args, words in [
        (["feed.speed=x"], ["FIELD=VALUE", "feed.speed", "'x' is not a value", "a number"]),
        (["feed.speed=1"], ["feed.speed", "cannot make a fountain"]),
        (["feed.sped=5"], ["feed.sped", "unknown key"]),
        (["rollers[1].radius=0.1"], ["rollers[1].radius", "has 0 rollers"]),
        (["feed.speed"], ["has no '='"]),
        (["--seed", "-3"], ["--seed", "-3", "a seed >= 0"]),
        (["recording.sample_interval=5", "--duration", "3"],
         ["--duration", "3 s is shorter than", "recording.sample_interval (5 s)"]),
    ]:
        r = _cli("run", "wide_low", *args, cwd=tmp_path)
        assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
        assert len(r.stderr.strip().splitlines()) == 1, r.stderr
        for w in words:
            assert w in r.stderr, (w, r.stderr)
    r = _cli("run", "falling_chain", "recording.sample_interval=1", cwd=tmp_path)  # 0.4-s run
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert "recording.sample_interval: 1 s is longer than the run (0.4 s)" in r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o"]


def test_check_reports_every_bad_file(tmp_path):
    wide = shipped.path("wide_low").read_text()
    (tmp_path / "bom.toml").write_bytes(b"\xef\xbb\xbf" + wide.encode())
    (tmp_path / "noname.toml").write_text(
        "\n".join(x for x in wide.splitlines() if not x.startswith("name = ")))
    (tmp_path / "bad.toml").write_text(wide.replace("speed = ", "speed = -"))
    r = _cli("check", "bom.toml", "noname.toml", "bad.toml", "nope.toml", cwd=tmp_path)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert r.stdout.strip() == "bom.toml: ok (feed: wide_low)"  # a byte-order mark is fine
    err = r.stderr.strip().splitlines()
    assert len(err) == 3, err
    assert err[0] == "chainfountain: error: noname.toml: meta.name: missing; required, a text " \
        "string"
    assert "bad.toml: feed.speed" in err[1] and "nope.toml: no such file" in err[2]


def test_levels_lists_what_is_installed(tmp_path):
    import os

    (tmp_path / "home" / "levels").mkdir(parents=True)
    (tmp_path / "home" / "levels" / "mine.toml").write_text(
        shipped.path("wide_low").read_text())
    r = _cli("levels", cwd=tmp_path, env={**os.environ, "CHAINFOUNTAIN_HOME": str(
        tmp_path / "home")})
    assert r.returncode == 0, r.stderr
    names = [line.split()[0] for line in r.stdout.splitlines()]
    assert names == sorted(p.stem for p in shipped.PATHS) + ["mine"]
    assert "beaker" in names and "scene" in r.stdout and "shipped" in r.stdout
    assert r.stdout.splitlines()[-1].split()[1:3] == ["feed", "yours"]
