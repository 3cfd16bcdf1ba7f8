"""Tension along the free fountain, speed bounds and force ranges.

Scaled tension ``Tbar = T/(lambda*v**2)``, ``k = g/v**2``; paper, section
"Inverted Catenary": ``Tbar = 1 - k/(q*cos(alpha)) = 1 - k/q + k*y`` with
``y`` measured from the vertex.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chainfountain.theory.constants import G0


def tension_bar(y: ArrayLike, q: float, k: float) -> NDArray[np.float64]:
    """Scaled tension at height ``y`` (vertex frame): ``Tbar = 1 - k/q + k*y``."""
    return 1.0 - k / q + k * np.asarray(y, dtype=float)


def T0_bar(q: float, k: float, h: float) -> float:
    """Scaled tension at the fountain start, Eq. (k_upper_bound) a: ``1 - k/q - k*h``."""
    return 1.0 - k / q - k * h


def TE_bar(q: float, k: float, h: float, H: float) -> float:
    """Scaled tension at the fountain end, Eq. (k_upper_bound) b: ``1 - k/q - k*(h+H)``."""
    return 1.0 - k / q - k * (h + H)


def k_max(q: float, h: float, H: float) -> float:
    """Largest ``k`` with tensile end force, Eq. (k_upper_bound): ``q/(1 + q*(h+H))``."""
    return q / (1.0 + q * (h + H))


def k_min_energy(H: float) -> float:
    """Rough lower bound ``k > 1/(2H)`` from energy conservation (``v < v_max``)."""
    return 1.0 / (2.0 * H)


def v_of_k(k: float, g: float = G0) -> float:
    """Chain speed for ``k = g/v**2``."""
    return math.sqrt(g / k)


def k_of_v(v: float, g: float = G0) -> float:
    """``k = g/v**2`` (paper, section "Equations of Motion")."""
    return g / v**2


def v_min(h: float, H: float, g: float = G0) -> float:
    """The paper's lower speed bound ``v_min = sqrt(g*(h+H))``.

    It follows from ``k <= k_max < 1/(h+H)``; the exact bound from a tensile
    end force is ``sqrt(g/k_max)``, slightly larger (see :func:`v_kmax`).
    """
    return math.sqrt(g * (h + H))


def v_kmax(q: float, h: float, H: float, g: float = G0) -> float:
    """Speed at ``k = k_max`` (zero end tension): the exact lower speed bound."""
    return math.sqrt(g / k_max(q, h, H))


def v_max(H: float, g: float = G0) -> float:
    """Rough upper speed bound from energy conservation, ``v_max = sqrt(2*g*H)``."""
    return math.sqrt(2.0 * g * H)


@dataclass(frozen=True)
class ForceRanges:
    """Admissible end tensions for a geometry, Eq. (range_forces).

    ``TE`` and ``T0`` are the intervals spanned as ``k`` runs over its
    admissible range ``(1/(2H), k_max]``; ``TE_paper`` and ``T0_paper`` are the
    paper's looser closed-form outer bounds. ``empty`` is True when the energy
    bound and the tensile bound leave no admissible ``k`` (``q*H*(1-xi) <= 1``).
    """

    k_lo: float
    k_hi: float
    TE: tuple[float, float]
    T0: tuple[float, float]
    TE_paper: tuple[float, float]
    T0_paper: tuple[float, float]
    empty: bool


def force_ranges(q: float, h: float, H: float) -> ForceRanges:
    """End-force ranges of Eq. (range_forces) for the geometry ``(q, h, H)``.

    ``0 <= TE < 1 - (1/(qH) + 1 + xi)/2 < 1/2`` and
    ``qH/(1 + qH(1+xi)) <= T0 < 1 - 1/(2qH) - xi/2`` (the paper states the
    looser ``T0 < 1 - 1/(2qH) < (1+xi)/2 < 1``).
    """
    xi = h / H
    qH = q * H
    k_lo, k_hi = k_min_energy(H), k_max(q, h, H)
    TE_hi = 1.0 - 0.5 * (1.0 / qH + 1.0 + xi)
    T0_lo = qH / (1.0 + qH * (1.0 + xi))
    T0_hi = 1.0 - 1.0 / (2.0 * qH) - 0.5 * xi
    return ForceRanges(
        k_lo=k_lo,
        k_hi=k_hi,
        TE=(0.0, TE_hi),
        T0=(T0_lo, T0_hi),
        TE_paper=(0.0, 0.5),
        T0_paper=(0.5, 1.0),
        empty=not k_lo < k_hi,
    )


@dataclass(frozen=True)
class BoundCheck:
    """Which of the paper's bounds a ``(geometry, v)`` pair satisfies."""

    tensile_start: bool
    """``Tbar_0 >= 0``."""
    tensile_end: bool
    """``Tbar_E >= 0``, equivalently ``k <= k_max`` (``v >= sqrt(g/k_max)``)."""
    above_v_min: bool
    """``v >= v_min = sqrt(g*(h+H))`` (implied by ``tensile_end``)."""
    below_v_max: bool
    """``v < v_max = sqrt(2*g*H)``, the rough energy bound (``k > 1/(2H)``)."""

    @property
    def ok(self) -> bool:
        return self.tensile_start and self.tensile_end and self.above_v_min and self.below_v_max

    def violations(self) -> list[str]:
        """Human-readable list of the bounds that fail."""
        out = []
        if not self.tensile_start:
            out.append("Tbar_0 >= 0 (tensile start force)")
        if not self.tensile_end:
            out.append("k <= k_max, i.e. Tbar_E >= 0 (tensile end force)")
        if not self.above_v_min:
            out.append("v >= v_min = sqrt(g*(h+H))")
        if not self.below_v_max:
            out.append("v < v_max = sqrt(2*g*H) (energy bound)")
        return out


def check_bounds(q: float, h: float, H: float, k: float, g: float = G0) -> BoundCheck:
    """Check the tensile and energy bounds of Eqs. (k_upper_bound) and (range_forces)."""
    v = v_of_k(k, g)
    tol = 1e-12
    return BoundCheck(
        tensile_start=T0_bar(q, k, h) >= -tol,
        tensile_end=TE_bar(q, k, h, H) >= -tol,
        above_v_min=v >= v_min(h, H, g) * (1 - tol),
        below_v_max=v < v_max(H, g),
    )
