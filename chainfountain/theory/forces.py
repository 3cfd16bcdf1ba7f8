"""Pick-up (unfolding) and put-down (folding) forces.

Paper, section "Pick-Up and Pull-Down Forces", Fig. (schematic_pick_up): a
chain with zero bending stiffness is unfolded by a massless roller that rolls
on the resting chain; the leaving branch makes the angle ``alpha`` with the
resting chain.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


def pickup_roller_speed(v: ArrayLike, alpha: ArrayLike) -> NDArray[np.float64]:
    """Roller (and mass-increase) speed ``v_R = v/(1 + cos(alpha))``."""
    return np.asarray(v, dtype=float) / (1.0 + np.cos(alpha))


def pickup_force_bar(alpha: ArrayLike) -> NDArray[np.float64]:
    """Scaled pulling force ``F/(lambda*v**2) = 1/(1 + cos(alpha))``.

    ``alpha = 0`` gives 1/2; ``alpha = pi/2`` gives 1, a pure impulse.
    """
    return 1.0 / (1.0 + np.cos(np.asarray(alpha, dtype=float)))


def pickup_force(lam: float, v: ArrayLike, alpha: ArrayLike) -> NDArray[np.float64]:
    """Pulling force (N) of the unfolding roller: ``F = lambda*v**2/(1 + cos(alpha))``."""
    return lam * np.asarray(v, dtype=float) ** 2 * pickup_force_bar(alpha)


def putdown_force_bar() -> float:
    """Scaled pull-down force of the folding mechanism: ``1/2``."""
    return 0.5


def putdown_force(lam: float, v: ArrayLike) -> NDArray[np.float64]:
    """Pull-down force (N) of the folding roller: ``F = lambda*v**2/2``."""
    return 0.5 * lam * np.asarray(v, dtype=float) ** 2
