"""Like-for-like ideal twins of the contact machine levels (``chainfountain.level.twins``).

The twin is the paper's ideal machine with the contact level's drop, launch angle,
offsets, chain and speed, its carts chosen by the paper's laws (section "Generating
Steady-State Chain Fountains"): ``Tbar_0 = 1/2 + Tbar_uc + xi2 k H``, ``Tbar_E = 1/2 +
Tbar_lc - xi3 k H``, steady ``Tbar_uc = Tbar_lc + k H (1 - xi2 - xi3)``. Where no carts
that only hold back can run the source's fountain, ``ideal_twin`` raises a one-line
``LevelError``; the tests check each preset's outcome against the paper's laws with the
carts at zero (an independent reason), not against a list.

The runs: the only shipped preset that twins is ``apparatus_limit`` (the paper's limit
case). Its twin is run from rest with the source's 2-cm chain and with a chain of 5-mm
links; a contact fold built at ``ideal_fold``'s geometry is run to show a twin that keeps
its template's bearing drag selecting its speed.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from chainfountain.level import io, library, twins
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.kinds.ideal.checks import IDEAL_MIN_KQ
from chainfountain.sim.machine_rules import keeps_any_speed
from chainfountain.sim.reference import LaunchReference
from chainfountain.theory import apparatus as ap
from tests import shipped

CONTACT = sorted(p.stem for p in shipped.PATHS
                 if io.load(p).sim.kind == "apparatus")
"""Every shipped contact machine preset (the eight of the brief and the fountain-D pair)."""

IDEAL = ("ideal_floor", "ideal_fold", "ideal_special", "ideal_limit", "ideal_open")
VARIANT_OF_DRIVE = {"ideal_floor": "floor", "ideal_fold": "fold", "ideal_open": "open"}


def _load(name: str) -> io.Level:
    return shipped.level(name)


def _source_TE(level: io.Level) -> float:
    """The end tension of the contact level's fountain: its floor's 0, else the
    ``apparatus.end_tension`` it is laid out and aimed for."""
    a = level.sim.apparatus
    return 0.0 if a.variant == "floor" else a.end_tension


def _why_the_paper_cannot(level: io.Level) -> str:
    """Why the paper's ideal machine cannot run ``level``'s fountain at its geometry, found
    with the carts at zero (a cart can only hold back), or '' when it can."""
    s = level.sim
    a, g, lam = s.apparatus, s.gravity, s.chain.linear_density
    v, H, TE = a.speed, a.drop, _source_TE(level)
    if a.variant == "floor":
        if a.end != "absorbing" or a.floor_depth > 0.0:
            return "no ideal floor of this kind"
        if ap.ideal_floor_speed(H, a.xi2, 0.0, lam, g) < v:
            return "too slow even with no upper cart"
    elif a.variant == "fold":
        if ap.ideal_fold_TE_bar(v, a.xi3, 0.0, lam, H, g) > TE + 1e-12:
            return "the put-down alone pulls the end harder than its fountain's Tbar_E"
        if ap.ideal_fold_T0_bar(v, a.xi2, 0.0, lam, H, g) > TE + g * H / v**2 + 1e-12:
            return "the pick-up alone pulls harder than its fountain's Tbar_0"
    elif ap.ideal_open_speed(H, a.xi2, 0.0, TE * v * v / g, lam, g) < v:
        return "too slow even with no upper cart"
    ref = LaunchReference.from_launch(v, a.launch_angle, H, g, TE_bar=TE)
    if ref.k / ref.q < IDEAL_MIN_KQ:
        return "too near critical"
    return ""


def _template(name: str, drive: str) -> io.Level:
    shipped = library.twin(name)
    if shipped is not None and _load(shipped).sim.feed.drive == drive:
        return _load(shipped)
    return _load(drive)


def _assert_like_for_like(src: io.Level, twin: io.Level) -> None:
    """The twin has the source's geometry, chain and speed by the paper's laws."""
    a, f = src.sim.apparatus, twin.sim.feed
    lam, g = src.sim.chain.linear_density, src.sim.gravity
    assert twin.sim.kind == "feed" and VARIANT_OF_DRIVE[f.drive] == a.variant
    assert (f.drop, f.launch_angle, f.xi2) == (a.drop, a.launch_angle, a.xi2)
    if a.variant == "fold":
        assert f.xi3 == a.xi3
    assert twin.sim.chain == src.sim.chain and twin.sim.gravity == g
    assert min(f.cart_force, f.lower_cart_force, f.bearing_drag, f.turn_drop) >= 0.0
    ref = LaunchReference.of_level(twin.sim)  # what the window's machine line reads
    assert ref.v == pytest.approx(a.speed, rel=1e-6)
    assert ref.TE_bar == pytest.approx(_source_TE(src), abs=1e-6)
    if f.drive == "ideal_fold":
        v, H = a.speed, a.drop
        T0 = ap.ideal_fold_T0_bar(v, f.xi2, f.cart_force, lam, H, g, f.bearing_drag)
        TE = ap.ideal_fold_TE_bar(v, f.xi3, f.lower_cart_force, lam, H, g, f.bearing_drag)
        assert T0 - TE == pytest.approx(g * H / v**2, abs=1e-9)  # steady: Tbar_0 - Tbar_E = kH
        if f.bearing_drag > 0.0:
            assert ap.ideal_fold_speed(f.cart_force, f.lower_cart_force, f.xi2, f.xi3,
                                       f.bearing_drag, lam, H, g) == pytest.approx(v, rel=1e-6)
        else:
            assert keeps_any_speed(twin.sim)
        if TE == pytest.approx(0.0, abs=1e-9):  # a free end: slower, the strand goes slack
            assert ap.ideal_fold_slack_speed(f.xi3, f.lower_cart_force, lam, H, g) \
                == pytest.approx(v, rel=1e-6)
            assert ap.ideal_floor_speed(H, f.xi2, f.cart_force + 0.5 * f.bearing_drag * v, lam,
                                        g) == pytest.approx(v, rel=1e-6)
    tpl = _template(src.name, f.drive).sim
    assert (twin.sim.solver, twin.sim.initial, twin.sim.recording) == \
        (tpl.solver, tpl.initial, tpl.recording)
    assert (f.starter, f.machine_mass, f.chain_length) == \
        (tpl.feed.starter, tpl.feed.machine_mass, tpl.feed.chain_length)
    m = twin.meta
    assert m.name == f"{src.name} (ideal twin)" == twin.sim.name
    assert src.meta.shown_title in m.title and "ideal rollers" in m.title
    assert "ideal rollers" in m.description and m.description.endswith(".")
    assert m.description.count(". ") <= 2, m.description  # at most three sentences
    back = io.loads(io.dumps(twin), "twin.toml")  # passes the level checks, and round-trips
    assert back.meta == twin.meta and back.sim == twin.sim


@pytest.mark.parametrize("name", CONTACT)
def test_each_contact_preset_twins_exactly_when_the_papers_carts_can_run_it(name) -> None:
    src = _load(name)
    why = _why_the_paper_cannot(src)
    if why:
        with pytest.raises(io.LevelError) as exc:
            twins.ideal_twin(src)
        msg = str(exc.value)
        assert msg.startswith(f"{name} has no ideal twin: ") and "\n" not in msg, msg
        return
    twin = twins.ideal_twin(src)
    assert twin is not None
    _assert_like_for_like(src, twin)


@pytest.mark.parametrize("ideal", ["ideal_floor", "ideal_fold", "ideal_special", "ideal_open"])
def test_a_contact_level_at_an_ideal_presets_geometry_twins_to_that_preset(ideal) -> None:
    """The contact preset paired with ``ideal`` rebuilt at that ideal preset's drop, launch,
    offsets, speed and end tension: its twin is the shipped ideal preset's machine (carts,
    drag, turn), designed independently (docs/apparatus.md, "Presets")."""
    want = _load(ideal)
    ref = LaunchReference.of_level(want.sim)
    src = _load(library.twin(ideal))
    a, f = src.sim.apparatus, want.sim.feed
    a.drop, a.launch_angle, a.speed, a.xi2 = f.drop, f.launch_angle, ref.v, f.xi2
    a.xi3, a.end_tension = (f.xi3 if f.drive == "ideal_fold" else a.xi3), ref.TE_bar
    twin = twins.ideal_twin(src)
    got = twin.sim.feed
    for field in ("drive", "xi2", "xi3", "bearing_drag"):
        assert getattr(got, field) == getattr(f, field), field
    for field in ("cart_force", "lower_cart_force", "turn_drop"):
        assert getattr(got, field) == pytest.approx(getattr(f, field), abs=1e-9), field
    _assert_like_for_like(src, twin)


def test_a_drag_the_carts_cannot_carry_leaves_the_twin_loss_free() -> None:
    """``apparatus_limit``'s template (``ideal_limit``) drags with 0.03 N s/m, ``c v/2`` at
    each roller. The paper's upper cart for the limit case at 2.6 m/s is lighter than
    that, so with the drag it would have to push: the twin is the loss-free machine."""
    src = _load("apparatus_limit")
    a, lam, g = src.sim.apparatus, src.sim.chain.linear_density, src.sim.gravity
    c = _load("ideal_limit").sim.feed.bearing_drag
    paper_upper = ap.balanced_cart_force(0.0, a.xi2, a.xi3, lam, a.drop, g)
    assert 0.0 < paper_upper < 0.5 * c * a.speed
    f = twins.ideal_twin(src).sim.feed
    assert f.bearing_drag == 0.0 and f.lower_cart_force == 0.0
    assert f.cart_force == pytest.approx(paper_upper, abs=1e-12)


@pytest.mark.parametrize("change, words", [
    ({"speed": 2.0}, ["makes no fountain", "sqrt(g H)"]),
    ({"end": "solid"}, ["'solid'", "piles"]),
    ({"speed": 3.4}, ["at most at 2.62 m/s", "slower than its 3.4 m/s"]),
])
def test_a_floor_the_ideal_machine_cannot_run_says_why_in_one_line(change, words) -> None:
    src = _load("apparatus_floor")
    for k, v in change.items():
        setattr(src.sim.apparatus, k, v)
    with pytest.raises(io.LevelError) as exc:
        twins.ideal_twin(src)
    msg = str(exc.value)
    assert msg.startswith("apparatus_floor has no ideal twin: ") and "\n" not in msg
    for w in words:
        assert w in msg, msg


def test_a_slower_floor_twins_with_an_upper_cart() -> None:
    """``apparatus_floor`` at 2.6 m/s, below the 2.62 m/s the paper's rollers reach at its
    drop and offset with no cart (and above the 2.56 m/s where its fountain's ``k/q``
    falls below 0.125): the twin holds the chain back with ``F_uc = lambda (g H (1 - xi2) -
    v^2/2)`` and selects 2.6 m/s."""
    src = _load("apparatus_floor")
    src.sim.apparatus.speed = 2.6
    twin = twins.ideal_twin(src)
    assert twin.sim.feed.cart_force > 0.0
    _assert_like_for_like(src, twin)


@pytest.mark.parametrize("name", ["beaker", "paper_tall", "classroom", "chain_on_scale",
                                  *IDEAL])
def test_levels_with_no_contact_machine_have_no_ideal_twin(name) -> None:
    assert twins.ideal_twin(_load(name)) is None


@pytest.mark.parametrize("name", IDEAL)
def test_a_shipped_ideal_preset_opens_its_contact_preset(name) -> None:
    got = twins.contact_twin(_load(name))
    assert got is not None and got.name == library.twin(name) and got.sim.kind == "apparatus"
    assert got.sim.apparatus.variant == VARIANT_OF_DRIVE[_load(name).sim.feed.drive]


def test_other_levels_have_no_known_contact_twin() -> None:
    renamed = _load("ideal_fold")
    renamed.meta = dataclasses.replace(renamed.meta, name="my_fold")
    made = twins.ideal_twin(_load("apparatus_limit"))
    for lvl in (renamed, made, _load("apparatus_fold"), _load("beaker"), _load("paper_tall")):
        assert twins.contact_twin(lvl) is None, lvl.name


# ---------------------------------------------------------------------------- runs
RUNS = pytest.mark.xdist_group("twins_run")
"""One worker runs the twins' runs (``--dist loadgroup``), one after another."""


