"""The apparatus level kind, variant 'fold' (the paper's full arrangement).

What is asserted is what the simulation does (``docs/apparatus.md``, "Fold
variant"): the floor preset's chain (2 cm links, dt 0.5 ms, **20 iterations**),
``xi2 = xi3 = 1/2`` (the paper's special case), upper cart 17.5 g and lower
cart 41 g on 30 deg tracks. The rig laws re-measured at 20 iterations
(``benchmarks/pickup_study.py --pickup-2cm/--putdown-2cm --iterations 20``: pick-up
``0.305 + 0.65*Tbar_uc``, put-down ``0.143 + 0.76*Tbar_lc`` at 3 m/s) are those of
10 iterations within their scatter; their balance ``T_in = T_exit`` asks for a 34 g
lower cart, with which the chain slows (-0.07 m/s per s) since the apparatus's
put-down entry tension is about 0.06 ``lambda*v**2`` below the rig's; 41 g is the
measured balance (36.7 and 39.5 g slow down, 42 and 46 g speed up and lose the
catch). The lower channel is a frictionless joint guide (slide joints to the bend
centres, grooves on the straight parts and the lower plate); the folding roller
lays the chain back to rest.

Over the clean part of the run (0.2-1.7 s) the rollers roll at half the chain
speed, the speed is steady and the tensions are in the paper's ranges. From
about 1.8 s (about 146 links in the lower plate grooves; 110 at 10 iterations,
180 at 30) the first turn's slide joints yield outward and the run collapses by
2.5 s (strict xfail), as in the 'open' variant with a long grooved tail.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus import report

LEVEL = Path(__file__).resolve().parents[1] / "levels" / "apparatus_floor.toml"
CLEAN = (0.2, 1.7)
RUN = 2.6
ITERATIONS = 20


@pytest.fixture(scope="module")
def run():
    cfg = io.load(LEVEL).sim
    a = dataclasses.replace(cfg.apparatus, variant="fold", xi2=0.5, xi3=0.5, plate_links=0,
                            end_tension=0.17, speed=3.0, duration=5.5)
    carts = (dataclasses.replace(cfg.carts[0], mass=0.0175),
             dataclasses.replace(cfg.carts[0], mass=0.041))
    solver = dataclasses.replace(cfg.solver, iterations=ITERATIONS)
    sim = Simulation(dataclasses.replace(cfg, apparatus=a, carts=carts, solver=solver))
    rec = Recorder(sim, profiles=False)
    sim.advance(CLEAN[1])
    rep = report(sim, rec, *CLEAN)
    held = []
    while sim.time < RUN - 1e-9:
        sim.advance(0.1)
        held.append(len(sim.apparatus._gq[0]))
    return sim, rep, held


def test_fold_builds_a_joint_guide(run) -> None:
    sim, rep, _ = run
    app = sim.apparatus
    assert app.variant == "fold" and app.fold_guided and app.lower is not None
    assert [e.kind for e in app.guide] == ["arc", "line", "arc", "line"]
    assert rep["fold"]["released_links"] > 40  # chain laid back to rest


def test_fold_rollers_roll_at_half_the_chain_speed(run) -> None:
    _, rep, _ = run
    m = rep["measured"]
    # paper: v_R = v/(1 + cos alpha) = v/2 at alpha = 0; measured 0.5003 and 0.5017
    assert m["roller_ratio_up"] == pytest.approx(0.5, abs=0.01)
    assert m["roller_ratio_lo"] == pytest.approx(0.5, abs=0.01)


def test_fold_speed_steady_while_clean(run) -> None:
    _, rep, _ = run
    m = rep["measured"]
    assert m["v"] == pytest.approx(3.0, rel=0.02)  # measured 2.985
    assert abs(m["speed_drift_per_s"]) <= 0.01  # measured +0.4 %/s over 1.5 s


@pytest.mark.xfail(strict=True, reason="vertex 0.1347 m against the catenary through the "
                   "ends 0.1319 m: +2.1 % over 0.2-1.7 s (0.5-s windows -0.3 ... +3.3 %; "
                   "10 iterations over 0.2-1.3 s: +1.4 %); docs/apparatus.md")
def test_fold_vertex_on_the_catenary_through_the_ends(run) -> None:
    _, rep, _ = run
    assert abs(rep["catenary"]["vertex_y_rel_error"]) <= 0.02


def test_fold_tensions_in_the_papers_ranges(run) -> None:
    _, rep, _ = run
    r = rep["paper_ranges"]
    assert r["TE_in_range"] and r["T0_in_range"]  # measured 0.242, 0.663


@pytest.mark.xfail(strict=True, reason="Tbar_0 - Tbar_E = 0.421 against k*H = 0.551 over "
                   "0.2-1.7 s (10 iterations: 0.450 against 0.547; 'open': 0.47 against "
                   "0.58); docs/apparatus.md")
def test_fold_fountain_carries_kH(run) -> None:
    _, rep, _ = run
    m = rep["measured"]
    assert m["T0_bar"] - m["TE_bar"] == pytest.approx(m["kH"], abs=0.06)


@pytest.mark.xfail(strict=True, reason="the first turn's slide joints yield outward from "
                   "about 1.8 s at 20 iterations (2 -> 16 mm beyond R by 2.3 s, with about "
                   "146 links in the lower plate grooves), the turn empties by 2.5 s and "
                   "the run collapses; docs/apparatus.md")
def test_fold_guide_holds_for_2_6s(run) -> None:
    _, _, held = run
    assert min(held) >= 15
