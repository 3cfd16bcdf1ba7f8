"""A stiff fed level's run: ``summary.json``'s theory says it is the stiff-chain theory,
with the joints and the catenary beside it, and ``chainfountain run`` prints the stiff
theory's vertex and landing beside the measured ones."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from chainfountain.headless import RunSummary, describe_outputs, run_level
from chainfountain.headless.section_text import stiff_lines
from chainfountain.sim import Simulation
from tests import shipped


def laid(c: float = 0.015, d: float = 0.0006):
    """``stiff_chain`` laid on its catenary (a fountain to measure within a second)."""
    lvl = shipped.level("stiff_chain")
    lvl.sim.initial.mode = "catenary"
    lvl.sim.chain.bending_stiffness = c
    lvl.sim.chain.bending_damping = d
    return lvl


@pytest.fixture(scope="module")
def stiff_run(tmp_path_factory) -> Path:
    return run_level(laid(), tmp_path_factory.mktemp("stiff"), 1.0, progress=False)


def test_the_theory_block_says_which_theory(stiff_run):
    th = json.loads(stiff_run.read_text())["theory"]
    ref = Simulation(laid().sim).reference
    assert th["theory"] == "stiff" and th["q"] is None
    assert th["h"] == pytest.approx(ref.h) and th["l"] == pytest.approx(ref.landing_x)
    assert th["vertex_x"] == pytest.approx(ref.x_rise)
    assert th["joints"]["c"] == 0.015 and th["joints"]["d"] == 0.0006
    assert th["joints"]["e"] > 0 and th["joints"]["delta"] > 0
    cat = th["catenary"]
    assert cat["h"] == pytest.approx(ref.catenary.h) and cat["q"] == pytest.approx(
        ref.catenary.q)
    assert set(cat["rel_error"]) == {"h", "vertex_x", "l"}
    s = RunSummary.load(stiff_run)
    assert s.theory.stiff and s.theory.catenary == cat and s.to_json()["theory"] == th


def test_run_prints_the_stiff_vertex_and_landing(stiff_run):
    s = RunSummary.load(stiff_run)
    th, f = s.theory, s.fountain
    text = describe_outputs(stiff_run, s)
    assert (f"  vertex height {f.h:.4f} m (stiff-chain theory {th.h:.4f}, "
            f"{100 * th.rel_error.h:+.2f} %), landing {f.l:.4f} m (stiff-chain theory "
            f"{th.l:.4f}, {100 * th.rel_error.l:+.2f} %)") in text
    assert "c = 0.015 N*m/rad, d = 0.0006 N*m*s/rad" in text
    cat = th.catenary
    assert (f"  the catenary (no joint resistance): vertex height {cat['h']:.4f} m "
            f"({100 * cat['rel_error']['h']:+.2f} %)") in text


def test_a_loose_chain_s_block_is_the_catenary_s():
    """``theory`` names the catenary and adds nothing else (the figures as before)."""
    from chainfountain.headless.report import AbsErrors, RelErrors, Theory

    none = dict.fromkeys(("h", "vertex_x", "l", "q", "v"))
    th = Theory(h=1.0, vertex_x=0.5, l=2.0, q=1.0, k=0.5, v=4.0, T0_bar=0.3, TE_bar=0.0,
                rel_error=RelErrors(**none),
                abs_error=AbsErrors(T0_bar=None, TE_bar=None, tension_rms=None))
    d = th.to_json()
    assert d["theory"] == "catenary"
    assert not {"joints", "catenary", "why_none"} & set(d)
    assert Theory.from_json(d) == th


def test_no_steady_stiff_fountain_is_printed():
    from chainfountain.headless.report import AbsErrors, RelErrors, Theory

    none = dict.fromkeys(("h", "vertex_x", "l", "q", "v"))
    th = Theory(h=None, vertex_x=None, l=None, q=None, k=0.5, v=3.0, T0_bar=None,
                TE_bar=0.0, rel_error=RelErrors(**none),
                abs_error=AbsErrors(T0_bar=None, TE_bar=None, tension_rms=None),
                theory="stiff", joints={"c": 0.03, "d": 0.0, "e": 0.0025, "delta": 0.0},
                catenary={"h": 0.2587, "l": 0.8422, "rel_error": {"h": 0.3, "l": -0.2}},
                why_none="no steady stiff fountain at c = 0.03 N*m/rad, d = 0 N*m*s/rad")
    lines = stiff_lines(th, 0.3457, 0.6683, 2.9658)
    assert lines[0] == ("  vertex height 0.3457 m, landing 0.6683 m, speed 2.9658 m/s: "
                        "no steady stiff fountain at c = 0.03 N*m/rad, d = 0 N*m*s/rad")
    assert lines[1].startswith("  the catenary (no joint resistance): vertex height 0.2587")


def test_a_run_without_a_steady_stiff_fountain_says_so(tmp_path, monkeypatch):
    from chainfountain.sim import stiff_reference
    from chainfountain.theory.stiff import NoSteadyFountain

    def none(*args, **kw):
        raise NoSteadyFountain("no steady stiff fountain found: test")

    monkeypatch.setattr(stiff_reference, "stiff_fountain_of", none)
    path = run_level(laid(0.03, 0.0), tmp_path, 0.5, progress=False)
    th = json.loads(path.read_text())["theory"]
    assert th["theory"] == "stiff" and th["h"] is None and th["l"] is None
    assert th["why_none"].startswith("no steady stiff fountain at c = 0.03 N*m/rad, d = 0")
    assert th["catenary"]["h"] is not None
    text = describe_outputs(path)
    assert "no steady stiff fountain at c = 0.03 N*m/rad" in text
    assert "the catenary (no joint resistance)" in text


def test_a_chain_too_little_damped_to_settle_says_so(stiff_run, tmp_path):
    """``stiff_chain``'s damper settles its fountain (A well above 2.2); without it the
    same springs do not, and summary.json and the printed lines say so."""
    j = json.loads(stiff_run.read_text())["theory"]["joints"]
    assert j["settles"] is True and j["damper_decay"] > 2.2
    assert "does not" not in describe_outputs(stiff_run, RunSummary.load(stiff_run))
    bare = run_level(laid(d=0.0), tmp_path, 0.2, progress=False)
    jb = json.loads(bare.read_text())["theory"]["joints"]
    assert jb["settles"] is False and jb["damper_decay"] == 0.0
    assert "below the 2.2 at which stiff fountains settle: this one does not" in (
        describe_outputs(bare, RunSummary.load(bare)))
