"""The stiff chain's steady fountain as a boundary value problem
(:mod:`chainfountain.theory.stiff`): its boundary conditions hold at both ends, it is
converged in the mesh, and it tends to the paper's catenary as the joints loosen."""

from __future__ import annotations

import math

import numpy as np
import pytest

from chainfountain.theory import stiff
from chainfountain.theory.fountain import Fountain

V, ALPHA0, H, TE = 4.0, math.pi / 3, 0.5, 0.1  # wide_low's fountain, with a floor pull


@pytest.fixture(scope="module")
def solved() -> stiff.StiffFountain:
    return stiff.stiff_fountain(V, ALPHA0, H, TE, 1e-3, n=2000)


def test_the_boundary_conditions_hold_at_both_ends(solved):
    s = solved
    assert (s.x[0], s.y[0]) == pytest.approx((0.0, 0.0), abs=1e-9)
    assert s.alpha[0] == pytest.approx(ALPHA0, abs=1e-9)
    assert s.y[-1] == pytest.approx(-H, abs=1e-9)
    assert s.T_bar[-1] == pytest.approx(TE, abs=1e-9)
    assert abs(s.kappa[-1]) < 1e-6  # no moment at the free end
    assert abs(s.dkappa[-1]) < 1e-6 * np.abs(s.dkappa).max()  # nor shear


def test_it_is_converged_in_the_mesh(solved):
    finer = stiff.stiff_fountain(V, ALPHA0, H, TE, 1e-3, n=4000)
    assert finer.h == pytest.approx(solved.h, rel=1e-6)
    assert finer.l == pytest.approx(solved.l, rel=1e-6)


def test_loose_joints_give_the_paper_s_catenary():
    cat = Fountain.from_launch(v=V, alpha0=ALPHA0, H=H, TE_bar=TE, g=9.81)
    s = stiff.stiff_fountain(V, ALPHA0, H, TE, 2e-5, n=4000)
    assert s.h == pytest.approx(cat.h, rel=2e-3)
    assert s.l == pytest.approx(cat.end[0] - cat.start[0], rel=1e-3)
    assert s.T0_bar == pytest.approx(cat.T0_bar, abs=1e-3)


def test_stiff_joints_move_the_fountain_off_the_catenary(solved):
    cat = Fountain.from_launch(v=V, alpha0=ALPHA0, H=H, TE_bar=TE, g=9.81)
    much = stiff.stiff_fountain(V, ALPHA0, H, TE, 3e-3, n=1000)
    assert abs(much.h / cat.h - 1.0) > 0.01  # a stiff chain is not a string (-1.45 %)


def test_no_stiffer_than_the_links_inertia_is_refused():
    e = stiff.scaled_stiffness(0.0, 0.02, 0.05, V)
    assert e == pytest.approx(-0.02**2 / 12)
    with pytest.raises(ValueError, match="rotary inertia"):
        stiff.stiff_fountain(V, ALPHA0, H, TE, e)


L, LAM = 0.02, 0.05  # wide_low's links


@pytest.fixture(scope="module")
def damped() -> stiff.StiffFountain:
    c, d = 0.04, 1e-3
    return stiff.stiff_fountain(V, ALPHA0, H, TE, stiff.scaled_stiffness(c, L, LAM, V),
                                delta=stiff.scaled_damping(d, L, LAM, V),
                                ec=c * L / (LAM * V * V), n=2000)


def test_a_damped_chain_leaves_the_guide_straight_and_lands_free(damped):
    s = damped
    assert (s.x[0], s.y[0], s.alpha[0]) == pytest.approx((0.0, 0.0, ALPHA0), abs=1e-9)
    assert abs(s.kappa[0]) < 1e-6 * np.abs(s.kappa).max()  # straight out of the guide
    assert s.y[-1] == pytest.approx(-H, abs=1e-9)
    assert s.T_bar[-1] == pytest.approx(TE, abs=1e-9)
    assert abs(s.moment_bar[-1]) < 1e-6 * np.abs(s.moment_bar).max()
    assert abs(s.shear_bar[-1]) < 1e-6 * np.abs(s.shear_bar).max()


