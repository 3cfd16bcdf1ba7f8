"""The typed run summary (:mod:`chainfountain.headless.report`), its sections
(:data:`chainfountain.headless.SECTIONS`), the exit statuses' one table
(:mod:`chainfountain.exits`) and the snapshot comparison across renamed keys."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

from chainfountain import exits
from chainfountain.headless import (
    OLD_NAMES,
    SECTIONS,
    RunSummary,
    describe_outputs,
    exit_status,
    run_level,
)
from chainfountain.headless.report import Ended, FountainFigures, Theory
from chainfountain.level import io

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("quick")
    return run_level(io.make_level("quick", "short headless test run"), out, 0.3,
                     progress=False)


def test_summary_json_reads_back_typed_and_writes_the_same(quick_run):
    d = json.loads(quick_run.read_text())
    s = RunSummary.load(quick_run)
    assert isinstance(s.fountain, FountainFigures) and isinstance(s.theory, Theory)
    assert s.fountain.h == d["h"] and s.theory.rel_error.h == d["theory"]["rel_error"]["h"]
    assert s.fountain.v == d["v"] and s.theory.rel_error.v == d["theory"]["rel_error"]["v"]
    assert s.to_json() == d
    assert list(s.sections)[:1] == ["theory"] and "error_model" in s.sections


def test_one_name_per_quantity(quick_run):
    """``h``, ``l``, ``v``, ``q`` once each: no ``vertex``/``end``/``speed_mean``/``q_fit``
    beside them, and the theory and its errors under the same names."""
    d = json.loads(quick_run.read_text())
    for old in ("vertex", "start", "end", "speed_mean", "q_fit"):
        assert old not in d, old
    assert set(d["theory"]["rel_error"]) == {"h", "vertex_x", "l", "q", "v"}
    assert {"h", "vertex_x", "l", "q", "v"} <= set(d["theory"]) <= set(d) | {"rel_error",
                                                                            "abs_error"}


def test_the_terminal_text_comes_from_the_object(quick_run):
    s = RunSummary.load(quick_run)
    text = describe_outputs(quick_run, s)
    assert text == describe_outputs(quick_run)
    assert f"vertex height {s.fountain.h:.4f} m (theory {s.theory.h:.4f}" in text
    s.fountain.h = 1.25
    assert "vertex height 1.2500 m" in describe_outputs(quick_run, s)


def test_a_section_is_one_function_in_the_table(quick_run, monkeypatch):
    """A kind adds its section by one entry of SECTIONS and its name in the kind's
    sections; a failing one is named in analysis_failed and loses nothing else."""
    import dataclasses

    from chainfountain.headless import summary
    from chainfountain.sim.kinds import REGISTRY

    def extra(level, sim, rec, window):
        return {"links_seen": sim.n_links, "window_v": window.speed_mean}

    def broken(level, sim, rec, window):
        raise RuntimeError("no")

    monkeypatch.setitem(summary.SECTIONS, "extra", extra)
    monkeypatch.setitem(summary.SECTIONS, "broken", broken)
    feed = REGISTRY["feed"]
    monkeypatch.setitem(REGISTRY, "feed", dataclasses.replace(
        feed, sections=(*feed.sections, "extra", "broken")))
    out = quick_run.parent / "again"
    s = RunSummary.load(run_level(io.make_level("quick", "t"), out, 0.3, progress=False))
    assert s.sections["extra"]["links_seen"] == s.links
    assert s.sections["extra"]["window_v"] == pytest.approx(s.fountain.v)
    assert s.analysis_failed == {"broken report": "RuntimeError: no"}
    assert "theory" in SECTIONS and s.theory is not None


def test_exit_statuses_from_the_object_and_its_json():
    base = {"level": "x", "kind": "feed", "outputs": [], "write_failed": {}}
    assert exit_status(base) == 0
    assert exit_status({**base, "write_failed": {"speed.csv": "full"}}) == exits.WRITE_FAILED
    s = RunSummary.from_json(base)
    s.ended_early = Ended(t_s=1.0, cause="machine", reason="table used up")
    assert exit_status(s) == 3 == exit_status(s.to_json())
    s.ended_early = Ended(t_s=1.0, cause="interrupted", reason="", signal_number=15)
    assert exit_status(s) == 143
    assert s.to_json()["ended_early"] == {"t_s": 1.0, "cause": "interrupted", "reason": "",
                                          "signal_number": 15}


def test_exit_statuses_are_described_from_one_table(capsys):
    """The README's table and ``run --help`` say what :data:`chainfountain.exits.EXITS`
    says."""
    from chainfountain.cli import main

    assert exits.markdown_table() in (ROOT / "README.md").read_text()
    with pytest.raises(SystemExit):
        main(["run", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    for e in exits.EXITS:
        assert " ".join(f"{e.status} {e.meaning.replace('`', '')}".split()) in help_text


def test_an_old_snapshot_compares_under_the_new_names(capsys):
    spec = importlib.util.spec_from_file_location(
        "summary_snapshot", ROOT / "research" / "summary_snapshot.py")
    snap = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(snap)
    old = {"lvl": {"speed_mean": 3.0, "q_fit": 2.0, "vertex": [0.4, 0.6], "h": 0.6,
                   "start": [0.0, 0.0], "end": [1.1, -2.0], "l": 1.1, "H": 2.0,
                   "theory": {"vertex": [0.5, 0.7], "h": 0.7,
                              "rel_error": {"speed": 0.01, "h": -0.1}}}}
    new = {"lvl": {"v": 3.0, "q": 2.0, "vertex_x": 0.4, "h": 0.6, "l": 1.1, "H": 2.0,
                   "theory": {"vertex_x": 0.5, "h": 0.7,
                              "rel_error": {"v": 0.01, "h": -0.1}}}}
    assert snap.compare(old, new) == 0
    new["lvl"]["v"] = 3.5
    assert snap.compare(old, new) == 1 and "lvl.v: 3.0 -> 3.5" in capsys.readouterr().out
    assert all(v is None or isinstance(v, str) for v in OLD_NAMES.values())
