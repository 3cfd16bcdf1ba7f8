"""Closed forms of falling chains, the scenes the chain model is tested against.

- The folded chain falling with one end fixed (Calkin and March, Am. J. Phys. 57, 154,
  1989): an inextensible chain of length ``Lc`` hangs folded from a fixed end, its other
  end held beside it and let go. Energy is conserved, so after falling ``x`` the free end
  moves at ``v**2 = g*x*(2*Lc - x)/(Lc - x)`` (faster than free fall), and the fixed end
  holds the hanging arm's weight and a quarter of the momentum flux,
  ``F = lambda*(g*(Lc + x)/2 + v**2/4)``.
- A chain dropped onto a scale (Hamm and Geminard, Am. J. Phys. 78, 828, 2010): a chain
  hanging straight down, released from rest just above a scale, falls freely; the scale
  reads the weight landed plus the momentum flux, ``3*lambda*g*y`` with ``y = g*t**2/2``
  the length landed.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike


def folded_fall_speed(x: ArrayLike, length: float, g: float) -> np.ndarray:
    """Speed (m/s) of the free end after falling ``x`` (m), energy conserved."""
    x = np.asarray(x, dtype=float)
    return np.sqrt(g * x * (2.0 * length - x) / (length - x))


def folded_fall_pin_force(x: ArrayLike, length: float, linear_density: float,
                          g: float) -> np.ndarray:
    """Force (N) on the fixed end when the free end has fallen ``x`` (m)."""
    x = np.asarray(x, dtype=float)
    v2 = g * x * (2.0 * length - x) / (length - x)
    return linear_density * (g * (length + x) / 2.0 + v2 / 4.0)


def scale_landed(t: ArrayLike, gap: float, g: float) -> np.ndarray:
    """Length (m) landed on the scale at time ``t`` (s) after the release, the chain's
    lowest point ``gap`` (m) above the scale: ``g*t**2/2 - gap``, never below 0."""
    t = np.asarray(t, dtype=float)
    return np.maximum(g * t**2 / 2.0 - gap, 0.0)


def scale_force(landed: ArrayLike, linear_density: float, g: float) -> np.ndarray:
    """What the scale reads (N) with ``landed`` (m) of chain on it: ``3*lambda*g*y``."""
    return 3.0 * linear_density * g * np.asarray(landed, dtype=float)
