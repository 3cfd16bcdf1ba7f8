"""The energy balance of a cart step (:mod:`chainfountain.theory.apparatus`, not in the paper)."""

from __future__ import annotations

import numpy as np
import pytest

from chainfountain.theory.apparatus import cart_step_speed, referred_mass


def test_referred_mass_adds_a_quarter_of_the_unit_and_the_roller_spin() -> None:
    # carriage and roller at v/2: (m_c + m_r)/4; roller spin (uniform disc at v/(2r)): m_r/8
    assert referred_mass(0.4, 0.08, 0.02) == pytest.approx(0.4 + 0.025 + 0.0025)


def test_step_speed_solves_its_equation() -> None:
    t = np.linspace(0.0, 3.0, 3001)
    dF, M, gain, drag = 0.25, 0.44, 0.5, 0.069
    dv = cart_step_speed(t, dF, M, gain=gain, drag=drag)
    lhs = M * np.gradient(dv, t)
    rhs = -gain * dF - drag * dv
    assert np.max(np.abs(lhs - rhs)[1:-1]) < 1e-5
    assert dv[0] == 0.0


def test_step_speed_limits() -> None:
    dF, M = 0.25, 0.44
    # no drag: constant deceleration gain*dF/M
    assert cart_step_speed(0.3, dF, M) == pytest.approx(-0.5 * dF * 0.3 / M)
    # early times with drag: the same; late times: the new steady speed -gain*dF/drag
    assert cart_step_speed(1e-4, dF, M, drag=0.07) == pytest.approx(-0.5 * dF * 1e-4 / M,
                                                                     rel=1e-4)
    assert cart_step_speed(500.0, dF, M, gain=0.68, drag=0.07) == pytest.approx(
        -0.68 * dF / 0.07)


@pytest.mark.parametrize("kwargs, field", [
    ({"mass": 0.0}, "mass"), ({"mass": float("nan")}, "mass"), ({"drag": -1.0}, "drag"),
])
def test_step_speed_bad_input_names_the_field(kwargs: dict, field: str) -> None:
    args = {"t": 1.0, "dF": 0.1, "mass": 0.4} | kwargs
    with pytest.raises(ValueError, match=field):
        cart_step_speed(**args)


def test_referred_mass_bad_input_names_the_field() -> None:
    with pytest.raises(ValueError, match="carriage_mass"):
        referred_mass(0.4, -0.01, 0.02)
