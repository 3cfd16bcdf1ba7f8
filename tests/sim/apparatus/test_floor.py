"""The apparatus level kind, variant 'floor' (paper: idealized beaker, real floor).

What is asserted is what the simulation does (``docs/apparatus.md``):

- the level loads, round-trips and builds; the chain starts at ``v0`` and the
  pick-up roller rolls at about half the chain speed (paper ``v/(1 + cos 0)``);
- the tension gained in the upper guide (a frictionless joint guide,
  ``upper_guide = "joints"``, in this preset) is the weight of the rise,
  ``Tbar_0 - Tbar_exit = xi2*k*H`` (paper's ``Tbar_0 = p + Tbar_uc + xi2*k*H``),
  within the scatter of the readings;
- summary.json carries the measured and predicted quantities side by side;
- with the absorbing floor (free end, Tbar_E = 0) the fountain becomes steady
  and its speed selects itself, ``v**2 = (g*H*(1 - xi2) - G*F_uc/lambda)/p``;
  the paper's ``p = 1/2, G = 1`` predicts a speed 23 % too slow;
- the pick-up's exit tension is the rig's for these links
  (:data:`~chainfountain.sim.apparatus.PICKUP_RIG_2CM`, ``CART_GAIN_2CM``) at the
  measured speed and cart (0.3695 against 0.3686);
- but the chain runs 2.4 % below the speed the rig law selects (3.071 +- 0.013 m/s;
  strict expected failure): the rig law assumes an ideal guide;
- the energy budget (:class:`~chainfountain.sim.budget.EnergyBudget`, an exact impulse
  sweep from the free end) finds where the rest goes: 0.0159 ``lambda v**3`` is lost
  between the plate and the free end, most of it (0.0108) in the upper guide's arc,
  whose velocity-level slide joints are not energy-neutral on a discrete curved path;
  with that loss added to ``p_inf`` the rig law gives 2.983 m/s (+0.4 %, within two
  sigma). The rig law read through biased contacts predicts 3.034 (-1.2 %, within two
  sigma), close by chance.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from chainfountain.headless import run_level
from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation, placement
from chainfountain.sim.apparatus_report import report
from chainfountain.sim.budget import EnergyBudget, rig_law_speed
from chainfountain.sim.guide import PLAY
from tests import shipped
from tests.sim.apparatus.runs import load_on_path

LEVEL = shipped.path("apparatus_floor")
RUN = 6.0
STEADY = (3.0, RUN)
REST = (6.0, 16.0)
"""The window read from the level's own start, from rest: the starter lets go about 4 s in."""


pytestmark = pytest.mark.xdist_group("apparatus_floor")
"""The module-scoped run is computed once, on one worker (``--dist loadgroup``)."""


@pytest.fixture(scope="module")
def run():
    lvl = load_on_path(LEVEL)
    sim = Simulation(lvl.sim)
    rec = Recorder(sim, profiles=False)
    EnergyBudget(sim, start=STEADY[0], every=2)  # sim.probe: read by the budget tests
    off: list[float] = []  # guided link centres' distances from the upper guide's line
    while sim.time < RUN - 1e-9:
        sim.advance(0.5)
        off += _guide_offsets(sim.apparatus)
    return lvl, sim, rec, np.array(off)


@pytest.fixture(scope="module")
def from_rest():
    """The level as shipped: at rest, run up by its starter, then on its own."""
    sim = Simulation(io.load(LEVEL).sim)
    rec = Recorder(sim, profiles=False)
    v_max0 = max(lk.body.velocity.length for lk in sim.chain.links)
    let_go = None
    while sim.time < REST[1] - 1e-9:
        sim.advance(0.25)
        if let_go is None and not sim.apparatus.starting:
            let_go = sim.time
    return sim, rec, v_max0, let_go


def _guide_offsets(app) -> list[float]:
    """Distance (m) of each link held by the upper joint guide from its element."""
    out = []
    for el, q in zip(app.up_guide, app.upper_held, strict=True):
        for lk, _ in q:
            p = lk.body.position
            if el.form == "arc":
                out.append(abs(math.hypot(p.x - el.a[0], p.y - el.a[1]) - el.R))
            else:
                (ax, ay), (bx, by) = el.a, el.b
                ln = math.hypot(bx - ax, by - ay)
                out.append(abs((p.x - ax) * (by - ay) - (p.y - ay) * (bx - ax)) / ln)
    return out


def test_level_round_trips_and_is_apparatus() -> None:
    lvl = io.load(LEVEL)
    assert lvl.sim.kind == "apparatus" and lvl.sim.apparatus.variant == "floor"
    assert lvl.sim.initial.mode == "stub" and lvl.sim.apparatus.starter > 0  # a demo: from rest
    assert io.loads(io.dumps(lvl)) == lvl


