"""Biggins and Warner's relations for a chain fountain out of a pot
(:mod:`chainfountain.theory.mould`)."""

from __future__ import annotations

import math

import pytest

from chainfountain.theory.mould import alpha_from_rise, alpha_from_speed, bw_rise, bw_speed


@pytest.mark.parametrize("alpha, beta", [(0.0, 0.0), (0.2, 0.0), (0.15, 0.1), (0.5, 0.0)])
def test_speed_and_rise_give_back_alpha(alpha, beta):
    H = 1.3
    v = bw_speed(H, alpha, beta)
    h = bw_rise(H, alpha, beta)
    assert alpha_from_speed(v, H, beta) == pytest.approx(alpha, abs=1e-12)
    assert alpha_from_rise(h, H, beta) == pytest.approx(alpha, abs=1e-12)


def test_no_push_is_free_fall_of_the_drop_and_no_rise():
    # alpha = beta = 0: picked up from rest with T = lambda v^2, ends free: v^2 = g H
    assert bw_speed(2.0, 0.0) == pytest.approx(math.sqrt(9.81 * 2.0))
    assert bw_rise(2.0, 0.0) == 0.0


def test_energy_bound_is_alpha_one_half():
    # a loss-free pick-up (alpha = 1/2, beta = 0) gives the free-fall speed sqrt(2 g H)
    assert bw_speed(1.0, 0.5) == pytest.approx(math.sqrt(2 * 9.81))


def test_no_steady_fountain_at_alpha_plus_beta_one():
    with pytest.raises(ValueError, match="alpha \\+ beta < 1"):
        bw_speed(1.0, 0.6, 0.4)
    with pytest.raises(ValueError, match="speed > 0"):
        alpha_from_speed(0.0, 1.0)
