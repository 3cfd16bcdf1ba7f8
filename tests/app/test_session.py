"""The app's model side (no window): schema-driven controls, clamping, live changes, save/load."""

from __future__ import annotations

import math

import numpy as np
import pytest

from chainfountain.app import controls
from chainfountain.app.session import Session
from chainfountain.level import io
from chainfountain.sim.config import CartConfig, SimConfig
from tests import shipped


@pytest.fixture(autouse=True)
def _home(tmp_path, monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))


def small_level(**feed) -> io.Level:
    cfg = SimConfig()
    cfg.feed.drop = 0.5
    cfg.feed.speed = 4.0
    cfg.chain.link_length = 0.03
    for k, v in feed.items():
        setattr(cfg.feed, k, v)
    return io.make_level("small", "test level", cfg)


def test_controls_come_from_the_schema():
    specs = {s.path: s for s in controls.control_fields(SimConfig())}
    assert list(specs)[:3] == ["feed.speed", "feed.launch_angle", "feed.drop"]
    speed = specs["feed.speed"]
    meta = io.field_meta("feed.speed")
    assert (speed.lo, speed.hi, speed.live, speed.unit) == (meta["min"], meta["max"], True, "m/s")
    assert specs["chain.link_length"].live is False
    assert specs["feed.launch_angle"].unit == "deg"  # radians shown in degrees
    assert "carts[0].mass" not in specs


def test_apparatus_fields_appear_when_the_level_has_them():
    cfg = SimConfig(carts=(CartConfig(), CartConfig(mass=0.3)))
    paths = [s.path for s in controls.control_fields(cfg)]
    for p in ("carts[0].mass", "carts[1].mass", "carts[0].incline", "carts[1].incline"):
        assert p in paths
    assert controls.get_value(cfg, "carts[1].mass") == 0.3


@pytest.mark.parametrize("bad", [-5.0, 1e9, math.inf, -math.inf, math.nan, "abc", None])
def test_clamp_never_raises_and_stays_in_range(bad):
    for spec in controls.control_fields(SimConfig(carts=(CartConfig(),))):
        v, msg = spec.clamp(bad)
        assert math.isfinite(v)
        if spec.lo is not None:
            assert v > spec.lo or (v == spec.lo and spec.lo_incl)
        if spec.hi is not None:
            assert v < spec.hi or (v == spec.hi and spec.hi_incl)
        assert msg is None or spec.label in msg


