"""The linear model of the apparatus's stored-length mode (chainfountain.theory.swing)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from chainfountain.theory.swing import (
    fountain_spring,
    mode_matrix,
    stored_length,
    swing_mode,
)

RNG = np.random.default_rng(11)
PARAMS = [(float(m1), float(m2), float(K), float(v)) for m1, m2, K, v in zip(
    RNG.uniform(0.02, 0.3, 6), RNG.uniform(0.02, 0.3, 6), RNG.uniform(0.05, 2.0, 6),
    RNG.uniform(1.0, 6.0, 6), strict=True)]


def test_stored_length_is_the_catenary_arc() -> None:
    """Against the arc length of the inverted catenary ``y = -a cosh(x/a)`` integrated
    from the start (slope ``tan(theta)``) over the vertex to the point ``H`` below the
    start."""
    for a, theta, H in [(0.13, math.radians(60), 0.5), (0.4, math.radians(35), 2.0),
                        (0.05, math.radians(80), 0.1)]:
        x0 = -a * math.asinh(math.tan(theta))
        x1 = a * math.acosh(math.cosh(x0 / a) + H / a)
        arc, _ = quad(lambda x, a=a: math.cosh(x / a), x0, x1)
        assert stored_length(a, theta, H) == pytest.approx(arc, rel=1e-9)


def test_spring_of_the_presets_fountain() -> None:
    # a 60-deg fountain with a 0.13 m vertex, 0.5 m drop, 50 g/m: dS/da = 3.59
    K = fountain_spring(0.13, math.radians(60), 0.5, 0.05)
    assert K == pytest.approx(0.05 * 9.81 / (0.5 * 3.588), rel=1e-3)


@pytest.mark.parametrize("m1, m2, K, v", PARAMS)
def test_energy_rate_is_the_rig_laws_departure_from_the_paper(m1, m2, K, v) -> None:
    """``dE/dt = lambda v ((1 - 2p) dv1^2 - (1 - 2d) dv2^2)`` for any state: the velocity
    cross terms (the fountain's momentum flux) do no work."""
    lam = 0.05
    for p, d in [(0.5, 0.5), (0.28, 0.13), (0.7, 0.2)]:
        A = mode_matrix(m1, m2, K, lam, v, p, d)
        W = np.diag([m1, m2, K])
        for x in RNG.normal(size=(5, 3)):
            rate = x @ W @ (A @ x)
            want = lam * v * ((1 - 2 * p) * x[0] ** 2 - (1 - 2 * d) * x[1] ** 2)
            assert rate == pytest.approx(want, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("m1, m2, K, v", PARAMS)
def test_papers_laws_leave_the_mode_undamped(m1, m2, K, v) -> None:
    s = swing_mode(m1, m2, K, 0.05, v)  # p = d = 1/2
    assert abs(s.growth) < 1e-9 and abs(s.selection) < 1e-9
    assert math.isfinite(s.period)


def test_weaker_pick_up_law_feeds_the_mode_and_a_stronger_drains_it() -> None:
    args = (0.066, 0.097, 0.273, 0.05, 3.0)
    assert swing_mode(*args, p=0.4, d=0.5).growth > 0
    assert swing_mode(*args, p=0.6, d=0.5).growth < 0
    # a weaker put-down law drains it
    assert swing_mode(*args, p=0.5, d=0.3).growth < 0


def test_without_the_velocity_terms_the_period_is_the_spring_on_two_masses() -> None:
    m1, m2, K = 0.066, 0.097, 0.273
    s = swing_mode(m1, m2, K, 0.0, 3.0)
    assert s.period == pytest.approx(2 * math.pi / math.sqrt(K * (1 / m1 + 1 / m2)), rel=1e-9)
    assert s.ratio == pytest.approx(m2 / m1, rel=1e-9)  # momentum: m1 dv1 = -m2 dv2
    assert abs(abs(s.phase) - 180.0) < 1e-6
    # a delay feeds it at omega^2 tau / 2
    w = 2 * math.pi / s.period
    assert swing_mode(m1, m2, K, 0.0, 3.0, delay=0.04).growth == pytest.approx(0.02 * w * w)


def test_bad_parameters_are_refused() -> None:
    with pytest.raises(ValueError, match="theta"):
        stored_length(0.1, 2.0, 0.5)
    with pytest.raises(ValueError, match="m1, m2, K"):
        mode_matrix(0.0, 0.1, 0.2, 0.05, 3.0)
