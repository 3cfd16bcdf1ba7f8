"""The inverted catenary of the free fountain (all bending terms zero).

Paper, section "Inverted Catenary", Eq. (func_graph): ``q*y = 1 - cosh(q*x)``
with the vertex at the origin and ``y`` up. This project's sign convention:
the chain moves in ``+x`` (start on the left at ``y = -h``, end on the right at
``y = -(h+H)``); ``alpha`` is the angle of the tangent (and velocity) from
``+x``, so ``alpha > 0`` while rising and ``alpha`` decreases along the arc
length ``s``: ``alpha' = -q*cos(alpha)**2`` (the paper writes
``alpha' = q*cos(alpha)**2``; only the orientation differs). Along the curve
``cos(alpha) = 1/(1 - q*y)``. Arc length ``s`` is measured from the vertex,
negative before it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chainfountain.theory.kinematics import acosh1p


def y_of_x(x: ArrayLike, q: float) -> NDArray[np.float64]:
    """Height of the catenary, Eq. (func_graph): ``y = (1 - cosh(q*x))/q``."""
    x = np.asarray(x, dtype=float)
    return -2.0 * np.sinh(0.5 * q * x) ** 2 / q


def x_of_y(y: ArrayLike, q: float, side: int = 1) -> NDArray[np.float64]:
    """Horizontal position where the catenary reaches height ``y <= 0``.

    ``side = -1`` gives the rising branch (before the vertex), ``+1`` the falling one.
    """
    y = np.asarray(y, dtype=float)
    return side * acosh1p(-q * y) / q


def alpha_of_x(x: ArrayLike, q: float) -> NDArray[np.float64]:
    """Tangent angle (rad) at ``x``: ``tan(alpha) = dy/dx = -sinh(q*x)``."""
    return -np.arctan(np.sinh(q * np.asarray(x, dtype=float)))


def s_of_x(x: ArrayLike, q: float) -> NDArray[np.float64]:
    """Arc length from the vertex: ``s = sinh(q*x)/q`` (negative before the vertex)."""
    return np.sinh(q * np.asarray(x, dtype=float)) / q


def x_of_s(s: ArrayLike, q: float) -> NDArray[np.float64]:
    """Inverse of :func:`s_of_x`: ``x = asinh(q*s)/q``."""
    return np.arcsinh(q * np.asarray(s, dtype=float)) / q


def alpha_of_s(s: ArrayLike, q: float) -> NDArray[np.float64]:
    """Tangent angle against arc length: ``alpha = -atan(q*s)``.

    It solves ``alpha' = -q*cos(alpha)**2`` (section "Inverted Catenary").
    """
    return -np.arctan(q * np.asarray(s, dtype=float))


def curvature_of_x(x: ArrayLike, q: float) -> NDArray[np.float64]:
    """Signed curvature ``y''/(1+y'^2)^(3/2) = -q*cos(alpha)**2``; equals ``-q`` at the vertex."""
    return -q / np.cosh(q * np.asarray(x, dtype=float)) ** 2


def cos_alpha_of_y(y: ArrayLike, q: float) -> NDArray[np.float64]:
    """``cos(alpha) = 1/(1 - q*y)`` along the curve (paper, section "Inverted Catenary")."""
    return 1.0 / (1.0 - q * np.asarray(y, dtype=float))


def sample_curve(
    x_start: float, x_end: float, q: float, n: int = 200, by_arc_length: bool = True
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Sample ``n`` points of the catenary from ``x_start`` to ``x_end``.

    With ``by_arc_length`` the points are equally spaced along the chain
    (useful for laying chain links on the curve), otherwise equally in ``x``.
    """
    if n < 2:
        raise ValueError("n must be >= 2")
    if by_arc_length:
        s = np.linspace(s_of_x(x_start, q), s_of_x(x_end, q), n)
        x = x_of_s(s, q)
    else:
        x = np.linspace(x_start, x_end, n)
    return x, y_of_x(x, q)
