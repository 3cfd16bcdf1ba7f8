"""The chain fountain out of a pot (the Mould effect): Biggins and Warner's relations.

J. S. Biggins and M. Warner, "Understanding the chain fountain", Proc. R. Soc. A 470
(2014) 20130689. A chain is picked up from a pile at rest and falls a height ``H`` to
the floor at steady speed ``v``. The pile pushes up on the chain being picked up with
``alpha*lambda*v**2`` (so the tension just above the pick-up is ``(1 - alpha)*lambda*v**2``),
the floor pulls on the landing chain with ``beta*lambda*v**2``. A moving string keeps
``T - lambda*v**2 - lambda*g*y`` constant along itself (this paper's ``Tbar = 1 - k/q +
k*y``), which gives

    v**2 = g*H/(1 - alpha - beta)               (B&W eq. 2.3)
    h/H  = alpha/(1 - alpha - beta)             (B&W eq. 2.4)

for the rise ``h`` of an idealised, zero-width fountain (two straight strands) above the
pick-up. An absorbing floor, which takes each link without pulling, has ``beta = 0``.
Read the other way, each of a measured speed, rise and pick-up tension gives ``alpha``
(:func:`alpha_from_speed`, :func:`alpha_from_rise`); so does this paper's catenary
through the measured ends at the measured speed: its ``Tbar_0 = 1 - alpha``.
"""

from __future__ import annotations

import math

from chainfountain.theory.constants import G0


def _fraction(alpha: float, beta: float) -> float:
    rest = 1.0 - alpha - beta
    if not rest > 0.0:
        raise ValueError(f"alpha + beta = {alpha + beta!r}: a steady fountain needs "
                         "alpha + beta < 1")
    return rest


def bw_speed(H: float, alpha: float, beta: float = 0.0, g: float = G0) -> float:
    """Chain speed (m/s) of a fountain falling ``H`` (pick-up to floor):
    ``v = sqrt(g*H/(1 - alpha - beta))`` (B&W eq. 2.3)."""
    return math.sqrt(g * H / _fraction(alpha, beta))


def bw_rise(H: float, alpha: float, beta: float = 0.0) -> float:
    """Rise (m) of the idealised fountain above the pick-up:
    ``h = H*alpha/(1 - alpha - beta)`` (B&W eq. 2.4)."""
    return H * alpha / _fraction(alpha, beta)


def alpha_from_speed(v: float, H: float, beta: float = 0.0, g: float = G0) -> float:
    """The pick-up factor a speed ``v`` over a drop ``H`` implies: ``1 - beta - g*H/v**2``
    (B&W eq. 2.3 solved for ``alpha``)."""
    if not v > 0.0:
        raise ValueError(f"v = {v!r}: a speed > 0 is needed")
    return 1.0 - beta - g * H / (v * v)


def alpha_from_rise(h: float, H: float, beta: float = 0.0) -> float:
    """The pick-up factor a rise ``h`` above the pick-up over a drop ``H`` implies:
    ``(1 - beta)*h/(H + h)`` (B&W eq. 2.4 solved for ``alpha``)."""
    if not H + h > 0.0:
        raise ValueError(f"H + h = {H + h!r}: must be > 0")
    return (1.0 - beta) * h / (H + h)