def _run(twin: io.Level, seconds: float) -> tuple[Simulation, Recorder]:
    sim = Simulation(twin.sim)
    rec = Recorder(sim, profiles=False)
    sim.advance(seconds)
    return sim, rec


def _window(rec: Recorder, t0: float, t1: float, name: str = "speed_mean") -> float:
    t, x = rec.series("t"), rec.series(name)
    return float(np.mean(x[(t >= t0) & (t < t1)]))


@RUNS
@pytest.mark.slow
def test_the_limit_twin_runs_from_rest_where_its_laws_put_its_simulated_fountain() -> None:
    """The twin of ``apparatus_limit`` from its stub, 20 s: the starter lets go at 5.7 s (5 s
    after the chain lands) and the machine runs on its laws. Slower than 2.6 m/s its lower
    strand is slack, and its upper half's ``Tbar_0 = 1/2 + Tbar_uc + xi2 k H`` meets the
    fountain's. The simulated 2-cm fountain over this 0.5-m drop holds ``Tbar_0`` a little
    below the paper's ``k H`` (``delta`` about 0.018 over the late windows): with it the law
    gives ``v^2 = v_paper^2/(1 + 2 delta)``, 1.8 % below the source's speed, and the run
    follows that (measured over 8-20 s: within +0.25 / -0.11 % in every 2-s window; four
    nudged starts agree to 0.01 %; half the step moves it by +0.2 %). The offset is the
    chain's discretisation: with 1-cm links the run is 1.0 % low, with 5-mm links 0.03 %
    (the next test), so the 2.5 % allowed against the source is that measured 1.8 % and the
    windows' wander, not a loss of the twin."""
    src = _load("apparatus_limit")
    twin = twins.ideal_twin(src)
    sim, rec = _run(twin, 20.0)
    assert not sim.piston.starting and sim.piston.hand_over < 8.0
    f, g = twin.sim.feed, sim.g
    v = _window(rec, 18.0, 20.0)
    delta = g * f.drop / v**2 - _window(rec, 18.0, 20.0, "T0_bar")
    assert 0.0 < delta < 0.03, delta  # the simulated fountain's own deficit, small
    v_law = ap.ideal_floor_speed(f.drop, f.xi2, f.cart_force, twin.sim.chain.linear_density,
                                 g) / math.sqrt(1.0 + 2.0 * delta)
    assert v == pytest.approx(v_law, rel=0.005)  # 2x the largest measured window's miss
    assert v == pytest.approx(src.sim.apparatus.speed, rel=0.025)
    assert sim.feed.end_pull(v) == 0.0  # the lower strand is slack there, as the law says


