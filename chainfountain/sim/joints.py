"""The joints' rotary springs and dampers (``chain.bending_stiffness`` c and
``chain.bending_damping`` d): the pymunk step their spring needs, and the same chain at
another link length.

**Stability.** pymunk (Chipmunk's ``cpDampedRotarySpring``) applies the spring's torque
explicitly, once a step, and the damper as an exact exponential decay of the relative
turning rate (``1 - exp(-d h/I)``). Two linked links of moment ``I = lambda L^3/12`` held by
a spring ring at ``omega = sqrt(4 c/I)``, and like any explicit step the spring diverges
once ``omega h`` passes 2 (:data:`SPRING_STABILITY`; ``h`` the pymunk step). The damper has
no such limit: ``wide_low`` ran 2 s with its joints whole up to ``d h/I = 100``.

**The same chain at other links.** A chain of links ``L`` with joint springs ``c`` and
dampers ``d`` bends like a rod of rigidity ``c L`` (N*m^2) damped by ``d L``; the same chain
cut into links ``L'`` has springs ``c L/L'`` and dampers ``d L/L'`` (:func:`same_chain`),
which refinement and ``solver.accuracy`` keep to (its links' rotary inertia, the
``-L^2/12`` of :func:`chainfountain.theory.stiff.scaled_stiffness`, is what changes).
"""

from __future__ import annotations

import math

from chainfountain.sim.config import ChainConfig, SolverConfig

SPRING_STABILITY = 2.0
"""Largest ``omega*h`` the joints' rotary springs are stepped stably at. Measured (0.5 s
from each level's start, ``chain.bending_stiffness`` raised): ``wide_low``,
``apparatus_fold`` and ``beaker`` ran at ``omega*h`` 1.8 and 2.0 and diverged at 2.2-2.3."""
SUBSTEP_MARGIN = 0.8
"""Sub-steps chosen for a spring keep ``omega*h`` at or below this fraction of
:data:`SPRING_STABILITY`."""


def link_moment(chain: ChainConfig) -> float:
    """A link's moment of inertia about its centre, ``lambda L^3/12`` (kg*m^2)."""
    return chain.linear_density * chain.link_length**3 / 12.0


def omega_h(chain: ChainConfig, h: float) -> float:
    """``omega*h`` of the joint springs at pymunk step ``h`` (0 without springs)."""
    c = chain.bending_stiffness
    return 2.0 * math.sqrt(c / link_moment(chain)) * h if c > 0.0 else 0.0


def stiffness_limit(chain: ChainConfig, h: float) -> float:
    """The spring stiffness (N*m/rad) at which ``omega*h`` reaches the limit."""
    return link_moment(chain) * (SPRING_STABILITY / h) ** 2 / 4.0


def substeps_for_spring(chain: ChainConfig, solver: SolverConfig) -> int:
    """The fewest pymunk steps per ``solver.dt`` (at least ``solver.substeps``) that keep the
    springs at or below :data:`SUBSTEP_MARGIN` of the limit."""
    need = omega_h(chain, solver.dt) / (SUBSTEP_MARGIN * SPRING_STABILITY)
    return max(solver.substeps, math.ceil(need))


def same_chain(chain: ChainConfig, link_length: float) -> None:
    """Cut ``chain`` into links of ``link_length`` (m), keeping its bending rigidity
    ``c L`` and damping ``d L`` (in place)."""
    ratio = chain.link_length / link_length
    chain.bending_stiffness *= ratio
    chain.bending_damping *= ratio
    chain.link_length = link_length
