"""Simulation object: determinism, commands, views, config metadata, helpers."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pymunk
import pytest

from chainfountain.sim import (
    LaunchReference,
    Recorder,
    RollerConfig,
    SimConfig,
    Simulation,
    placement,
)
from chainfountain.sim import config as cfgmod
from chainfountain.sim.measure import fit_catenary, steady_time, vertex_of


def _short() -> SimConfig:
    """wide_low's fountain (4 m/s, 60 deg, 0.5 m drop), started on the catenary."""
    return SimConfig(feed=cfgmod.FeedConfig(speed=4.0, launch_angle=math.radians(60.0),
                                            drop=0.5, floor_width=4.0))


def test_reference_matches_physics_notes() -> None:
    """v=5, H=1, alpha0=75 deg: h = 1.148 m, vertex 0.813 m downstream (physics.md)."""
    r = LaunchReference.from_launch(5.0, math.radians(75.0), 1.0, 9.81)
    assert r.h == pytest.approx(1.148, abs=5e-4)
    assert r.x_rise == pytest.approx(0.813, abs=5e-4)
    assert r.T0_bar == pytest.approx(r.k * 1.0)
    x, y, _ = r.points_at_arc(np.array([0.0, r.arc_length]))
    assert x[0] == pytest.approx(0.0, abs=1e-12) and y[0] == pytest.approx(0.0, abs=1e-12)
    assert y[1] == pytest.approx(-1.0, abs=1e-9) and x[1] == pytest.approx(r.landing_x)


def test_every_config_field_is_declared() -> None:
    """All numeric fields carry unit and doc metadata for the level loader."""
    for cls in (cfgmod.ChainConfig, cfgmod.FeedConfig, cfgmod.SolverConfig,
                cfgmod.InitialConfig, cfgmod.RecordingConfig, cfgmod.RollerConfig,
                cfgmod.CartConfig, cfgmod.SimConfig):
        for f in dataclasses.fields(cls):
            if f.type in ("float", "int", "str", "bool"):
                assert "unit" in f.metadata and f.metadata["doc"], (cls.__name__, f.name)


def test_runs_are_deterministic() -> None:
    a, b = Simulation(_short()), Simulation(_short())
    a.advance(0.3)
    b.advance(0.3)
    assert np.array_equal(a.chain_polyline(), b.chain_polyline())


def test_seed_changes_the_start() -> None:
    c1, c2 = _short(), _short()
    c2.initial.seed = 1
    assert not np.array_equal(Simulation(c1).chain_polyline(), Simulation(c2).chain_polyline())


def test_reader_order_survives_feed_and_absorption() -> None:
    """Batch readout matches per-body attributes after many spawns and removals."""
    sim = Simulation(_short())
    sim.advance(0.5)
    assert sim.feed.absorbed > 10
    st = sim.state()
    for i in (0, 7, sim.n_links - 1):
        p = sim.chain.links[i].body.position
        assert st.position[i] == pytest.approx((p.x, p.y))
    pts = sim.chain_polyline()
    gaps = np.diff(pts, axis=0)
    assert np.allclose(np.hypot(gaps[:, 0], gaps[:, 1]), sim.chain.L, rtol=0.05)


def test_live_commands_and_reset() -> None:
    sim = Simulation(_short())
    sim.advance(0.1)
    sim.set_feed_speed(4.5)
    assert sim.reference.v == 4.5
    v_guide = sim.chain.links[-1].body.velocity
    assert math.hypot(*v_guide) == pytest.approx(4.5)
    sim.set_bending(stiffness=1e-3, damping=1e-5)
    assert all(lk.up_spring is not None for lk in sim.chain.links if lk.up_joint is not None)
    sim.advance(0.05)
    sim.set_bending(stiffness=0.0, damping=0.0)
    # only the wave damper stays, on joints between two moving links
    d_wave = sim.chain.wave_damping
    assert d_wave > 0.0
    for lk, up in zip(sim.chain.links, sim.chain.links[1:], strict=False):
        both = {lk.body.body_type, up.body.body_type} == {pymunk.Body.DYNAMIC}
        if lk.up_spring is None:
            assert not both
        else:
            assert both and lk.up_spring.stiffness == 0.0
            assert lk.up_spring.damping == pytest.approx(d_wave)
    sim.set_param("solver.iterations", 12)
    assert sim.space.iterations == sim.config.solver.iterations == 12
    sim.reset()
    assert sim.time == 0.0 and sim.config.feed.speed == 4.5


