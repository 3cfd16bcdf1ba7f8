"""The paper's worked example (Fig. "schematic_chain_fountain": H = 2, xi = 0.14, kappa = 0.165)."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from chainfountain import theory as th
from chainfountain.theory import Fountain

H, h, l = 2.0, 0.28, 0.33


@pytest.fixture(scope="module")
def paper():
    return Fountain.from_geometry(l, h, H, k=0.377)


def test_qH_matches_paper(paper):
    # 44.20 is the two-decimal value; the exact root is 44.2012 (checked to 1e-10 below).
    assert paper.qH == pytest.approx(44.20, rel=1e-3)
    assert round(paper.qH, 2) == 44.20
    # The caption's 44.4 came from rounded inputs: within 0.5 %.
    assert paper.qH == pytest.approx(44.4, rel=5e-3)


def test_q_against_independent_root_finder(paper):
    f = lambda q: math.acosh(1 + q * (h + H)) + math.acosh(1 + q * h) - q * l  # noqa: E731
    q_ref = brentq(f, 1e-6, 1e4, xtol=1e-14, rtol=1e-15)
    assert paper.q == pytest.approx(q_ref, rel=1e-10)


def test_speeds_match_paper(paper):
    assert paper.k_max == pytest.approx(0.4301, abs=1e-4)
    assert paper.v_kmax == pytest.approx(4.78, abs=5e-3)  # the paper's "4.8"
    assert paper.v == pytest.approx(5.10, abs=5e-3)  # the paper's "5.1"
    assert paper.v_min == pytest.approx(math.sqrt(9.81 * 2.28))
    assert paper.v_max == pytest.approx(math.sqrt(2 * 9.81 * 2))


def test_end_tensions(paper):
    assert paper.T0_bar == pytest.approx(0.8774, abs=1e-4)
    assert paper.TE_bar == pytest.approx(0.1234, abs=1e-4)
    assert paper.T0_bar - paper.TE_bar == pytest.approx(paper.k * H, rel=1e-12)
    at_max = paper.with_k(paper.k_max)
    assert at_max.TE_bar == pytest.approx(0.0, abs=1e-12)
    assert at_max.T0_bar == pytest.approx(at_max.k * H, rel=1e-12)
    assert at_max.T0_bar == pytest.approx(0.8601, abs=1e-4)


def test_bounds_hold_and_fail(paper):
    assert paper.bounds().ok
    too_fast = paper.with_k(0.2)
    b = too_fast.bounds()
    assert not b.below_v_max and b.tensile_end and not b.ok
    too_slow = paper.with_k(0.5)
    assert not too_slow.bounds().tensile_end
    assert "k <= k_max" in too_slow.bounds().violations()[0]


def test_force_ranges(paper):
    r = paper.force_ranges()
    assert r.k_lo == pytest.approx(0.25)
    assert r.k_hi == pytest.approx(paper.k_max)
    assert r.TE[0] == 0 and r.TE[1] < 0.5
    assert 0.5 < r.T0[0] < r.T0[1] < 1
    assert r.T0[0] <= paper.T0_bar < r.T0[1]
    assert r.TE[0] <= paper.TE_bar < r.TE[1]


def test_pickup_and_putdown():
    assert th.pickup_force_bar(0.0) == pytest.approx(0.5)
    assert th.pickup_force_bar(math.pi / 2) == pytest.approx(1.0)
    assert th.pickup_force(0.1, 2.0, 0.0) == pytest.approx(0.2)
    assert th.pickup_roller_speed(3.0, math.pi / 2) == pytest.approx(3.0)
    assert th.pickup_roller_speed(3.0, 0.0) == pytest.approx(1.5)
    assert th.putdown_force(0.1, 2.0) == pytest.approx(0.2)


def test_apparatus_relations(paper):
    k = paper.k
    s = th.settings_for(paper.TE_bar, k, H, xi2=0.3, xi3=0.6)
    assert s.balanced and s.feasible
    assert s.TE_bar == pytest.approx(paper.TE_bar)
    assert s.T0_bar == pytest.approx(paper.T0_bar)
    assert s.T_uc == pytest.approx(s.T_lc + k * H * (1 - 0.3 - 0.6))
    # Unbalanced carts leave a net force.
    assert th.imbalance_bar(s.T_uc + 0.1, s.T_lc, 0.3, 0.6, k, H) == pytest.approx(0.1)


def test_special_case_half_half(paper):
    k = th.special_case_k(paper.q, h, H)
    f = paper.with_k(k)
    s = th.settings_for(f.TE_bar, k, H, xi2=0.5, xi3=0.5)
    assert s.T_lc == pytest.approx(0.0, abs=1e-12)
    assert s.T_uc == pytest.approx(0.0, abs=1e-12)
    assert f.T0_bar == pytest.approx(0.5 + k * H / 2)


def test_limit_case_kmax(paper):
    k = paper.k_max
    xi3 = th.limit_case_xi3(k, H)
    s = th.settings_for(0.0, k, H, xi2=0.1, xi3=xi3)
    assert s.T_lc == pytest.approx(0.0, abs=1e-12)
    assert s.TE_bar == pytest.approx(0.0, abs=1e-12)
    assert s.T0_bar == pytest.approx(k * H)


def test_cart_force_roundtrip():
    m = th.cart_mass(0.3, math.radians(30), 0.05, 4.0)
    assert th.cart_force_bar(m, math.radians(30), 0.05, 4.0) == pytest.approx(0.3)


def test_launch_example_from_notes():
    f = Fountain.from_launch(5.0, math.radians(75), 1.0)
    assert f.h == pytest.approx(1.148, abs=1e-3)
    assert -f.start[0] == pytest.approx(0.813, abs=1e-3)
    assert f.TE_bar == pytest.approx(0.0, abs=1e-12)
    assert math.degrees(f.alpha0) == pytest.approx(75.0)


def test_launch_rejects_impossible():
    with pytest.raises(ValueError, match="v >"):
        Fountain.from_launch(2.0, math.radians(75), 1.0)  # k*H >= 1
    with pytest.raises(ValueError, match="alpha0"):
        Fountain.from_launch(5.0, math.radians(95), 1.0)


def test_from_forces_recovers_paper(paper):
    sols = Fountain.from_forces(paper.T0_bar, paper.k, l, H)
    assert any(abs(s.h - h) < 1e-9 and abs(s.q - paper.q) < 1e-9 * paper.q for s in sols)


def test_solver_vectorised_and_exact_on_grid():
    xi = np.linspace(0, 0.99, 300)
    kappa = np.geomspace(1e-3, 50, 300)
    X, K = np.meshgrid(xi, kappa)
    Q = th.solve_qH(X, K)
    assert Q.shape == X.shape and np.all(Q > 0)
    resid = np.arccosh(1 + Q * (1 + X)) + np.arccosh(1 + Q * X) - Q * K
    assert np.max(np.abs(resid) / (Q * K)) < 1e-10


@pytest.mark.parametrize("bad", [(-1, 0.2, 1), (1, -0.1, 1), (1, 0.2, 0), (math.nan, 0.2, 1)])
def test_solve_q_rejects_bad_geometry(bad):
    with pytest.raises(ValueError):
        th.solve_q(*bad)


def test_plate_reaction_grows_at_lambda_g_v():
    """Non-stationary arrangement: at a constant speed the reaction grows linearly at
    ``lambda*g*v``; a speed ramp gives the integral (the trapezoid is exact for it)."""
    from chainfountain.theory.apparatus import plate_reaction

    t = np.linspace(0.0, 2.0, 201)
    R = plate_reaction(t, np.full_like(t, 3.0), 0.2, 0.05, 9.81)
    assert R[0] == 0.2 and R[-1] == pytest.approx(0.2 + 0.05 * 9.81 * 3.0 * 2.0, rel=1e-12)
    R = plate_reaction(t, 3.0 - 0.1 * t, 0.0, 0.05, 9.81)
    assert R[-1] == pytest.approx(0.05 * 9.81 * (6.0 - 0.2), rel=1e-12)
    with pytest.raises(ValueError, match="one length"):
        plate_reaction(t, t[:-1], 0.0, 0.05)
