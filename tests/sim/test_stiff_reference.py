"""The fed level's theory switch (:mod:`chainfountain.sim.stiff_reference`): loose joints
are compared with the paper's catenary, stiff or damped ones with the steady stiff
fountain, read like the catenary; where there is none, the reference says why."""

from __future__ import annotations

import math

import numpy as np
import pytest

from chainfountain.sim import Simulation
from chainfountain.sim.reference import LaunchReference
from chainfountain.sim.stiff_reference import (
    StiffReference,
    headline,
    predict,
    stiff_applies,
)
from chainfountain.theory.stiff import NoSteadyFountain, stiff_fountain_of
from tests import shipped


def stiff_level(c: float = 0.015, d: float = 0.0006):
    lvl = shipped.level("stiff_chain")
    lvl.sim.chain.bending_stiffness = c
    lvl.sim.chain.bending_damping = d
    return lvl


@pytest.fixture(scope="module")
def stiff_sim() -> Simulation:
    return Simulation(stiff_level().sim)


def test_loose_joints_keep_the_catenary():
    sim = Simulation(shipped.level("wide_low").sim)
    assert type(sim.reference) is LaunchReference and sim.reference is sim.catenary
    assert sim.reference.theory == "catenary" and sim.reference_note == ""
    lvl = stiff_level(0.0, 0.0)
    assert not stiff_applies(lvl.sim)
    assert type(Simulation(lvl.sim).reference) is LaunchReference


def test_the_machines_keep_the_paper_s_string_model():
    lvl = shipped.level("ideal_floor")
    lvl.sim.chain.bending_stiffness = 0.01
    assert not stiff_applies(lvl.sim)


def test_stiff_joints_give_the_bvp_s_fountain(stiff_sim):
    ref, cfg = stiff_sim.reference, stiff_sim.config
    assert isinstance(ref, StiffReference) and ref.theory == "stiff"
    assert ref.label == "stiff-chain theory" and ref.catenary is stiff_sim.catenary
    ch, f = cfg.chain, cfg.feed
    bvp = stiff_fountain_of(ch.bending_stiffness, ch.bending_damping, ch.link_length,
                            ch.linear_density, f.speed, f.launch_angle, f.drop,
                            f.end_tension, cfg.gravity)
    assert ref.h == bvp.h and ref.vertex == (bvp.vertex_x, bvp.h)
    assert ref.landing_x == bvp.l and ref.T0_bar == bvp.T0_bar
    assert ref.delta > 0.0  # the damper is in the theory
    assert abs(ref.h / ref.catenary.h - 1.0) > 0.03  # and moves the fountain


def test_the_stiff_reference_reads_like_the_catenary(stiff_sim):
    ref = stiff_sim.reference
    f = ref.fountain
    x, y, a = ref.points_at_arc([0.0, ref.arc_length])
    assert (x[0], y[0], a[0]) == pytest.approx((0.0, 0.0, ref.alpha0), abs=1e-6)
    assert (x[1], y[1]) == pytest.approx((ref.landing_x, -ref.H), abs=1e-6)
    assert ref.y_of_x(ref.x_rise) == pytest.approx(ref.h)
    assert ref.x_rise + ref.x_fall == ref.landing_x
    xy = ref.curve(50)
    assert xy.shape == (50, 2) and xy[:, 1].max() <= ref.h + 1e-12
    i = len(f.s) // 3
    assert ref.tension_profile(f.x[i], f.y[i]) == pytest.approx(f.T_bar[i], rel=1e-3)
    assert ref.tension_bar(-ref.H) == pytest.approx(f.T_bar[-1], abs=1e-6)
    assert len(ref.thinned().s) <= 400 and ref.thinned().h == pytest.approx(ref.h, rel=1e-3)


def test_the_feed_drives_by_the_catenary(stiff_sim):
    """The comparison does not change the drive: the floor's pull and the launch spin are
    the catenary's, as for loose joints."""
    feed, cat = stiff_sim.feed, stiff_sim.catenary
    c = 1.0 / (1.0 + cat.q * (cat.h + cat.H))
    assert feed.end_dir[0] == pytest.approx(c)
    assert feed.launch_omega == pytest.approx(-cat.v * cat.q * math.cos(cat.alpha0) ** 2)


def test_a_live_change_of_the_joints_solves_again():
    sim = Simulation(stiff_level().sim)
    h0, version = sim.reference.h, sim.theory_version
    sim.set_param("chain.bending_stiffness", 0.05)
    assert sim.theory_version == version + 1 and sim.reference.c == 0.05
    assert sim.reference.h < 0.95 * h0  # stiffer joints: a lower arch
    sim.set_param("chain.bending_stiffness", 0.0)
    sim.set_param("chain.bending_damping", 0.0)
    assert type(sim.reference) is LaunchReference  # loose again: the catenary


def test_a_deferred_change_waits_for_refresh():
    sim = Simulation(stiff_level().sim, defer_theory=True)
    assert sim.reference is None and sim.theory_stale and sim.catenary is not None
    sim.refresh_theory()
    assert isinstance(sim.reference, StiffReference) and not sim.theory_stale
    old = sim.reference
    sim.set_param("chain.bending_stiffness", 0.04)
    assert sim.theory_stale and sim.reference is old
    sim.refresh_theory()
    assert sim.reference.c == 0.04 and not sim.theory_stale


def test_no_steady_fountain_is_said(monkeypatch):
    from chainfountain.sim import stiff_reference

    def none(*args, **kw):
        raise NoSteadyFountain("no steady stiff fountain found at e = 1 m^2: test")

    monkeypatch.setattr(stiff_reference, "stiff_fountain_of", none)
    lvl = stiff_level(0.03, 0.0)
    sim = Simulation(lvl.sim)
    assert sim.reference is None and sim.catenary is not None
    assert headline(sim.reference_note) == ("no steady stiff fountain at c = 0.03 N*m/rad, "
                                            "d = 0 N*m*s/rad")
    assert "no steady stiff fountain at c = 0.03" in sim.describe()
    pred = predict(lvl.sim, sim.catenary)
    assert pred.theory == "stiff" and pred.reference is None
    assert np.isfinite(sim.feed.launch_omega)  # the feed still drives by the catenary