def test_drag_moves_a_link() -> None:
    sim = Simulation(_short())
    sim.advance(0.1)
    st = sim.state()
    i = sim.n_free // 2
    p = tuple(st.position[i])
    assert sim.grab(p) is not None and sim.dragging
    target = (p[0], p[1] + 0.2)
    for _ in range(400):
        sim.drag_to(target)
        sim.step()
    sim.release()
    assert not sim.dragging


def test_views_and_building_blocks() -> None:
    cfg = _short()
    cfg.feed.floor = "solid"
    cfg.feed.chain_length = 3.0
    cfg.rollers = (RollerConfig(x=1.0, y=-0.3, radius=0.05, angular_speed=2.0),)
    cfg.carts = (cfgmod.CartConfig(x=-1.0, y=-0.3, incline=0.3),)
    sim = Simulation(cfg)
    sim.advance(0.2)
    assert sim.chain.shapes
    y, x0, x1, mode = placement.floor(sim)
    assert mode == "solid" and y == -cfg.feed.drop and x0 < x1
    (rx, ry, rr, _), = placement.rollers(sim)
    assert (rx, ry, rr) == (1.0, -0.3, 0.05)
    cart = sim.carts[0]
    assert len(cart.shape.get_vertices()) == 4 and cart.track_start != cart.track_end
    front, back = sim.link_endpoints()
    assert front.shape == back.shape == (sim.n_links, 2)
    sim.set_param("rollers[0].angular_speed", -3.0)
    assert sim.rollers[0].body.angular_velocity == sim.config.rollers[0].angular_speed == -3.0


def test_finite_chain_runs_out() -> None:
    cfg = _short()
    cfg.feed.chain_length = 0.5
    sim = Simulation(cfg)
    sim.advance(1.0)
    assert sim.feed.n_guide == 0 and sim.n_links == 0


def test_recorder_samples_and_summary() -> None:
    sim = Simulation(_short())
    rec = Recorder(sim)
    sim.advance(0.3)
    assert len(rec.samples) == pytest.approx(0.3 / rec.cfg.sample_interval, abs=1)
    s = rec.summary(window=0.2)
    assert s.samples > 5 and math.isfinite(s.tension_rms) and math.isfinite(s.q_fit)


def test_steady_time_and_fits() -> None:
    t = np.linspace(0.0, 10.0, 1001)
    y = 1.0 + 0.5 * np.exp(-t)  # within 1 % of 1 from t = ln(50) = 3.91
    ts = steady_time(t, y, 0.01, smoothing=0.0, window=1.0)
    assert ts == pytest.approx(math.log(50.0), abs=0.02)
    assert steady_time(t, np.sin(t), 0.01) is None
    q, xv, yv = 2.3, 0.4, 1.1
    x = np.linspace(-0.5, 1.5, 80)
    pts = np.column_stack((x, yv + (1.0 - np.cosh(q * (x - xv))) / q))
    assert vertex_of(pts) == pytest.approx((xv, yv), abs=1e-3)
    assert fit_catenary(pts, 0.3, 1.0, 1.0) == pytest.approx((xv, yv, q), rel=1e-6)


def test_unsupported_kind() -> None:
    cfg = SimConfig()
    cfg.kind = "bogus"
    with pytest.raises(ValueError, match="bogus"):
        Simulation(cfg)


def test_recorder_thins_profiles_evenly() -> None:
    """A bounded recorder keeps evenly spaced profiles and the same window averages."""
    cfg = _short()
    full = Simulation(cfg)
    rec_full = Recorder(full)
    bounded = Simulation(cfg)
    rec = Recorder(bounded, max_profiles=16)
    for sim in (full, bounded):
        sim.advance(1.2)
    n = len(rec.samples)
    assert n == len(rec_full.samples) and n > 40
    assert len(rec_full.profiles) == n
    assert 8 <= len(rec.profiles) <= 16
    gaps = np.diff([p.t for p in rec.profiles])
    assert np.allclose(gaps, gaps[0], rtol=1e-6)
    stride = gaps[0] / (rec.every * bounded.dt)  # samples per kept profile: a power of two
    assert stride >= 2 and math.log2(stride) == pytest.approx(round(math.log2(stride)), abs=1e-6)
    assert rec.profiles[-1].t >= rec.samples[-1].t - stride * rec.every * bounded.dt
    a, b = rec_full.summary(window=1.0), rec.summary(window=1.0)
    assert b.vertex_y == a.vertex_y  # scalar series are never thinned
    assert b.tension_rms == pytest.approx(a.tension_rms, abs=0.01)
    with pytest.raises(ValueError, match="max_profiles"):
        Recorder(bounded, max_profiles=1)
