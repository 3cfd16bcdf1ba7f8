"""The public scene API (:class:`chainfountain.sim.scene.ChainScene`) at its default
solver: a chain hanging at rest holds the weight below each point and the pin the whole
weight; a chain lying on a floor presses it with its weight; a released chain falls
freely; a scene's kinetic energy is that of its links; bad polylines and points are one
clear error. The closed forms of falling chains run through their levels
(``tests/sim/test_scene_levels.py``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from chainfountain.sim.scene import ChainScene

G, LAM = 9.81, 0.05


def test_hanging_chain_tension_is_the_weight_below() -> None:
    n, L = 60, 0.01
    pts = np.column_stack((1e-3 * np.arange(n + 1) * L, -L * np.arange(n + 1)))
    sc = ChainScene(pts, linear_density=LAM, bending_damping=2e-4)
    pin = sc.pin(0)
    sc.advance(1.0)
    T = np.mean([sc.step() or sc.tensions() for _ in range(200)], axis=0)
    weight_below = LAM * L * G * (n - np.arange(1, n))  # at points 1 .. n-1
    assert T == pytest.approx(weight_below, rel=0.01)
    assert sc.pin_force(pin) == pytest.approx(LAM * n * L * G, rel=0.01)
    assert np.abs(sc.velocities()).max() < 0.01


@pytest.mark.slow
def test_chain_on_a_floor_presses_with_its_weight() -> None:
    n, L = 40, 0.01
    pts = np.column_stack((L * np.arange(n + 1), np.full(n + 1, 0.002)))
    sc = ChainScene(pts, linear_density=LAM, collide=True)
    sc.add_floor(0.0)
    sc.advance(0.5)
    F = np.mean([sc.step() or sc.floor_force() for _ in range(200)], axis=0)
    assert F[1] == pytest.approx(-LAM * n * L * G, rel=0.01)
    assert abs(F[0]) < 0.01 * LAM * n * L * G


def test_release_lets_the_chain_fall_freely() -> None:
    pts = np.column_stack((np.zeros(11), -0.01 * np.arange(11)))
    sc = ChainScene(pts)
    pin = sc.pin(0)
    sc.advance(0.1)
    sc.release(pin)
    v0 = sc.velocities().mean(axis=0)
    sc.advance(0.1)
    assert (sc.velocities().mean(axis=0) - v0)[1] == pytest.approx(-G * 0.1, rel=1e-3)


@pytest.mark.parametrize("points, match", [
    ([(0, 0), (0.01, 0), (0.03, 0)], "same length"),
    ([(0, 0), (0.01, 0)], "at least 2 links"),
    ([(0, 0), (0.01, 0), (math.nan, 0)], "finite"),
])
def test_bad_polyline_is_one_clear_error(points, match) -> None:
    with pytest.raises(ValueError, match=match):
        ChainScene(points)


def test_pin_names_the_allowed_points() -> None:
    sc = ChainScene([(0, 0), (0.01, 0), (0.02, 0)])
    with pytest.raises(ValueError, match=r"point 3: allowed: 0 \.\. 2"):
        sc.pin(3)


def test_kinetic_energy_is_half_m_v_squared() -> None:
    pts = np.column_stack((0.01 * np.arange(11), np.zeros(11)))
    sc = ChainScene(pts, linear_density=LAM)
    sc.set_velocity(2.0, 0.0)
    assert sc.kinetic_energy() == pytest.approx(0.5 * LAM * 0.1 * 4.0, rel=1e-9)