def test_slider_round_trip():
    """Every slider position is a rung of the field's ladder and comes back to itself."""
    for spec in controls.control_fields(SimConfig()):
        top = spec.positions
        assert 1 <= top <= 200, spec.path
        for pos in (0, 1, top // 2, top - 1, top):
            v = spec.from_slider(pos)
            assert spec.to_slider(v) == pos, (spec.path, pos)


def test_slider_arrows_step_by_round_amounts():
    """A slider's rungs between its ends are a round step apart (1, 2 or 5 times a power
    of ten; a logarithmic one 1, 2, 5 in each decade), so an arrow click moves a value
    such as 9 g to 9.5 g, not to 9.073 g."""
    for spec in controls.control_fields(SimConfig()):
        rungs = spec.ladder()[1:-1]
        if spec.log or len(rungs) < 2:
            continue
        steps = {round(b - a, 12) for a, b in zip(rungs, rungs[1:], strict=False)}
        assert len(steps) == 1, (spec.path, steps)
        step = steps.pop()
        mantissa = step / 10 ** math.floor(math.log10(step))
        assert round(mantissa, 9) in (1.0, 2.0, 5.0), (spec.path, step)
    spec = controls.FieldSpec("carts[0].mass", "cart", "g", "", 0.0, 1.0, True, True, True,
                              False, 1000.0, 8.0, 27.0, False)
    assert spec.ladder()[:4] == [8.0, 8.5, 9.0, 9.5]


def test_live_change_rebuild_and_refusal():
    s = Session(small_level())
    s.advance(0.1)
    t = s.sim.time
    sim = s.sim
    r = s.set_field("feed.speed", 4.5)
    assert r.ok and r.live and s.sim is sim and s.sim.time == t
    assert s.sim.feed.speed == 4.5 and s.level.sim.feed.speed == 4.5
    r = s.set_field("chain.bending_damping", 3e-5)  # within the damper's step here and at 25 mm
    assert r.ok and r.live
    r = s.set_field("chain.link_length", 0.025)
    assert r.ok and not r.live and s.sim is not sim and s.sim.time == 0
    assert "rebuilt" in r.message
    # a schema limit: clamped, and said so; then the window's real-time budget
    r = s.set_field("feed.speed", 99.0)
    fastest = s.value("feed.speed")
    assert r.ok and 4.5 < fastest < 30.0
    assert "outside the allowed range" in r.message and "too slow for the window" in r.message
    # a cross-field limit (too slow to reach the floor): refused, old value kept
    r = s.set_field("feed.speed", 1.0)
    assert not r.ok and s.value("feed.speed") == fastest and "refused" in r.message


def test_pause_step_reset_slow():
    s = Session(small_level())
    s.toggle_pause()
    assert s.tick(0.05, 1.0) == 0 and s.sim.time == 0
    n = s.step_frame(1 / 60)
    assert s.sim.steps == n and s.sim.time == pytest.approx(n * s.sim.dt)
    s.step_physics()
    assert s.sim.steps == n + 1
    s.reset()
    assert s.sim.time == 0
    assert [s.cycle_slow() for _ in range(3)] == [0.5, 0.25, 1.0]


def test_tick_keeps_to_its_budget():
    """A frame stops its physics when its budget is spent; the next frames make up what it
    left, up to CATCH_UP s; a longer backlog is dropped (the fountain slows instead)."""
    from chainfountain.app.session import CATCH_UP

    s = Session(small_level())
    dt = s.sim.dt
    first = s.tick(0.05, budget=1e-9)  # no time at all: one chunk, then it gives up
    assert 0 < first < round(0.05 / dt)
    assert s.behind
    done = s.tick(1 / 60, budget=10.0)  # made up
    assert done == pytest.approx((0.05 + 1 / 60) / dt - first, abs=1)
    assert not s.behind
    for _ in range(3):  # 0.3 s behind: more than CATCH_UP
        s.tick(0.1, budget=1e-9)
    assert 0.3 > CATCH_UP
    done = s.tick(1 / 60, budget=10.0)  # dropped: one frame's worth
    assert done <= round((1 / 60 + CATCH_UP) / dt) + 1


def test_readout_and_history():
    s = Session(small_level())
    r0 = s.readout()
    assert not r0.measured and r0.curve is not None  # prediction from the feed settings
    s.advance(0.3)
    r = s.readout()
    from chainfountain.app.session import APP_SAMPLE_INTERVAL

    assert r.measured and len(s.history.t) >= int(0.3 / APP_SAMPLE_INTERVAL) - 1
    assert r.v == pytest.approx(4.0, rel=0.05)
    assert 0 <= r.T0_theory < 1 and r.curve is not None and r.vertex is not None
    assert len(r.tension_bar) == len(r.tension_y) > 5


def test_save_and_load_round_trip(tmp_path):
    s = Session(small_level())
    s.set_field("feed.speed", 4.25)
    path = s.save("My level!")
    assert path is not None and path.parent == tmp_path / "home" / "levels"
    assert not s.dirty
    lvl = io.load(path)
    assert lvl.meta.name == "My level!" and lvl.sim.feed.speed == 4.25
    s2 = Session(small_level())
    assert s2.load_path(path) and s2.value("feed.speed") == 4.25
    assert not s2.load_path(tmp_path / "missing.toml")
    assert "no such file" in s2.messages[-1][1]
    assert s2.value("feed.speed") == 4.25  # the old level stays


def test_drag_a_link():
    s = Session(small_level())
    s.advance(0.05)
    p = s.sim.state().position[s.sim.n_free // 2]
    assert s.grab((float(p[0]), float(p[1])), max_dist=0.05)
    s.drag_to((float(p[0]) + 0.1, float(p[1]) - 0.1))
    s.step_frame(0.05)
    assert s.dragging
    s.release()
    assert not s.dragging
    assert not s.grab((50.0, 50.0), max_dist=0.05)


def test_used_up_apparatus_table_pauses_with_a_message(level) -> None:

    lvl = level("apparatus_floor")
    lvl.sim.apparatus.plate_links = 0  # the real geometry, sized for a 0.2-s run
    lvl.sim.apparatus.duration = 0.2
    s = Session(lvl)
    s.advance(2.0)  # no exception escapes
    assert s.paused
    shown = s.messages[-1][1]
    assert "upper table ran out of chain" in shown and "built for 0.2 s" in shown
    assert s.sim.time < 1.0


@pytest.mark.parametrize("variant, shown", [("fold", True), ("floor", False), ("open", False)])
def test_xi3_control_only_where_the_variant_uses_it(variant, shown):
    from chainfountain.sim.config import ApparatusConfig

    cfg = SimConfig(kind="apparatus", apparatus=ApparatusConfig(variant=variant))
    paths = [s.path for s in controls.control_fields(cfg)]
    assert "apparatus.xi2" in paths
    assert ("apparatus.xi3" in paths) is shown
    # only 'floor' has a floor to lower below the fountain end
    assert ("apparatus.floor_depth" in paths) is (variant == "floor")
    # only 'fold' has a folding roller to give a clearance
    assert ("apparatus.fold_clearance" in paths) is (variant == "fold")


def test_fold_clearance_control_lowers_the_lower_table(level) -> None:
    """The collapse message at a small step advises apparatus.fold_clearance = 0.002; the
    window offers it (a linear slider over 0-5 mm) and the rebuilt scene has the lower
    table that much lower."""

    lvl = level("apparatus_special")
    s = Session(lvl)
    spec = controls.spec_for(s.level.sim, "apparatus.fold_clearance")
    assert not spec.log and spec.slider_lo == 0.0 and spec.slider_hi == 0.005
    y0, c0 = s.sim.apparatus.y_table_lo, s.level.sim.apparatus.fold_clearance
    r = s.set_field("apparatus.fold_clearance", c0 + 0.001)
    assert r.ok and not r.live and "rebuilt" in r.message
    assert s.sim.apparatus.y_table_lo == pytest.approx(y0 - 0.001, abs=1e-12)
    r = s.set_field("apparatus.fold_clearance", 0.01)
    assert "outside the allowed range" in r.message and "[0, 0.005]" in r.message


def test_floor_depth_control_rebuilds_and_refuses(level) -> None:

    lvl = level("apparatus_floor")
    s = Session(lvl)
    H = s.sim.apparatus.H
    r = s.set_field("apparatus.floor_depth", 0.1)
    assert r.ok and not r.live and "rebuilt" in r.message
    assert s.sim.apparatus.floor_y == pytest.approx(-H - 0.1)
    # deeper than the launch speed can reach (v0 <= sqrt(g*(H + d))): refused, kept
    r = s.set_field("apparatus.floor_depth", 5.0)
    assert not r.ok and "refused" in r.message and "apparatus.speed" in r.message
    assert s.value("apparatus.floor_depth") == 0.1


def test_collapsed_fold_pauses_and_keeps_the_reason(level, capsys) -> None:
    """apparatus_limit (no lower cart): the folding roller rolls back at about 1 s; the
    session pauses and keeps why until the scene is rebuilt: in the window one plain
    sentence with what to do (here: open the ideal twin), on the terminal the full
    explanation (push, catch) that a headless run also gives."""

    lvl = level("apparatus_limit")
    s = Session(lvl)
    s.advance(2.0)  # no exception escapes
    assert s.paused and 0.5 < s.sim.time < 2.0
    shown = s.stopped
    assert shown is not None and "fold collapsed" in shown and "; M opens ideal_limit" in shown
    assert shown.count(". ") == 0 and len(shown) < 200 and "lambda" not in shown
    assert "[[carts]]" not in shown and "docs/" not in shown  # nothing a window cannot do
    err = capsys.readouterr().err
    assert "folding roller rolls backwards" in err and "lambda*v^2" in err
    s.load_path(shipped.path("ideal_limit"))
    assert s.stopped is None and not s.paused  # M after the stop: the twin runs
    s.load_level(lvl)
    assert not s.paused
    s.toggle_pause()
    s.load_path(shipped.path("ideal_limit"))
    assert s.paused  # a pause the user chose stays
    s.reset()
    assert s.stopped is None and s.sim.time == 0.0


def test_apparatus_history_has_the_roller_speeds(level) -> None:
    """The speed plot's pick-up and fold lines (twice each roller's speed) are in the
    history for a fold level, and absent (nan) for a feed level."""
    lvl = level("apparatus_special")
    s = Session(lvl)
    s.advance(0.6)
    h = s.history.arrays()
    late = h["t"] > 0.3
    assert late.sum() > 5
    v = float(np.mean(h["speed"][late]))
    # rolling without slip at alpha = 0: the chain moves at twice each roller's speed
    assert np.mean(h["speed_in"][late]) == pytest.approx(v, rel=0.03)
    assert np.mean(h["speed_out"][late]) == pytest.approx(v, rel=0.03)
    f = Session(small_level())
    f.advance(0.2)
    assert len(f.history.t) > 2 and np.isnan(f.history.arrays()["speed_in"]).all()


def test_setting_link_length_by_hand_turns_the_accuracy_off(level):
    lvl = level("wide_low")
    assert lvl.sim.solver.accuracy > 0
    s = Session(lvl)
    r = s.set_field("chain.link_length", 0.03)
    assert r.ok and s.level.sim.chain.link_length == 0.03
    assert s.level.sim.solver.accuracy == 0.0
    assert "solver.accuracy off" in r.message
    # a saved copy keeps the hand-set link length
    again = io.loads(io.dumps(s.level))
    assert again.sim.chain.link_length == 0.03


def test_a_changed_level_is_saved_with_a_description_of_its_changes(level, tmp_path):
    lvl = level("wide_low")
    s = Session(lvl)
    path = s.save("same", tmp_path)
    assert io.load(path).meta.description == lvl.meta.description  # unchanged: as it was
    assert s.set_field("feed.speed", 4.5).ok
    desc = io.load(s.save("faster", tmp_path)).meta.description
    assert desc.startswith("Level 'same' with changes (feed.speed 4.0 -> 4.5)")
    assert desc.endswith(lvl.meta.description)


def test_a_stalled_chain_pauses_with_a_sentence_and_no_nonsense_readout(level) -> None:
    """A 30 g upper cart stalls apparatus_floor's chain once its starter lets go: the window
    pauses with the stall's sentence, and the readout says there is no fountain instead of
    fitting a catenary (Tbar_E -19.6) and scaling tensions by a vanishing lambda*v^2."""
    lvl = level("apparatus_floor")
    lvl.sim.carts[0].mass = 0.03
    s = Session(lvl)
    s.advance(12.0)
    assert s.paused and "the chain has stopped" in s.messages[-1][1]
    ro = s.readout()
    assert ro.note.startswith("no fountain") and ro.curve is None
    assert math.isnan(ro.T0_bar) and math.isnan(ro.TE_theory)


@pytest.mark.parametrize("t", [0.6, 3.0])
def test_while_the_starter_runs_the_readout_names_it_and_reads_no_pull(level, t: float) -> None:
    """apparatus_fold_gripped from rest: while the starter sets the links' velocities the
    momentum balance reads its drive (a launch pull of -0.67 N at 1.1 s), so the readout
    names the starter and shows no pull; at 0.6 s the head flies at 1.87 m/s, slower than a
    fountain over the drop needs, and the readout names the starter, not a missing
    fountain."""
    s = Session(level("apparatus_fold_gripped"))
    s.advance(t)
    assert s.sim.apparatus.starting
    ro = s.readout()
    assert ro.note.startswith("the starter motor is running the chain")
    assert math.isnan(ro.T0_bar) and math.isnan(ro.TE_bar)


def test_window_keeps_a_fed_fountain_at_real_time(level):
    """Guard-rail: 30 m/s on classroom (3,400 links in flight, about 0.16x real time) is
    set to the fastest speed whose physics the error model's cost keeps within half of
    real time, with a message saying why and that level files accept it; a link length
    that would need 13,600 links is refused; a level shipped slower (paper_tall, 0.94 s
    per simulated second) may grow to 1.5 times its own cost."""
    from chainfountain.app import cost as budget

    s = Session(level("classroom"))
    r = s.set_field("feed.speed", 30.0)
    assert r.ok and 8.0 < r.value < 30.0
    assert "too slow for the window" in r.message and "level files" in r.message
    assert budget.cost(s.level.sim)[1] <= budget.WINDOW_COST
    r = s.set_field("chain.link_length", 0.002)
    assert not r.ok and r.message.startswith("refused:") and "links in flight" in r.message
    p = Session(level("paper_tall"))
    shipped = budget.cost(p.level.sim)[1]
    assert shipped > budget.WINDOW_COST
    assert p.set_field("feed.speed", 6.0).ok and p.value("feed.speed") == 6.0
    r = p.set_field("feed.speed", 30.0)
    assert r.ok and 6.0 < r.value < 30.0
    assert budget.cost(p.level.sim)[1] <= budget.ORIGIN_FACTOR * shipped


def test_pure_numbers_show_no_unit(level):
    s = Session(level("classroom"))
    r = s.set_field("chain.friction", 0.5)
    assert r.ok and r.message.startswith("friction = 0.5") and " 1 " not in r.message + " "


def test_a_level_that_cannot_be_opened_is_said_in_the_window() -> None:
    """``chainfountain play BAD.toml`` with a display opens the window on the default level,
    paused, and says why over the scene until R starts it (the line also goes to stderr
    and the command exits 2): a teacher looking at the projector sees what went wrong."""
    from chainfountain.app.session import default_level
    from chainfountain.commands.play import refused_notice
    from chainfountain.level.model import LevelError

    s = Session(default_level())
    s.hold(refused_notice(LevelError("BAD.toml: meta: missing; required, a [meta] table")))
    assert s.paused and s.stopped is not None
    shown = s.messages[-1][1]
    assert shown.startswith("could not open that level: BAD.toml: meta: missing")
    assert "default level" in shown and "press R" in shown and "\n" not in shown
    s.toggle_pause()  # Space keeps it paused and says it again
    assert s.paused and s.messages[-1][1] == shown
    s.reset()
    assert s.stopped is None and not s.paused


def test_window_keeps_an_apparatus_at_real_time(level) -> None:
    """Guard-rail: a start speed of 30 m/s on apparatus_floor would put about 8,000 links
    in the solver (0.03x real time): the window refuses it, saying why and that level
    files accept it; 4 m/s (about 180 links) is taken. The estimate follows the machine's
    parts: within 10 % of the links the presets build (134 against 125 for the floor,
    191 against 193 for the special case)."""
    from chainfountain.app import cost as budget
    from chainfountain.sim import Simulation
    from chainfountain.study.changes import laid_on_path

    for name in ("apparatus_floor", "apparatus_special", "apparatus_fold"):
        lvl = laid_on_path(level(name))
        built = len(Simulation(lvl.sim).chain.links)
        assert budget.apparatus_links(lvl.sim) == pytest.approx(built, rel=0.1), name
    s = Session(level("apparatus_floor"))
    r = s.set_field("apparatus.speed", 30.0)
    assert not r.ok and r.message.startswith("refused:") and "links moving" in r.message
    assert "level files" in r.message and s.value("apparatus.speed") == pytest.approx(2.98)
    assert s.set_field("apparatus.speed", 4.0).ok


def test_an_internal_error_in_a_step_is_said_plainly(monkeypatch, capsys) -> None:
    """Nothing raw from an exception reaches the screen: a bug in a step (here a division
    by zero) pauses the window with one plain sentence naming the kind of error and
    pointing to the terminal, where the traceback goes; R starts the level again."""
    s = Session(small_level())

    def broken() -> None:
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(s.sim, "step", broken)
    s.advance(0.05)  # no exception escapes
    shown = s.messages[-1][1]
    assert s.paused and "internal error (ZeroDivisionError" in shown and "press R" in shown
    assert "float division by zero" not in shown and "\n" not in shown
    assert "float division by zero" in capsys.readouterr().err
    s.reset()
    assert s.stopped is None


def test_level_files_and_run_accept_what_the_window_refuses(level, tmp_path) -> None:
    """The guard-rails are the window's: a 30 m/s classroom, which the window refuses (about
    0.03x real time), loads as a level and runs headless."""
    import chainfountain
    from chainfountain.app import cost as budget
    from chainfountain.study.changes import with_changes

    lvl = level("classroom")
    changes = {"feed.speed": 30.0, "solver.accuracy": 0.0}  # its own link length and step
    fast = with_changes(lvl, changes)
    assert budget.over_budget(fast.sim, lvl.sim) is not None
    r = chainfountain.run("classroom", duration=0.05, changes=changes, out=tmp_path / "o")
    assert r.summary["ended_early"] is None and r.summary["duration_s"] >= 0.05 - 1e-9


def test_a_run_that_stops_within_a_frame_steps_no_further(level, capsys) -> None:
    """A window frame asks for many physics steps; when the machine stops itself in one
    of them the frame ends there (it said why once, and the clock stays at the stop)."""

    lvl = level("apparatus_limit")
    s = Session(lvl)
    s.advance(0.9)
    assert s.stopped is None
    capsys.readouterr()
    for _ in range(3):  # 0.1 s of wall time per frame: past the collapse near 1 s
        s.tick(0.1, budget=60.0)
    assert s.stopped is not None and s.paused
    t_stop = s.sim.time
    assert t_stop < 1.1
    assert capsys.readouterr().err.count("rolls backwards") == 1
    s.tick(0.1, budget=60.0)  # paused: nothing more
    assert s.sim.time == t_stop


def test_floor_machine_readout_says_what_its_cart_selects(level) -> None:
    """The contact floor machine's readout gives, beside the measured speed, the speed its
    upper cart selects by this model's pick-up law and by the paper's laws, and follows a
    live cart change. The paper's figure is checked against its formula here:
    ``v**2 = (g*H*(1 - xi2) - F_uc/lambda)/(1/2)`` (``Tbar_0 = 1/2 + Tbar_uc + xi2*k*H``
    meeting the free-ended fountain's ``Tbar_0 = k*H``)."""
    import math

    from chainfountain.sim.apparatus.laws import floor_speeds

    lvl = level("apparatus_floor")
    s = Session(lvl)

    def paper_speed() -> float:
        app, cfg = s.sim.apparatus, s.sim.config
        lam, g = cfg.chain.linear_density, cfg.gravity
        return math.sqrt((g * app.H * (1 - cfg.apparatus.xi2) - app.upper.force / lam) / 0.5)

    s.advance(0.05)
    model, paper = floor_speeds(s.sim.config)
    assert paper == pytest.approx(paper_speed(), rel=1e-12)
    assert model > paper  # this model's pick-up pulls less than the paper's 1/2
    line = s.readout().machine
    assert f"{model:.2f} m/s by this model's rollers" in line
    assert f"{paper:.2f} m/s by the paper's laws" in line
    assert s.set_field("carts[0].mass", 1.5 * lvl.sim.carts[0].mass).ok
    s.advance(0.05)
    model2, paper2 = floor_speeds(s.sim.config)
    assert model2 < model and paper2 == pytest.approx(paper_speed(), rel=1e-12)
    assert f"{model2:.2f} m/s" in s.readout().machine
