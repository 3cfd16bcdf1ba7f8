"""The notebook-style page ``docs/python.md`` runs: its Python blocks, in order, in one
namespace, in a fresh folder (what it shows is what the code does); and the Python API
checks its arguments with the command line's messages and leaves nothing on disk."""

from __future__ import annotations

import math
import re
import tempfile
from pathlib import Path

import pytest

import chainfountain
from chainfountain.errors import UserError

DOC = Path(__file__).resolve().parents[2] / "docs" / "python.md"


def test_the_python_page_runs(tmp_path, monkeypatch, capsys):
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(), flags=re.S)
    assert len(blocks) >= 4
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    for block in blocks:
        exec(compile(block, str(DOC), "exec"), namespace)  # noqa: S102 - the page's code
    out = capsys.readouterr().out
    # what the page says these print
    assert "duration: -1 is out of range; allowed: a duration in s > 0 and <= 3600" in out
    assert "seed: -3 is out of range; allowed: a seed >= 0" in out
    assert "changes: feed.speed: 'fast' is not allowed; allowed: a number in [0, 30]" in out
    assert "chain.link_length: cannot change while the level runs" in out
    assert (tmp_path / "runs" / "stepped" / "summary.json").is_file()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["runs"]


@pytest.mark.parametrize("kwargs, words", [
    ({"duration": -1}, ["duration", "-1", "> 0 and <= 3600"]),
    ({"duration": 0}, ["duration", "0 is out of range"]),
    ({"duration": math.nan}, ["duration", "nan is out of range"]),
    ({"duration": "5"}, ["duration", "'5' is not a number"]),
    ({"seed": -3}, ["seed", "-3 is out of range", "a seed >= 0"]),
    ({"seed": 1.5}, ["seed", "not a whole number"]),
    ({"changes": ["feed.speed"]}, ["changes", "a mapping"]),
    ({"changes": {"feed.speed": 1.0}}, ["feed.speed", "cannot make a fountain"]),
    ({"progress": "yes"}, ["progress", "True or False"]),
    ({"out": 3}, ["out", "a folder"]),
])
def test_the_api_refuses_bad_arguments_in_one_line_before_running(kwargs, words, tmp_path,
                                                                  monkeypatch):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))  # this test's temporary folders
    with pytest.raises(UserError) as exc:
        chainfountain.run("wide_low", **kwargs)
    msg = str(exc.value)
    assert "\n" not in msg
    for w in words:
        assert w in msg, (w, msg)
    with pytest.raises(UserError):
        chainfountain.start("wide_low", **{k: v for k, v in kwargs.items()
                                           if k in ("seed", "changes", "duration")}
                            or {"seed": -1})
    assert list(tmp_path.iterdir()) == []


def test_the_api_and_the_command_line_say_the_same(tmp_path):
    import subprocess
    import sys

    r = subprocess.run([sys.executable, "-m", "chainfountain", "run", "wide_low",
                        "--duration", "nan"], capture_output=True, text=True, timeout=120)
    with pytest.raises(UserError) as exc:
        chainfountain.run("wide_low", duration=math.nan)
    cli = r.stderr.strip().split("argument --duration: ", 1)[1].removesuffix(" (see --help)")
    assert str(exc.value) == f"duration: {cli}"


def test_a_run_without_out_leaves_no_folder_behind(tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))  # this test's temporary folders
    r = chainfountain.run("wide_low", duration=0.2)
    assert r.ok and r.out_dir is None and r.paths == {} and len(r.series["t"]) > 5
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(UserError, match="a level name"):
        chainfountain.run(42)