def test_roller_rolls_at_half_the_chain_speed(run) -> None:
    lvl, sim, rec, _ = run
    m = report(sim, rec, 0.4, RUN)["measured"]
    assert m["v"] == pytest.approx(lvl.sim.apparatus.speed, rel=0.15)
    # paper: v_R = v/(1 + cos alpha) = v/2
    assert m["roller_ratio_up"] == pytest.approx(0.5, abs=0.02)


def test_channel_adds_the_weight_of_the_rise(run) -> None:
    lvl, sim, rec, _ = run
    m = report(sim, rec, 0.4, 1.2)["measured"]
    gain = m["T0_bar"] - m["T_pickup_exit_bar"]
    assert gain == pytest.approx(lvl.sim.apparatus.xi2 * m["kH"], abs=0.1)


def test_steady_speed(run) -> None:
    _, sim, rec, _ = run
    r = report(sim, rec, *STEADY)
    assert abs(r["measured"]["speed_drift_per_s"]) <= 0.01


def test_speed_selects_itself_far_from_the_papers_p(run) -> None:
    """Paper: steady needs Tbar_0 = k*H (free end) = p + G*Tbar_uc + xi2*k*H. With the
    paper's ``p = 1/2, G = 1`` that predicts a speed 23 % lower than the chain runs at:
    the discrete chain's pick-up needs less than ``lambda v^2/2`` (rig law ``p(v)``)."""
    _, sim, rec, _ = run
    sel = report(sim, rec, *STEADY)["speed_selection"]
    assert sel["rel_error_paper"] > 0.2


def test_pickup_exit_tension_is_the_rig_law(run) -> None:
    """Exit tension on the grooved plate against the rig law at the measured speed and
    cart force: within 0.015 ``lambda v^2``, twice the single rig runs' scatter about
    the law (0.0065) plus its uncertainty (0.002). Measured 0.3695 against 0.3686."""
    from chainfountain.sim.apparatus import CART_GAIN_2CM, pickup_rig_2cm

    _, sim, rec, _ = run
    m = report(sim, rec, *STEADY)["measured"]
    law = pickup_rig_2cm(m["v"]) + CART_GAIN_2CM * m["Tbar_uc"]
    assert m["T_pickup_exit_bar"] == pytest.approx(law, abs=0.015)


@pytest.mark.xfail(strict=True, reason="measured 2.997 m/s against the rig law's 3.071 +- "
                   "0.013 (-2.4 %): the law assumes an ideal guide; the energy budget finds "
                   "0.0159 lambda v^3 lost in the discrete guide and grooves, and with it "
                   "the law agrees (next test); docs/apparatus.md, 'Energy budget'")
def test_speed_selects_itself_within_two_sigma(run) -> None:
    _, sim, rec, _ = run
    assert sim.config.apparatus.upper_guide == "joints"
    sel = report(sim, rec, *STEADY)["speed_selection"]
    assert abs(sel["v_measured"] - sel["v_rig_2cm"]) <= 2.0 * sel["v_rig_2cm_sigma"]


def test_energy_budget_sweep_is_exact(run) -> None:
    """The budget's impulse sweep closes: for every free link the angular momentum
    equation left over after the sweep holds to rounding (measured 1.2e-19 N m s against
    link impulses ``I dw`` of order 1e-6)."""
    _, sim, _, _ = run
    b = sim.probe.result()
    assert b.steps > 2000
    assert b.rotation_residual < 1e-15 and b.exact


def test_energy_budget_refuses_what_it_cannot_sweep() -> None:
    """The sweep knows joints and grooves only: a guide of walls (contacts off the link
    centres) is refused with a message, not measured wrongly."""
    import dataclasses

    cfg = load_on_path(LEVEL).sim
    walls = dataclasses.replace(cfg.apparatus, upper_guide="walls", plate="contact")
    with pytest.raises(ValueError, match="upper_guide = 'joints'"):
        EnergyBudget(Simulation(dataclasses.replace(cfg, apparatus=walls)))
    with pytest.raises(ValueError, match="every must be >= 1"):
        EnergyBudget(Simulation(cfg), every=0)


def test_speed_is_the_rig_law_with_the_measured_losses(run) -> None:
    """The losses the energy budget finds between the plate and the free end (the
    discrete guide and grooves; no tension reading involved), added to the rig law's
    ``p_inf``, give the measured speed within two sigma of the law (measured 2.996
    against 2.983 m/s, +0.4 %; loss 0.0159 ``lambda v**3``; without it the law is
    3.071, -2.4 %). docs/apparatus.md, "Energy budget"."""
    _, sim, rec, _ = run
    sel = report(sim, rec, *STEADY)["speed_selection"]
    loss = sim.probe.result().total
    assert 0.0 < loss < 0.05
    assert abs(sel["v_measured"] - rig_law_speed(sim.config, loss)) \
        <= 2.0 * sel["v_rig_2cm_sigma"]


