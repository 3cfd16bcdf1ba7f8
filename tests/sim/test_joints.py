"""The joints' springs and dampers (:mod:`chainfountain.sim.joints`): the same chain at
other links, and the sub-steps its spring needs, as refinement and ``solver.accuracy``
use them."""

from __future__ import annotations

import pytest

from chainfountain.refine import refined_config
from chainfountain.sim import joints
from chainfountain.sim.config import ChainConfig, SolverConfig
from chainfountain.study.changes import with_changes


def test_the_same_chain_keeps_its_rigidity_and_damping():
    chain = ChainConfig(link_length=0.02, bending_stiffness=0.05, bending_damping=1e-3)
    joints.same_chain(chain, 0.005)
    assert chain.link_length == 0.005
    assert chain.bending_stiffness * chain.link_length == pytest.approx(0.05 * 0.02)
    assert chain.bending_damping * chain.link_length == pytest.approx(1e-3 * 0.02)


@pytest.mark.parametrize("c", [0.0, 0.01, 0.3, 3.0])
def test_substeps_keep_the_spring_inside_its_limit(c):
    chain = ChainConfig(link_length=0.01, bending_stiffness=c)
    solver = SolverConfig(dt=2.5e-4, substeps=1)
    n = joints.substeps_for_spring(chain, solver)
    assert joints.omega_h(chain, solver.dt / n) <= joints.SUBSTEP_MARGIN * joints.SPRING_STABILITY
    if n > 1:  # and no more than that
        assert joints.omega_h(chain, solver.dt / (n - 1)) > (joints.SUBSTEP_MARGIN
                                                             * joints.SPRING_STABILITY)


def test_a_refined_stiff_level_is_the_same_chain_and_passes_its_check(level):
    lvl = with_changes(level("wide_low"), {"solver.accuracy": 0.0,
                                           "chain.bending_stiffness": 0.3,
                                           "chain.bending_damping": 1e-3}, where="stiff")
    cfg = lvl.sim
    fine = refined_config(cfg, 2)
    assert fine.chain.bending_stiffness * fine.chain.link_length == pytest.approx(
        cfg.chain.bending_stiffness * cfg.chain.link_length)
    assert fine.chain.bending_damping == pytest.approx(2 * cfg.chain.bending_damping)
    h = fine.solver.dt / fine.solver.substeps
    assert joints.omega_h(fine.chain, h) < joints.SPRING_STABILITY
    assert fine.solver.substeps > 1  # four times the ring rate at half the step


def test_the_accuracy_s_links_are_the_same_chain(level):
    """A level's changes are resolved as a file is (``with_changes``): wide_low's 2-cm links
    with springs of 0.05 N*m/rad, asked for 0.4 %, run on 12-mm links."""
    lvl = with_changes(level("wide_low"), {"chain.bending_stiffness": 0.05,
                                           "solver.accuracy": 0.004}, where="stiff")
    ch = lvl.sim.chain
    assert ch.link_length == pytest.approx(0.012)  # the accuracy chose other links
    assert ch.bending_stiffness * ch.link_length == pytest.approx(0.05 * 0.02)
    assert joints.omega_h(ch, lvl.sim.solver.dt / lvl.sim.solver.substeps) < 2.0
