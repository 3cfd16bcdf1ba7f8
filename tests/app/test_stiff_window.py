"""The ``stiff_chain`` level in the window (SDL dummy driver): moving the stiffness slider
solves the stiff-chain theory again, beside the running window, and its curve, height
label and readout follow."""

from __future__ import annotations

import os
import time

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import numpy as np  # noqa: E402
import pygame  # noqa: E402
import pygame_gui  # noqa: E402
import pytest  # noqa: E402

from chainfountain.app.readout_text import readout_rows  # noqa: E402
from chainfountain.app.session import Session  # noqa: E402
from chainfountain.app.window import App  # noqa: E402
from chainfountain.sim.stiff_reference import StiffReference  # noqa: E402
from tests import shipped  # noqa: E402
from tests.app.offscreen import shipped_app  # noqa: E402


@pytest.fixture
def app(tmp_path, monkeypatch):
    with shipped_app("stiff_chain", tmp_path / "home", monkeypatch) as a:
        yield a


def frames_until(app: App, done, seconds: float = 20.0) -> None:
    """Run frames until ``done()`` (the theory's thread finishing), at most ``seconds``."""
    end = time.perf_counter() + seconds
    while not done():
        assert time.perf_counter() < end, "the theory was not solved"
        app.run_frame()
        time.sleep(0.01)


def test_the_stiffness_slider_moves_the_stiff_theory_s_curve(app):
    s = app.session
    frames_until(app, lambda: isinstance(s.sim.reference, StiffReference))
    ro = s.readout()
    before, h0 = ro.curve.copy(), ro.paper_h
    assert ro.theory == "stiff" and ro.theory_label == "stiff-chain theory"
    assert h0 == s.sim.reference.h
    text = " ".join(r.text for r in readout_rows(ro, 0.05, expert=False))
    assert "the stiff-chain theory predicts" in text
    row = app._row("chain.bending_stiffness")
    assert row is not None and row.spec.live
    version = s.sim.theory_version
    pygame.event.post(pygame.event.Event(pygame_gui.UI_HORIZONTAL_SLIDER_MOVED,
                                         ui_element=row.slider,
                                         value=row.spec.to_slider(0.05)))
    app.run_frame()
    assert s.value("chain.bending_stiffness") == pytest.approx(0.05)
    assert s.sim.chain.cfg.bending_stiffness == pytest.approx(0.05)  # the springs at once
    frames_until(app, lambda: s.sim.theory_version > version)
    ref = s.sim.reference
    assert ref.c == pytest.approx(0.05) and s.theory_solve_s is not None
    ro = s.readout()
    assert ro.paper_h == ref.h < 0.95 * h0  # stiffer: a lower arch, > 5 % on the screen
    assert not np.allclose(ro.curve, before)
    assert ro.curve == pytest.approx(ref.curve(160))


def test_slider_moves_in_a_drag_start_one_solve_at_a_time(app):
    s = app.session
    frames_until(app, lambda: isinstance(s.sim.reference, StiffReference))
    row = app._row("chain.bending_stiffness")
    for c in (0.02, 0.025, 0.03, 0.035, 0.04):
        pygame.event.post(pygame.event.Event(pygame_gui.UI_HORIZONTAL_SLIDER_MOVED,
                                             ui_element=row.slider,
                                             value=row.spec.to_slider(c)))
        app.run_frame()
    frames_until(app, lambda: not s.sim.theory_stale and s._solving is None)
    assert s.sim.reference.c == pytest.approx(s.value("chain.bending_stiffness"))


def test_the_readout_says_when_there_is_no_steady_stiff_fountain(tmp_path, monkeypatch):
    from chainfountain.sim import stiff_reference
    from chainfountain.theory.stiff import NoSteadyFountain

    def none(*args, **kw):
        raise NoSteadyFountain("no steady stiff fountain found: test")

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    monkeypatch.setattr(stiff_reference, "stiff_fountain_of", none)
    s = Session(shipped.level("stiff_chain"))
    assert s.readout().note == "solving the stiff-chain theory for these joints ..."
    assert s.refresh_theory(wait=True)
    ro = s.readout()
    assert s.sim.reference is None and ro.curve is None and np.isnan(ro.paper_h)
    assert ro.note == ("no steady stiff fountain at c = 0.015 N*m/rad, "
                       "d = 0.0006 N*m*s/rad")
    from chainfountain.app.readout_text import plain_rows

    assert any(r.text.strip() == ro.note and r.colour == "warn"
               for r in plain_rows(ro, 0.05))


def test_the_readout_warns_when_the_damper_is_too_weak_to_settle(tmp_path, monkeypatch):
    """``stiff_chain``'s damper settles its fountain; with the damping slider at 0 the
    theory's steady fountain still exists, and the readout says the chain will not
    settle on it (``docs/stiff_stability.md``)."""
    from chainfountain.app.readout_text import plain_rows

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    s = Session(shipped.level("stiff_chain"))
    assert s.refresh_theory(wait=True)
    assert s.sim.reference.settles and not s.readout().settle_note
    assert s.set_field("chain.bending_damping", 0.0).ok
    assert s.refresh_theory(wait=True)
    ro = s.readout()
    assert isinstance(s.sim.reference, StiffReference) and not s.sim.reference.settles
    assert any("does not settle" in r.text and r.colour == "warn"
               for r in plain_rows(ro, 0.05))


def test_the_joint_sliders_stop_at_their_step_limits(app):
    """The damping slider ends where the level check's damper limit is (0.00064 N*m*s/rad
    at 4-cm links and 62.5-us steps), below its 3x-the-value span; the stiffness slider
    keeps its span, far below the spring's limit."""
    from chainfountain.sim import joints

    s = app.session
    h = s.level.sim.solver.dt / s.level.sim.solver.substeps
    damp = app._row("chain.bending_damping").spec
    assert damp.slider_hi == pytest.approx(joints.damping_limit(s.level.sim.chain, h))
    assert s.set_field("chain.bending_damping", damp.slider_hi).ok
    stiff = app._row("chain.bending_stiffness").spec
    assert stiff.slider_hi < joints.stiffness_limit(s.level.sim.chain, h)
    assert stiff.slider_hi == pytest.approx(0.05)
