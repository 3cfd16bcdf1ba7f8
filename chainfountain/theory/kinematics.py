"""The kinematic constraint that fixes the fountain's shape parameter ``q``.

Paper, section "Inverted Catenary", Eq. (kinemat_constraint)::

    q*l = acosh(1 + q*(h + H)) + acosh(1 + q*h)

``l`` is the horizontal distance between fountain start and end, ``h`` the
overshoot height of the vertex above the start, ``H`` the drop from the start
to the end. The shape of the fountain depends on these three lengths only.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

_REL_TOL = 1e-14
_MAX_ITER = 200


def acosh1p(x: ArrayLike) -> NDArray[np.float64]:
    """``acosh(1 + x)`` for ``x >= 0``, accurate also for tiny ``x``."""
    x = np.asarray(x, dtype=float)
    return np.log1p(x + np.sqrt(x * (2.0 + x)))


def kinematic_residual(Q: ArrayLike, xi: ArrayLike, kappa: ArrayLike) -> NDArray[np.float64]:
    """Scaled residual of Eq. (kinemat_constraint) with ``Q = q*H``, ``xi = h/H``, ``kappa = l/H``.

    ``F(Q) = acosh(1 + Q*(1 + xi)) + acosh(1 + Q*xi) - Q*kappa``; the root in
    ``Q > 0`` is the fountain's ``q*H``.
    """
    Q = np.asarray(Q, dtype=float)
    return acosh1p(Q * (1.0 + xi)) + acosh1p(Q * xi) - Q * kappa


def _validate(l, h, H):  # noqa: E741 - paper's symbol
    l, h, H = np.broadcast_arrays(
        np.asarray(l, dtype=float), np.asarray(h, dtype=float), np.asarray(H, dtype=float)
    )
    bad = ~(np.isfinite(l) & np.isfinite(h) & np.isfinite(H))
    if np.any(bad):
        raise ValueError("l, h and H must be finite numbers")
    if np.any(l <= 0):
        raise ValueError(f"l must be > 0 (got {np.min(l):g})")
    if np.any(H <= 0):
        raise ValueError(f"H must be > 0 (got {np.min(H):g})")
    if np.any(h < 0):
        raise ValueError(f"h must be >= 0 (got {np.min(h):g})")
    return l, h, H


def solve_qH(xi: ArrayLike, kappa: ArrayLike) -> NDArray[np.float64] | float:
    """Scaled shape parameter ``qbar = q*H`` from ``xi = h/H >= 0`` and ``kappa = l/H > 0``.

    Solves Eq. (kinemat_constraint) in scaled form. The residual ``F(Q)`` is
    concave with ``F(0) = 0`` and ``F > 0`` just above zero, so the positive root
    is unique. Because ``acosh(1 + x) <= sqrt(2x)``, the point
    ``Q0 = 2*(sqrt(1+xi) + sqrt(xi))**2 / kappa**2`` has ``F(Q0) <= 0`` and
    Newton's method started there converges monotonically from above (the
    tangent of a concave function lies above it). Vectorised over arrays; the
    relative accuracy is close to machine precision (far better than 1e-10).
    """
    xi_a = np.asarray(xi, dtype=float)
    kappa_a = np.asarray(kappa, dtype=float)
    scalar = xi_a.ndim == 0 and kappa_a.ndim == 0
    xi_b, kappa_b = np.broadcast_arrays(xi_a, kappa_a)
    shape = xi_b.shape
    xi_a = np.ravel(xi_b).astype(float)
    kappa_a = np.ravel(kappa_b).astype(float)
    a = 1.0 + xi_a
    b = xi_a
    Q = 2.0 * (np.sqrt(a) + np.sqrt(b)) ** 2 / kappa_a**2
    active = np.ones(Q.shape, dtype=bool)
    for _ in range(_MAX_ITER):
        Qa = Q[active]
        aa, ba, ka = a[active], b[active], kappa_a[active]
        F = acosh1p(Qa * aa) + acosh1p(Qa * ba) - Qa * ka
        # d/dQ acosh(1 + c*Q) = sqrt(c) / sqrt(Q*(2 + c*Q)), finite for c = 0.
        dF = (
            np.sqrt(aa) / np.sqrt(Qa * (2.0 + aa * Qa))
            + np.sqrt(ba) / np.sqrt(Qa * (2.0 + ba * Qa))
            - ka
        )
        step = F / dF
        newQ = Qa - step
        # Monotone from above: never let round-off push us below zero.
        newQ = np.where(newQ > 0, newQ, 0.5 * Qa)
        Q[active] = newQ
        still = np.abs(step) > _REL_TOL * np.abs(newQ)
        idx = np.flatnonzero(active)
        active[idx[~still]] = False
        if not active.any():
            break
    return float(Q[0]) if scalar else Q.reshape(shape)


def solve_q(l: ArrayLike, h: ArrayLike, H: ArrayLike) -> NDArray[np.float64] | float:  # noqa: E741
    """Shape parameter ``q`` (1/m) of the fountain with geometry ``(l, h, H)``.

    Implements the kinematic constraint, Eq. (kinemat_constraint):
    ``q*l = acosh(1 + q*(h+H)) + acosh(1 + q*h)``. A unique root exists for
    every ``l > 0, H > 0, h >= 0``. Accepts scalars or broadcastable arrays.

    Raises ``ValueError`` for non-finite, zero or negative lengths.
    """
    scalar = all(np.ndim(v) == 0 for v in (l, h, H))
    l_a, h_a, H_a = _validate(l, h, H)
    Q = solve_qH(h_a / H_a, l_a / H_a)
    q = np.asarray(Q) / H_a
    return float(q) if scalar else q
