"""The pulley apparatus's stored-length mode: a linear model of the landing swing.

Not in the paper. The paper's apparatus (section "Generating Steady-State Chain
Fountains") is a chain moving through a fixed path: an upstream strand (speed ``v1``,
from the unfolding roller to the fountain start), the free fountain, which stores a
length ``S`` of chain, and a downstream strand (speed ``v2``, from the fountain end to
the folding roller). Linearised about the steady state (speed ``v``):

    m1 dv1/dt = (dT0/dv1 - dT_exit/dv1) dv1 + dT0/dv2 dv2 - K dS
    m2 dv2/dt = -dT_E/dv1 dv1 + (dT_in/dv2 - dT_E/dv2) dv2 + K dS
    dS/dt     = dv1 - dv2

* ``T0`` and ``T_E`` (the fountain's start and end tensions) carry the momentum flux
  ``lambda v_f^2`` of the flying chain; the closure here takes the fountain's speed as
  the mean of the strands', ``v_f = (v1 + v2)/2``, so each derivative is ``lambda v``.
* The rest of ``T0`` is set by the fountain's shape: a catenary leaving at the fixed
  angle ``theta`` with parameter ``a`` has ``T0 = lambda v^2 - lambda g a / cos(theta)``
  and ``T0 - T_E = lambda g H``. More stored chain, a larger ``a``: a spring of
  stiffness ``K = lambda g / (cos(theta) dS/da)`` (:func:`fountain_spring`).
* The pick-up's exit tension ``T_exit = p lambda v^2 + (terms fixed by the cart)`` and
  the put-down's entry tension ``T_in = d lambda v^2 + ...``; the paper has
  ``p = 1/(1 + cos alpha) = 1/2`` at ``alpha = 0`` (Eq. for the pulling force) and
  ``d = 1/2``.
* ``m1`` and ``m2`` are the moving masses on either side, the rollers, carriages and
  carts referred to the chain speed.

With the paper's ``p = d = 1/2`` the velocity terms are purely gyroscopic and the
energy ``(m1 dv1^2 + m2 dv2^2 + K dS^2)/2`` is conserved: the mode neither grows nor
decays, and one eigenvalue is zero (a speed with its matching stored length is another
steady state). Any other rig law feeds or drains the mode at the rate
``lambda v ((1 - 2p) <dv1^2> - (1 - 2d) <dv2^2>)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from chainfountain.theory.catenary import s_of_x, x_of_y, y_of_x
from chainfountain.theory.constants import G0


def stored_length(a: float, theta: float, H: float) -> float:
    """Chain stored in a catenary fountain of parameter ``a = 1/q`` (m) leaving at
    ``theta`` (rad above the horizontal) and ending ``H`` below its start: the arc of
    Eq. (func_graph) (:mod:`chainfountain.theory.catenary`) from the point of slope
    ``tan(theta)`` over the vertex to the falling branch ``H`` lower."""
    if a <= 0.0 or not 0.0 < theta < 0.5 * math.pi or H < 0.0:
        raise ValueError(f"need a > 0, 0 < theta < pi/2, H >= 0 (got {a}, {theta}, {H})")
    q = 1.0 / a
    x0 = -math.asinh(math.tan(theta)) / q
    x1 = float(x_of_y(float(y_of_x(x0, q)) - H, q, side=1))
    return float(s_of_x(x1, q) - s_of_x(x0, q))


def fountain_spring(a: float, theta: float, H: float, lam: float, g: float = G0) -> float:
    """Stiffness ``K = lambda g / (cos(theta) dS/da)`` (N/m) of the fountain's stored
    length against the pull on both strands (quasi-static: the shape follows the stored
    chain at once)."""
    h = 1e-6 * a
    dS = (stored_length(a + h, theta, H) - stored_length(a - h, theta, H)) / (2.0 * h)
    return lam * g / (math.cos(theta) * dS)


def mode_matrix(m1: float, m2: float, K: float, lam: float, v: float,
                p: float = 0.5, d: float = 0.5) -> np.ndarray:
    """The 3x3 matrix of ``d/dt (dv1, dv2, dS)`` (see the module docstring)."""
    if m1 <= 0.0 or m2 <= 0.0 or K <= 0.0:
        raise ValueError(f"need m1, m2, K > 0 (got {m1}, {m2}, {K})")
    c = lam * v
    return np.array([
        [c * (1.0 - 2.0 * p) / m1, c / m1, -K / m1],
        [-c / m2, -c * (1.0 - 2.0 * d) / m2, K / m2],
        [1.0, -1.0, 0.0],
    ])


@dataclass(frozen=True)
class SwingMode:
    """The oscillating eigenmode of :func:`mode_matrix` and the speed-selection rate."""

    growth: float
    """Growth rate ``sigma`` of the oscillation's amplitude (1/s; > 0 grows)."""
    period: float
    """Period (s); ``inf`` if no eigenvalue oscillates."""
    selection: float
    """The real eigenvalue (1/s): < 0, a disturbed speed returns; 0, neutral."""
    ratio: float
    """``|dv1| / |dv2|`` in the oscillation (how much further the upstream strand swings)."""
    phase: float
    """Phase of ``dv1`` relative to ``dv2`` in the oscillation (degrees)."""


def swing_mode(m1: float, m2: float, K: float, lam: float, v: float,
               p: float = 0.5, d: float = 0.5, delay: float = 0.0) -> SwingMode:
    """Eigen-analysis of :func:`mode_matrix`. ``delay`` (s): a spring that answers that
    much late adds ``omega^2 * delay / 2`` to the growth (first order in the delay)."""
    ev, vec = np.linalg.eig(mode_matrix(m1, m2, K, lam, v, p, d))
    osc = [i for i in range(3) if abs(ev[i].imag) > 1e-12]
    real = [i for i in range(3) if abs(ev[i].imag) <= 1e-12]
    if not osc:
        return SwingMode(float(max(ev.real)), math.inf,
                         float(min(ev.real)), math.nan, math.nan)
    i = max(osc, key=lambda j: ev[j].imag)
    w = float(ev[i].imag)
    x = vec[:, i]
    return SwingMode(
        growth=float(ev[i].real) + 0.5 * w * w * delay,
        period=2.0 * math.pi / w,
        selection=float(ev[real[0]].real) if real else math.nan,
        ratio=float(abs(x[0]) / abs(x[1])),
        phase=float(np.degrees(np.angle(x[0] / x[1]))),
    )
