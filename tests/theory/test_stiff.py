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
