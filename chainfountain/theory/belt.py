"""Belt approximation with joint resistance (paper, section "Equations of Motion").

The steady-state equations of a chain moving with constant speed ``v`` along its
own curve (paper, Eq. (2), scaled by ``lambda*v**2``, ``k = g/v**2``)::

    alpha'*(Tbar - 1) + Qbar' = k*cos(alpha)          (normal balance)
    Tbar' - alpha'*Qbar      = k*sin(alpha)          (tangential balance)

closed by the paper's ansatz for the normal (shear) force of the joints::

    Qbar = -(e0 + e1*Tbar)*alpha' - (e2 + e3*Tbar)*alpha''

Sign convention (same as the rest of the project): the chain moves in ``+x``,
``alpha`` is the angle of the tangent/velocity from ``+x`` (``x' = cos(alpha)``,
``y' = sin(alpha)``, ``y`` up, ``s`` the arc length along the motion), gravity is
``[0, -g]``. With this convention the paper's two scalar equations and the
ansatz are used *verbatim*: with all ``e_i = 0`` they give
``alpha' = k*cos(alpha)/(Tbar - 1) = -q*cos(alpha)**2`` (``Tbar < 1``), i.e.
``alpha`` decreases along ``s``; the paper's ``alpha' = q*cos(alpha)**2`` is the
magnitude of the curvature. The scalar equations follow from the momentum
balance if ``Qbar`` acts along the *left* normal ``[-sin(alpha), cos(alpha)]``
(the paper's vector ``[sin, -cos]`` has the opposite sign to its own scalar
equations). Then ``e2 > 0`` is a positive bending stiffness (moment
``M = e2*alpha'``, ``Qbar = -M'``) and the forward integration is stable: the
linearised bending modes solve ``e2*m**2 + e1*Tbar*m + (1 - Tbar) = 0`` and are
weakly damped oscillations. With the opposite sign of the ``e_i`` they would grow
like ``exp(s*sqrt((1 - Tbar)/e2))`` and no fountain could be integrated.

Which quantities are held fixed (``belt_fountain``): the fountain is integrated
as an initial value problem from the *start* (beaker) point of the catenary
with the catenary's start angle ``alpha_0``, start tension
``Tbar_0 = 1 - k/q - k*h`` and curvature data ``alpha'(0) = -q*cos(alpha_0)**2``,
``alpha''(0) = -2*q**2*cos(alpha_0)**3*sin(alpha_0)``, until it comes down to the
floor ``y = -(h + H)``. This is the launch the beaker actually imposes (position,
direction, pull); the overshoot height and the landing distance are outputs, which
is how the paper's fountains A-C differ in height and width. With all ``e_i = 0``
the result is the catenary through start, vertex and end.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

__all__ = [
    "BeltFountain",
    "Eps",
    "belt_fountain",
    "catenary_start",
    "PAPER_FOUNTAINS",
]


@dataclass(frozen=True)
class Eps:
    """Joint-resistance coefficients of the ansatz ``Qbar = -(e0 + e1*T)a' - (e2 + e3*T)a''``.

    All must be ``>= 0`` (paper: ``e_i in R+, << 1``). ``e0``, ``e2`` have units
    of length and length**2 (scaled by ``lambda*v**2``), like ``e1``, ``e3``.
    """

    e0: float = 0.0
    e1: float = 0.0
    e2: float = 0.0
    e3: float = 0.0

    def __post_init__(self) -> None:
        if min(self.e0, self.e1, self.e2, self.e3) < 0:
            raise ValueError(f"joint resistance coefficients must be >= 0, got {self}")

    @property
    def order(self) -> int:
        """Highest derivative of ``alpha`` in the system: 1 (catenary), 2 or 3."""
        if self.e2 > 0 or self.e3 > 0:
            return 3
        if self.e0 > 0 or self.e1 > 0:
            return 2
        return 1


# Paper, caption of Fig. "schematic_chain_fountain". The caption header says
# "eps1 = eps3 = 0" but fountains A-C then list eps1 != 0 and eps2: the ansatz has
# four coefficients e0..e3, two are held at zero and two are varied, so the header
# is read as e0 = e3 = 0 (an index slip). See docs/paper_walkthrough.md.
PAPER_FOUNTAINS: dict[str, tuple[Eps, float]] = {
    "A": (Eps(e1=1e-5, e2=2e-4), 0.377),
    "B": (Eps(e1=2e-5, e2=4e-4), 0.377),
    "C": (Eps(e1=2e-5, e2=8e-4), 0.377),
    "D": (Eps(), 0.377),
    "D'": (Eps(), 0.430),
}


@dataclass(frozen=True)
class CatenaryStart:
    """Start (beaker) state of the catenary ``q*y = 1 - cosh(q*x)``, vertex at the origin."""

    x: float
    y: float
    alpha: float
    dalpha: float
    ddalpha: float
    T: float


def catenary_start(q: float, h: float, k: float) -> CatenaryStart:
    """Start point, angle, curvature and tension of the catenary at height ``-h``.

    Paper: ``cos(alpha) = 1/(1 - q*y)`` (Eq. 3), ``Tbar_0 = 1 - k/q - k*h``
    (Eq. k_upper_bound), ``alpha' = -q*cos(alpha)**2`` (project sign).
    """
    c = 1.0 / (1.0 + q * h)
    a0 = float(np.arccos(c))
    x0 = -float(np.arccosh(1.0 + q * h)) / q
    return CatenaryStart(
        x=x0,
        y=-h,
        alpha=a0,
        dalpha=-q * c**2,
        ddalpha=-2.0 * q**2 * c**3 * np.sin(a0),
        T=1.0 - k / q - k * h,
    )


@dataclass
class BeltFountain:
    """Steady belt fountain sampled along the arc length ``s`` (from the start point).

    ``x, y`` in the catenary's vertex frame (start of the catenary at ``(x[0], y[0])``),
    ``T`` the scaled tension ``Tbar``, ``Q`` the scaled normal force ``Qbar``,
    ``alpha`` the tangent angle (project convention, see module docstring).
    """

    s: NDArray[np.float64]
    x: NDArray[np.float64]
    y: NDArray[np.float64]
    alpha: NDArray[np.float64]
    T: NDArray[np.float64]
    Q: NDArray[np.float64]
    eps: Eps
    k: float
    q: float
    h: float
    H: float
    landed: bool
    """True if the chain reached the floor ``y = -(h + H)`` (last sample is on it)."""
    info: dict[str, float] = field(default_factory=dict)

    @property
    def overshoot(self) -> float:
        """Overshoot height: first apex (``alpha = 0``) above the start (``h`` for the catenary)."""
        return float(self.info["y_apex"] - self.y[0])

    @property
    def distance(self) -> float:
        """Horizontal distance start to landing (``l`` for the catenary); NaN if not landed."""
        return float(self.x[-1] - self.x[0]) if self.landed else float("nan")

    @property
    def apex(self) -> tuple[float, float]:
        """``(x, y)`` of the first apex, where the tangent is horizontal (vertex frame)."""
        return self.info["x_apex"], self.info["y_apex"]

    @property
    def length(self) -> float:
        """Arc length of the free fountain from start to floor (or to the integration end)."""
        return float(self.s[-1])


def _rhs_factory(eps: Eps, k: float):
    """Right-hand side of the steady belt equations (paper Eq. 2 with the ``Qbar`` ansatz).

    State layouts (``a = alpha``):
      order 1: ``[x, y, a, T]``                 ``a' = k cos a/(T - 1)``, ``T' = k sin a``
      order 2: ``[x, y, a, a', T]``             ``Q = -(e0 + e1 T) a'``
      order 3: ``[x, y, a, a', a'', T]``        ``Q = -(e0 + e1 T) a' - (e2 + e3 T) a''``
    """
    e0, e1, e2, e3 = eps.e0, eps.e1, eps.e2, eps.e3
    order = eps.order

    if order == 1:

        def rhs1(_s: float, u: NDArray[np.float64]) -> list[float]:
            _, _, a, T = u
            ca, sa = np.cos(a), np.sin(a)
            return [ca, sa, k * ca / (T - 1.0), k * sa]

        return rhs1

    if order == 2:

        def rhs2(_s: float, u: NDArray[np.float64]) -> list[float]:
            _, _, a, da, T = u
            ca, sa = np.cos(a), np.sin(a)
            Q = -(e0 + e1 * T) * da
            dT = k * sa + da * Q
            # Q' = -e1 T' a' - (e0 + e1 T) a''  and  Q' = k cos a - a'(T - 1)
            dda = (da * (T - 1.0) - k * ca - e1 * dT * da) / (e0 + e1 * T)
            return [ca, sa, da, dda, dT]

        return rhs2

    def rhs3(_s: float, u: NDArray[np.float64]) -> list[float]:
        _, _, a, da, dda, T = u
        ca, sa = np.cos(a), np.sin(a)
        Q = -(e0 + e1 * T) * da - (e2 + e3 * T) * dda
        dT = k * sa + da * Q
        # Q' = -e1 T' a' - (e0 + e1 T) a'' - e3 T' a'' - (e2 + e3 T) a'''
        ddda = (da * (T - 1.0) - k * ca - e1 * dT * da - (e0 + e1 * T) * dda - e3 * dT * dda) / (
            e2 + e3 * T
        )
        return [ca, sa, da, dda, ddda, dT]

    return rhs3


def _events(y_floor: float):
    """The integration's events: landing on the floor (terminal) and passing the apex."""

    def floor(_s: float, u: NDArray[np.float64]) -> float:
        return u[1] - y_floor

    floor.terminal = True  # type: ignore[attr-defined]
    floor.direction = -1  # type: ignore[attr-defined]

    def apex(_s: float, u: NDArray[np.float64]) -> float:
        return u[2]  # y' = sin(alpha) changes sign where alpha crosses 0 downwards

    apex.direction = -1  # type: ignore[attr-defined]
    return floor, apex


def _result(sol, n: int, y_floor: float, order: int, eps: Eps, *, k: float, q: float,
            h: float, H: float, s_cat: float) -> BeltFountain:
    """``n`` samples of the integrated belt, equally spaced in ``s``, with its apex."""
    landed = sol.status == 1 and len(sol.t_events[0]) > 0
    s_end = float(sol.t_events[0][0]) if landed else float(sol.t[-1])
    s = np.linspace(0.0, s_end, n)
    U = sol.sol(s)
    if landed:
        U[1, -1] = y_floor
    if len(sol.t_events[1]):
        s_apex = float(sol.t_events[1][0])
        x_apex, y_apex = (float(c) for c in sol.sol(s_apex)[:2])
    else:  # never turned over (possible only without a vertex, e.g. h = 0)
        i = int(np.argmax(U[1]))
        s_apex, x_apex, y_apex = float(s[i]), float(U[0, i]), float(U[1, i])
    x, y, a = U[0], U[1], U[2]
    T = U[-1]
    if order == 1:
        Q = np.zeros_like(s)
    elif order == 2:
        Q = -(eps.e0 + eps.e1 * T) * U[3]
    else:
        Q = -(eps.e0 + eps.e1 * T) * U[3] - (eps.e2 + eps.e3 * T) * U[4]
    return BeltFountain(
        s=s,
        x=x,
        y=y,
        alpha=a,
        T=T,
        Q=Q,
        eps=eps,
        k=k,
        q=q,
        h=h,
        H=H,
        landed=landed,
        info={
            "nfev": float(sol.nfev),
            "s_catenary": float(s_cat),
            "s_apex": s_apex,
            "x_apex": x_apex,
            "y_apex": y_apex,
        },
    )


def belt_fountain(
    q: float,
    h: float,
    H: float,
    k: float,
    eps: Eps | None = None,
    *,
    n: int = 801,
    s_max: float | None = None,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    method: str | None = None,
    dalpha0: float | None = None,
    ddalpha0: float | None = None,
) -> BeltFountain:
    """Integrate the steady belt equations from the catenary's start state to the floor.

    Paper Eq. (2) with ``Qbar = -(e0 + e1 T) alpha' - (e2 + e3 T) alpha''``. The
    catenary ``(q, h, H, k)`` supplies the start point ``(-acosh(1+qh)/q, -h)``,
    the start angle, curvature (``alpha'``, ``alpha''``) and tension
    ``Tbar_0 = 1 - k/q - k h``; the integration stops when ``y`` comes down to
    ``-(h + H)`` (after the apex) or at ``s_max`` (default: 3x the catenary length).
    Returns ``n`` samples equally spaced in ``s``. ``dalpha0``/``ddalpha0`` override the
    start curvature data (used only by the orders that carry them).
    """
    eps = Eps() if eps is None else eps
    if q <= 0 or h < 0 or H <= 0:
        raise ValueError(f"need q > 0, h >= 0, H > 0, got q={q}, h={h}, H={H}")
    st = catenary_start(q, h, k)
    if st.T >= 1.0:
        raise ValueError("start tension must be < 1 (chain faster than its transverse waves)")
    order = eps.order
    da0 = st.dalpha if dalpha0 is None else float(dalpha0)
    dda0 = st.ddalpha if ddalpha0 is None else float(ddalpha0)
    u0 = {
        1: [st.x, st.y, st.alpha, st.T],
        2: [st.x, st.y, st.alpha, da0, st.T],
        3: [st.x, st.y, st.alpha, da0, dda0, st.T],
    }[order]
    x_end = float(np.arccosh(1.0 + q * (h + H))) / q
    s_cat = (np.sinh(q * x_end) - np.sinh(q * st.x)) / q
    if s_max is None:
        s_max = 3.0 * s_cat
    y_floor = -(h + H)
    floor, apex = _events(y_floor)

    if method is None:
        # order 2 is stiff (decay rate (1 - T)/(e0 + e1 T)); orders 1 and 3 are not.
        method = "LSODA" if order == 2 else "DOP853"
    # the start is on the floor-crossing surface only if h == 0; it rises first for h > 0
    sol = solve_ivp(
        _rhs_factory(eps, k),
        (0.0, s_max),
        u0,
        method=method,
        rtol=rtol,
        atol=atol,
        events=(floor, apex),
        dense_output=True,
    )
    if sol.status < 0:
        raise RuntimeError(f"belt integration failed: {sol.message}")
    return _result(sol, n, y_floor, order, eps, k=k, q=q, h=h, H=H, s_cat=s_cat)