@RUNS
@pytest.mark.slow
def test_the_limit_twin_with_a_finer_chain_runs_at_the_source_speed() -> None:
    """The same twin with 5-mm links (and half the step, as a quarter link length needs):
    the discretisation offset of the previous test is gone and the machine runs at the
    source's 2.6 m/s (measured: -0.03 %, its 2-s windows within 0.03 % of each other from
    6 s on). 0.3 % is the ideal presets' agreement with their laws over 6 s from the
    fountain (docs/apparatus.md, "Against the paper": within 0.2 %) and a margin."""
    src = _load("apparatus_limit")
    twin = twins.ideal_twin(src)
    twin.sim.chain.link_length, twin.sim.solver.dt = 0.005, 1.25e-4
    sim, rec = _run(twin, 14.0)
    assert not sim.piston.starting
    assert _window(rec, 12.0, 14.0) == pytest.approx(src.sim.apparatus.speed, rel=0.003)


@RUNS
@pytest.mark.slow
def test_a_twin_with_bearing_drag_selects_the_source_speed_from_rest() -> None:
    """``apparatus_fold`` rebuilt at ``ideal_fold``'s 1-m geometry, 5 m/s and ``Tbar_E``:
    its twin keeps the template's drag (0.06 N s/m), its carts carry it, and from the stub
    the machine selects the source's speed: over 18-20 s 5.005 m/s (+0.10 %; two nudged
    starts agree to 1e-4). 0.5 % is how far a dragging ideal machine settles off its
    selected speed by the simulated chain's own imbalance over the drag, 0.2-0.5 % for the
    presets in 600-s runs (docs/apparatus.md, "How long they hold")."""
    src = _load("apparatus_fold")
    want = _load("ideal_fold").sim.feed
    a = src.sim.apparatus
    ref = LaunchReference.of_level(_load("ideal_fold").sim)
    a.drop, a.speed, a.xi2, a.xi3, a.end_tension = want.drop, ref.v, want.xi2, want.xi3, \
        ref.TE_bar
    twin = twins.ideal_twin(src)
    assert twin.sim.feed.bearing_drag > 0.0 and not keeps_any_speed(twin.sim)
    sim, rec = _run(twin, 20.0)
    assert not sim.piston.starting
    assert _window(rec, 18.0, 20.0) == pytest.approx(a.speed, rel=0.005)