def test_the_guides_arc_takes_most_of_the_loss(run) -> None:
    """The upper guide's arc (its slide joints and the pivots there) loses more than
    the grooves, the straights and the flight together (measured 0.0108 of 0.0159
    ``lambda v**3``): a velocity-level constraint on a discrete curved path is not
    energy-neutral (the loss scales as 1/R: research/energy_budget.py --radius)."""
    _, sim, _, _ = run
    b = sim.probe.result()
    assert b.region("arc") > b.total - b.region("arc")


def test_end_tensions_in_paper_ranges(run) -> None:
    _, sim, rec, _ = run
    r = report(sim, rec, *STEADY)
    m = r["measured"]
    assert 0.0 <= m["TE_bar"] < 0.05  # free end: only the end link's own inertia
    assert 0.5 < m["T0_bar"] < 1.0
    assert m["T0_bar"] - m["TE_bar"] == pytest.approx(m["kH"], abs=0.03)


def test_vertex_on_catenary_through_ends(run) -> None:
    _, sim, rec, _ = run
    c = report(sim, rec, *STEADY)["catenary"]
    assert abs(c["vertex_y_rel_error"]) <= 0.02


def test_summary_has_measured_and_predicted(tmp_path) -> None:
    lvl = load_on_path(LEVEL)
    s = json.loads(run_level(lvl, tmp_path, 0.3, progress=False).read_text())
    a = s["apparatus"]
    for k in ("T0_bar", "TE_bar", "k", "xi2", "Tbar_uc", "pickup_p", "speed_drift_per_s"):
        assert k in a["measured"], k
    for part in ("predicted_paper", "predicted_measured_laws"):
        assert "T0_bar" in a[part] and "v_steady" in a[part]
    assert "vertex_y_through_ends" in a["catenary"]
    assert s["kind"] == "apparatus" and s["H"] == lvl.sim.apparatus.drop


def test_live_cart_mass_and_views() -> None:
    sim = Simulation(load_on_path(LEVEL).sim)
    sim.set_param("carts[0].mass", 0.01)
    assert sim.apparatus.upper.force == pytest.approx(0.01 * 9.81 * math.sin(math.radians(30)))
    assert len(placement.rollers(sim)) == 1 and placement.walls(sim)
    assert placement.floor(sim)[3] == "absorbing" and sim.apparatus.upper.cart is not None
    with pytest.raises(KeyError):
        sim.set_param("carts[1].mass", 0.01)


def test_solid_end_builds_a_floor() -> None:
    """``end = "solid"``: the old static floor (the pile pushes back, not steady)."""
    cfg = load_on_path(LEVEL).sim
    cfg.apparatus.end = "solid"
    sim = Simulation(cfg)
    assert sim.apparatus.floor is not None and placement.floor(sim)[3] == "solid"


def test_upper_channel_is_a_joint_guide_without_shapes(run) -> None:
    """``upper_guide = "joints"``: no wall in the space (drawn only), no link shape in the
    guide, links held on the centre line: on the straights within micrometres, on the
    bend within its 1 mm play (they ride on the outer limit, as on the walls' outer
    wall: the tension is below ``lambda v^2``, so the bend must push the chain inward);
    a link just handed from the bend to the straight still carries the play (measured
    1.006 mm)."""
    _, sim, _, off = run
    app = sim.apparatus
    assert app.upper_guided and app.walls and all(w.space is None for w in app.walls)
    held = [lk for q in app.upper_held for lk, _ in q]
    # the guide's 0.31 m past the plate grooves hold 15-16 links
    assert len(held) >= 14 and all(lk.shape.space is None for lk in held)
    assert len(off) > 150 and off.max() <= PLAY + 1e-4


def test_joint_guide_adds_the_weight_of_the_rise_in_the_steady_window(run) -> None:
    """Frictionless: ``T0 - T_exit = xi2 k H``; measured 0.170 against 0.164 (the heavy
    preset: 0.183 against 0.195). The exit tension is read from the pivots on the grooved
    plate; the sum through the pick-up roller's uncorrected contacts reads 0.185 (0.180),
    biased by pymunk's stale impulses of contacts that touch again (docs/apparatus.md,
    "Contact impulses"). The tolerance is that contact reading's scatter between
    equivalent runs, 0.161-0.196 against 0.164-0.165 in ten runs with the release point
    (0-1 link) or the start speed changed (research/notes/apparatus_notebook.md, "the
    upper channel as a joint guide"):
    it catches a reconstruction gone wrong (without the upstream sum the exit tension read
    0.92, the gain -0.25) but cannot resolve the walls' drag of about 0.02, which the 2 %
    faster chain shows."""
    _, sim, rec, _ = run
    m = report(sim, rec, *STEADY)["measured"]
    assert m["T0_bar"] - m["T_pickup_exit_bar"] == pytest.approx(m["xi2"] * m["kH"], abs=0.04)