def test_the_damped_solution_is_converged_in_the_mesh(damped):
    finer = stiff.stiff_fountain(V, ALPHA0, H, TE, damped.e, delta=damped.delta,
                                 ec=damped.ec, n=4000, tol=1e-7)
    assert finer.h == pytest.approx(damped.h, rel=1e-5)
    assert finer.l == pytest.approx(damped.l, rel=1e-5)


def test_the_damped_balances_hold_along_the_curve(damped):
    """The solution satisfies the momentum balances it was solved for, checked by finite
    differences of its own arrays (not the solver's right-hand side)."""
    s, k = damped, 9.81 / V**2
    ds = np.gradient(s.s)
    dT = np.gradient(s.T_bar) / ds
    dN = np.gradient(s.shear_bar) / ds
    inner = slice(50, -50)
    assert np.allclose(dT[inner], (s.shear_bar * s.kappa + k * np.sin(s.alpha))[inner],
                       atol=2e-3 * np.abs(dT).max())
    assert np.allclose(dN[inner], (k * np.cos(s.alpha) - (s.T_bar - 1) * s.kappa)[inner],
                       atol=2e-3 * np.abs(dN).max())


def test_a_vanishing_damper_tends_to_the_undamped_solution():
    e = stiff.scaled_stiffness(0.04, L, LAM, V)
    bare = stiff.stiff_fountain(V, ALPHA0, H, TE, e)
    faint = stiff.stiff_fountain(V, ALPHA0, H, TE, e, delta=1e-7)  # +0.07 % and -0.02 %
    assert faint.h == pytest.approx(bare.h, rel=2e-3)
    assert faint.l == pytest.approx(bare.l, rel=2e-3)
    more = stiff.stiff_fountain(V, ALPHA0, H, TE, e, delta=1e-5)  # +2.0 %
    assert abs(more.h / bare.h - 1.0) > 5 * abs(faint.h / bare.h - 1.0)


def test_a_damper_raises_the_fountain():
    """A damped joint cannot bend as it leaves the guide: the fountain climbs straighter
    (wide_low's launch, d = 1e-3 and 1e-2 N*m*s/rad without a spring: +3.8 % and +7.2 %)."""
    cat = Fountain.from_launch(v=V, alpha0=ALPHA0, H=H, TE_bar=TE, g=9.81)
    hs = [stiff.stiff_fountain_of(0.0, d, L, LAM, V, ALPHA0, H, TE).h for d in (1e-3, 1e-2)]
    assert cat.h < hs[0] < hs[1]


def test_joints_that_do_not_matter_leave_the_catenary():
    assert stiff.stiff_fountain_of(0.0, 0.0, L, LAM, V, ALPHA0, H, TE) is None
    wave = 1e-3 * LAM * V * L**2  # solver.wave_damping's damper: a 2-mm layer
    assert stiff.stiff_fountain_of(0.0, wave, L, LAM, V, ALPHA0, H, TE) is None
    assert stiff.stiff_fountain_of(0.04, 0.0, L, LAM, V, ALPHA0, H, TE) is not None


def test_branches_are_followed_both_ways_and_lost_where_none_is_found():
    """On wide_low's launch the steady fountains of 6-11.5e-3 m^2 form one branch, found
    alike upwards, downwards and afresh; at 2e-2 m^2 none is found."""
    es = [6e-3, 8e-3, 1e-2, 2e-2]
    (b,) = stiff.branches(V, ALPHA0, 0.5, 0.0, es)
    assert np.all(np.isfinite(b.h[:3])) and np.isnan(b.h[3])
    assert np.all(np.diff(b.h[:3]) > 0)  # climbs with the stiffness here
