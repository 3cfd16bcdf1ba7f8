"""The apparatus level kind, variant 'fold' (the paper's full arrangement).

What is asserted is what the simulation does (``docs/apparatus.md``, "Fold
variant") with the `apparatus_fold` preset: the floor preset's chain (2 cm links,
dt 0.5 ms, **20 iterations**),
``xi2 = 0.5``, ``xi3 = 0.303`` (the lower plate 0.15 m above the fountain end; the
paper's special case ``xi3 = 1/2`` is `apparatus_special`, with a 58 g lower cart), upper cart
17.5 g and lower
cart 41 g on 30 deg tracks (41 g is the measured balance, with the upper channel's
walls; the rig laws' balance ``T_in = T_exit`` asks for 34 g, with which the chain
slows). The upper channel is a frictionless joint guide (``upper_guide = "joints"``;
the figures with the walls are in brackets). The lower
channel is
a frictionless joint guide (slide joints to the bend centres with the positions
projected back onto their limits every step, grooves on the straight parts and
the lower plate); the folding roller lays the chain back to rest. A link landing
off the turn's radius is brought onto it within about 12 ms (a stiff funnel,
``Apparatus.fold_close_rate`` = 5 m/s; at 0.5 m/s the landing swing grew faster).

Over 0.2-2.5 s the rollers roll at half the chain speed, the speed is 3.0 m/s
and steady within the 1 %/s target (+0.79 %/s; +0.81), the fountain's mean shape is
the catenary through its measured ends and the tensions are in the paper's ranges.
The fountain's landing point wanders by a few centimetres with a period of about
2-3 s, so in 0.5-s windows the vertex is off the catenary by several per cent
(strict xfail: +1.1, -2.7, -4.2, -1.2, +4.7 % over 0.5-3.0 s; with the walls +1.8,
-2.6, -4.6, +0.5, +9.0 %, which is why the steady window ends at 2.5 s). The turn
holds to the end of the run (3 s).
"""

from __future__ import annotations

import pytest

from tests import shipped
from tests.sim.apparatus.runs import load_real_geometry, run_fold

LEVEL = shipped.path("apparatus_fold")
CLEAN = (0.2, 2.5)
RUN = 3.0
WINDOWS = [(0.5 * i, 0.5 * i + 0.5) for i in range(1, 6)]


pytestmark = pytest.mark.xdist_group("apparatus_fold")
"""The module-scoped run is computed once, on one worker (``--dist loadgroup``)."""


@pytest.fixture(scope="module")
def run():
    cfg = load_real_geometry(LEVEL).sim
    a = cfg.apparatus
    assert (a.variant, a.xi2, a.xi3, a.plate_links, a.pickup_rest_links,
            cfg.solver.iterations, a.upper_guide) == ("fold", 0.5, 0.303, 0, 8, 20, "joints")
    assert [c.mass for c in cfg.carts] == [0.0175, 0.041]
    return run_fold(cfg, RUN, CLEAN, WINDOWS)


def test_fold_builds_a_joint_guide(run) -> None:
    sim, rep, _, _ = run
    app = sim.apparatus
    assert app.variant == "fold" and app.fold_guided and app.lower is not None
    assert [e.form for e in app.guide] == ["arc", "line", "arc", "line"]
    assert rep["fold"]["released_links"] > 40  # chain laid back to rest


def test_fold_rollers_roll_at_half_the_chain_speed(run) -> None:
    _, rep, _, _ = run
    m = rep["measured"]
    # paper: v_R = v/(1 + cos alpha) = v/2 at alpha = 0; measured 0.5008 and 0.5016
    # (walls 0.5004, 0.5010)
    assert m["roller_ratio_up"] == pytest.approx(0.5, abs=0.01)
    assert m["roller_ratio_lo"] == pytest.approx(0.5, abs=0.01)


def test_fold_speed_at_the_design_speed(run) -> None:
    _, rep, _, _ = run
    assert rep["measured"]["v"] == pytest.approx(3.0, rel=0.02)  # measured 3.008 (3.010)


def test_fold_speed_steady_while_clean(run) -> None:
    _, rep, _, _ = run
    # measured +0.79 %/s (walls: +0.81 %/s; +0.62 %/s with 20 resting links ahead of the
    # pick-up; +1.15 %/s with the old soft catch, fold_close_rate 0.5 m/s)
    assert abs(rep["measured"]["speed_drift_per_s"]) <= 0.01


def test_fold_guide_holds_the_turn(run) -> None:
    _, _, held, _ = run
    # links in the first turn, every 0.1 s: 18-19 while the chain runs through it (19-20)
    # (before the projection onto the slide joints' limits the turn emptied at 2.5 s)
    assert min(held) >= 15


def test_fold_vertex_on_the_catenary_through_the_ends(run) -> None:
    _, rep, _, _ = run
    # the mean fountain over 0.2-2.5 s: measured -1.52 % (walls -0.99 %)
    assert abs(rep["catenary"]["vertex_y_rel_error"]) <= 0.02


@pytest.mark.xfail(strict=True, reason="the landing point wanders (period about 2-3 s, "
                   "growing with the channel's walls): in 0.5-s windows the vertex is -4.2 ... "
                   "+4.7 % off the catenary through that window's ends (walls: -4.6 ... "
                   "+9.0 %); docs/apparatus.md")
def test_fold_vertex_on_the_catenary_in_every_half_second(run) -> None:
    _, _, _, windows = run
    assert all(abs(w["catenary"]["vertex_y_rel_error"]) <= 0.02 for w in windows)


def test_fold_tensions_in_the_papers_ranges(run) -> None:
    _, rep, _, _ = run
    r = rep["paper_ranges"]
    assert r["TE_in_range"] and r["T0_in_range"]  # measured 0.176, 0.718 (walls 0.183, 0.703)


def test_fold_fountain_carries_kH(run) -> None:
    _, rep, _, _ = run
    m = rep["measured"]
    # steady state: Tbar_0 - Tbar_E = k*H (energy); measured 0.542 against 0.542 (walls:
    # 0.519 against 0.541; 0.554 with 20 resting links ahead of the pick-up; with the
    # old soft catch 0.591
    # against 0.540, before the projection 0.421 against 0.551)
    assert m["T0_bar"] - m["TE_bar"] == pytest.approx(m["kH"], abs=0.06)
