"""The joints' rotary springs and dampers (``chain.bending_stiffness`` c and
``chain.bending_damping`` d): the pymunk step their spring needs, and the same chain at
another link length.

**Stability and accuracy.** pymunk (Chipmunk's ``cpDampedRotarySpring``) applies the
spring's torque explicitly, once a step, and the damper as an exponential decay of the
relative turning rate: a step takes ``1 - exp(-x)`` of it, ``x = 2 d h/I``. Two linked links
of moment ``I = lambda L^3/12`` held by a spring ring at ``omega = sqrt(4 c/I)``, and like
any explicit step the spring diverges once ``omega h`` passes 2 (:data:`SPRING_STABILITY`;
``h`` the pymunk step). The damper never diverges (``wide_low`` ran 2 s with its joints
whole up to ``d h/I = 100``), but beyond ``x ~ 1`` it is no longer the damper ``d``: on
``wide_low`` with ``d = 1e-3`` (``x = 15``) the vertex lies +0.4 ... +2.8 % off the steady
theory by the solver's iterations (10 ... 160), and within -0.5 % once sub-steps bring
``x`` to 0.5 (``d = 3e-4``: -0.5 % at ``x = 0.45``). :data:`DAMPER_X` is the limit
checked before a run and kept by the sub-steps refinement and ``solver.accuracy`` choose.

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
DAMPER_X = 0.3
"""Largest damper step exponent ``x = 2 d h/I``: the damper then acts as
``d (1 - exp(-x))/x``, at least 0.86 d (``research/stiff_runs.py`` runs at it)."""
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


def damper_x(chain: ChainConfig, h: float) -> float:
    """The damper's step exponent ``2 d h/I`` at pymunk step ``h``."""
    return 2.0 * chain.bending_damping * h / link_moment(chain)


def damping_limit(chain: ChainConfig, h: float) -> float:
    """The damper (N*m*s/rad) at which ``2 d h/I`` reaches :data:`DAMPER_X`."""
    return DAMPER_X * link_moment(chain) / (2.0 * h)


def substeps_for_spring(chain: ChainConfig, solver: SolverConfig) -> int:
    """The fewest pymunk steps per ``solver.dt`` (at least ``solver.substeps``) that keep the
    springs at or below :data:`SUBSTEP_MARGIN` of their limit and the dampers at
    :data:`DAMPER_X` or below."""
    spring = omega_h(chain, solver.dt) / (SUBSTEP_MARGIN * SPRING_STABILITY)
    damper = damper_x(chain, solver.dt) / DAMPER_X
    return max(solver.substeps, math.ceil(spring - 1e-12), math.ceil(damper - 1e-12))


def same_chain(chain: ChainConfig, link_length: float) -> None:
    """Cut ``chain`` into links of ``link_length`` (m), keeping its bending rigidity
    ``c L`` and damping ``d L`` (in place)."""
    ratio = chain.link_length / link_length
    chain.bending_stiffness *= ratio
    chain.bending_damping *= ratio
    chain.link_length = link_length