@pytest.mark.slow
def test_too_heavy_a_cart_stops_the_chain_with_one_plain_sentence(tmp_path):
    """A 30 g upper cart holds the chain back harder than the fall pulls it on: once the
    starter lets go (about 4 s in) the chain slows and stops, and the run ends saying so
    and what to change (not a chain left hanging with no message). A level file with that
    cart is refused before it runs (``test_start_region.py``); run anyway
    (``apparatus.start_region = "unchecked"``), as a cart changed live is, it stops so."""
    import chainfountain

    r = chainfountain.run("apparatus_floor", duration=12,
                          changes={"carts[0].mass": 0.03,
                                   "apparatus.start_region": "unchecked"},
                          out=tmp_path / "o")
    ended = r.summary["ended_early"]
    assert ended is not None and ended["cause"] == "machine"
    assert "the chain has stopped" in ended["reason"]
    assert "upper cart 30 g" in ended["reason"] and "carts[0].mass" in ended["reason"]
    assert "\n" not in ended["reason"]


@pytest.mark.slow
def test_forms_from_rest_and_selects_the_same_speed(run, from_rest) -> None:
    """The shipped level starts at rest; the starter runs the chain up, lets go 3 s after
    it lands (about 4 s in), and the machine alone then holds the speed it selects: over
    6-16 s it drifts less than issue 36's 0.2 %/s and runs at the speed of the study start
    (laid along the path at 2.98 m/s, 3-6 s) within 1.5 %, the spread of 10-s window means
    in 600-s runs from either start (2.95-2.99 m/s; research/contact_holds.py)."""
    sim, rec, v_max0, let_go = from_rest
    assert v_max0 == 0.0
    assert let_go is not None and 3.0 < let_go < 6.0
    rest = report(sim, rec, *REST)["measured"]
    _, sim1, rec1, _ = run
    path = report(sim1, rec1, *STEADY)["measured"]
    assert abs(rest["speed_drift_per_s"]) < 0.002
    assert rest["v"] == pytest.approx(path["v"], rel=0.015)
    assert rest["roller_ratio_up"] == pytest.approx(0.5, abs=0.02)


@pytest.mark.parametrize("change, field", [
    ({"apparatus.starter": 0.0}, "apparatus.starter"),
    ({"initial.mode": "catenary"}, "apparatus.starter"),
    ({"apparatus.variant": "open"}, "apparatus.variant"),
    ({"apparatus.variant": "fold"}, "apparatus.fold_roller"),  # the contact fold
    ({"apparatus.upper_guide": "walls"}, "apparatus.upper_guide"),
    ({"initial.jitter": 0.01}, "initial.jitter"),
    ({"apparatus.swing_damper": 0.5}, "apparatus.swing_damper"),
])
def test_a_start_that_cannot_work_is_refused_naming_the_field(change, field) -> None:
    """From rest without a starter the carts hold the chain and nothing falls; a starter
    with the study start does nothing; only the floor variant and the gripped fold, with
    the joint guide, can start from rest."""
    from chainfountain.level.model import LevelError
    from chainfountain.study.changes import with_changes

    with pytest.raises(LevelError, match=field.replace(".", r"\.")):
        with_changes(io.load(LEVEL), change)


def test_the_starter_runs_a_short_rise_up_and_says_when_it_cannot(monkeypatch) -> None:
    """With a short rise (xi2 = 0.2) the guide's last straight holds one link; the starter
    drives every link of the guide, so the chain still lands within 1 s. A chain that has
    not landed within ``LAND_WITHIN`` s ends the run with one sentence (here forced by a
    limit of 0.2 s), not a machine left standing with no message."""
    from chainfountain.sim.apparatus import starter
    from chainfountain.study.changes import with_changes

    sim = Simulation(with_changes(io.load(LEVEL), {"apparatus.xi2": 0.2}).sim)
    sim.advance(1.0)
    assert sim.apparatus.absorbed > 0 and sim.apparatus.speed > 2.5
    monkeypatch.setattr(starter, "LAND_WITHIN", 0.2)
    sim = Simulation(io.load(LEVEL).sim)
    with pytest.raises(starter.StarterFailed, match="the starter could not run the chain up"):
        sim.advance(0.5)
