"""The steady fountain of a chain with stiff joints, as a two-point boundary value problem.

A chain moving steadily at speed ``v`` along a fixed curve ``(x(s), y(s))`` of tangent
angle ``alpha(s)`` (``s`` the arc length from the launch, ``y`` up, curvature
``kappa = alpha'``). Its momentum balance is the paper's Eq. (2) (section "Equations of
Motion"), tension ``T`` along the tangent and shear ``N`` along the left normal, the
acceleration of a link moving along the curve being ``v^2 kappa`` towards it::

    T' = N kappa + lambda g sin(alpha)                       (tangential)
    N' = lambda g cos(alpha) - (T - lambda v^2) kappa        (normal)

Where it departs from the paper: the shear is not the paper's ansatz but follows from
the moment balance of links of rotary inertia ``j = lambda L^2/12`` per length, which
turn at ``v kappa`` as they move along the curve (so their angular acceleration is
``v^2 kappa'``), with the bending moment of a rotary spring ``c`` between links ``L``
apart, ``M = c L kappa`` (the joints' damper ``d`` adds ``d L v kappa'``; it is not
in this module)::

    M' + N = j v^2 kappa'   =>   N = (j v^2 - c L) kappa'

Scaled by ``lambda v^2`` (``Tbar = T/(lambda v^2)``, ``k = g/v^2``) and with
``e = c L/(lambda v^2) - L^2/12`` (the paper's ``e2`` of its ansatz, less the links'
rotary inertia, which enters with the opposite sign to the stiffness)::

    x' = cos(alpha),  y' = sin(alpha),  alpha' = kappa,
    e kappa'' = (Tbar - 1) kappa - k cos(alpha),
    Tbar' = -e kappa' kappa + k sin(alpha)

Boundary conditions, as the simulator poses them: at the launch the guide fixes the
position and the direction (``x = y = 0``, ``alpha = alpha0``; it takes whatever moment
and shear the chain needs); at the absorbing floor ``y = -H`` the end is pulled with
``Tbar_E`` and is free of moment and shear (``kappa = kappa' = 0``); the arc length ``S``
is free. With ``e -> 0`` the solution is the paper's catenary
(:class:`~chainfountain.theory.fountain.Fountain`) but for layers of width
``sqrt(|e|/(1 - Tbar))`` at both ends. Where ``e > 0`` (joints stiffer than the links'
rotary inertia, ``c > lambda L v^2/12``) the bending modes do not decay: bending waves
of wavelength ``2 pi sqrt(e/(1 - Tbar))`` stand along the whole fountain, and the
vertex lies above or below the catenary's by their phase there. Only ``e > 0`` is
solved here.

Against the simulator (``wide_low`` with ``chain.bending_stiffness`` c, no damper,
started on the catenary, the window 2.5-4 s): at c = 0.121 N*m/rad the simulated vertex
is +2.7 % above the catenary and this solution +4.5 %; at c = 0.25, -9.8 % and -4.0 %.
The direction agrees, the size does not: those fountains are not steady (their speed in
flight drifts by up to 3 % by 8-10 s), so this module is not yet the simulator's
reference for stiff runs (issue 62).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_bvp

from chainfountain.theory.fountain import Fountain

Array = NDArray[np.float64]


@dataclass(frozen=True)
class StiffFountain:
    """A steady stiff fountain: the curve from the launch (origin) to the floor."""

    s: Array
    """Arc length from the launch (m)."""
    x: Array
    y: Array
    alpha: Array
    """Tangent angle from ``+x`` (rad)."""
    kappa: Array
    """Curvature ``alpha'`` (1/m)."""
    dkappa: Array
    """``kappa'`` (1/m^2): the shear is ``-e kappa' lambda v^2``."""
    T_bar: Array
    """Scaled tension ``T/(lambda v^2)``."""
    e: float
    """``c L/(lambda v^2) - L^2/12`` (m^2)."""

    @property
    def h(self) -> float:
        """Vertex height above the launch (m)."""
        return float(self.y.max())

    @property
    def vertex_x(self) -> float:
        """Horizontal distance of the vertex from the launch (m)."""
        return float(self.x[int(np.argmax(self.y))])

    @property
    def l(self) -> float:  # noqa: E743 - the paper's name
        """Where the chain lands, horizontally from the launch (m)."""
        return float(self.x[-1])

    @property
    def T0_bar(self) -> float:
        """Scaled tension at the launch."""
        return float(self.T_bar[0])


class NoSteadyFountain(ValueError):
    """The boundary value problem found no steady fountain (the solver's message)."""


def scaled_stiffness(c: float, L: float, lam: float, v: float) -> float:
    """``e = c L/(lambda v^2) - L^2/12`` (m^2): the bending stiffness less the links'
    rotary inertia, scaled by ``lambda v^2``."""
    return c * L / (lam * v * v) - L * L / 12.0


def _guess(f: Fountain, n: int) -> tuple[Array, Array]:
    """The catenary ``f`` as a guess: ``sigma`` in [0, 1] and ``(x, y, alpha, kappa,
    kappa', Tbar)`` from the launch, with its arc length."""
    xv, yv = f.curve(n)
    x0, y0 = f.start
    x, y = xv - x0, yv - y0
    ds = np.hypot(np.diff(x), np.diff(y))
    s = np.concatenate([[0.0], np.cumsum(ds)])
    alpha = np.arctan(np.sinh(f.q * xv))  # y = (cosh(q x) - 1)/q turned over: slope
    alpha = -alpha  # the chain moves in +x and its tangent turns clockwise
    kappa = -f.q * np.cos(alpha) ** 2
    dkappa = np.gradient(kappa, s)
    tbar = f.tension_bar(yv)
    return s / s[-1], np.vstack([x, y, alpha, kappa, dkappa, tbar]), float(s[-1])


def stiff_fountain(v: float, alpha0: float, H: float, TE_bar: float, e: float,
                   g: float = 9.81, guess: StiffFountain | None = None, n: int = 400,
                   tol: float = 1e-6) -> StiffFountain:
    """The steady fountain of scaled stiffness ``e`` (:func:`scaled_stiffness`) launched
    at ``v`` (m/s) and ``alpha0`` (rad) onto a floor ``H`` below pulling with ``TE_bar``
    (see the module docstring); ``guess``: a solution nearby (continuation), else the
    paper's catenary. :class:`NoSteadyFountain` when the solver does not converge."""
    if not e > 0.0:
        raise ValueError(f"e = {e:.3g} m^2: the joints are no stiffer than the links' "
                         "rotary inertia (c <= lambda L v^2/12); the paper's catenary holds "
                         "away from millimetre layers at the ends")
    k = g / (v * v)
    if guess is None:
        f = Fountain.from_launch(v=v, alpha0=alpha0, H=H, TE_bar=TE_bar, g=g)
        sigma, Y, S = _guess(f, n)
    else:
        S = float(guess.s[-1])
        sigma = guess.s / S
        Y = np.vstack([guess.x, guess.y, guess.alpha, guess.kappa, guess.dkappa,
                       guess.T_bar])

    def rhs(sig: Array, Yv: Array, p: Array) -> Array:
        x, y, a, kap, dkap, tb = Yv
        length = p[0]
        return length * np.vstack([np.cos(a), np.sin(a), kap, dkap,
                                   ((tb - 1.0) * kap - k * np.cos(a)) / e,
                                   -e * dkap * kap + k * np.sin(a)])

    def bc(ya: Array, yb: Array, p: Array) -> Array:
        return np.array([ya[0], ya[1], ya[2] - alpha0, yb[1] + H, yb[5] - TE_bar,
                         yb[3], yb[4]])

    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # trial steps
        sol = solve_bvp(rhs, bc, sigma, Y, p=[S], tol=tol, max_nodes=200_000)
    if not sol.success:
        raise NoSteadyFountain(f"no steady stiff fountain found at e = {e:.3g} m^2: "
                               f"{sol.message}")
    length = float(sol.p[0])
    sig = np.linspace(0.0, 1.0, max(n, 2000))
    x, y, a, kap, dkap, tb = sol.sol(sig)
    return StiffFountain(s=sig * length, x=x, y=y, alpha=a, kappa=kap, dkappa=dkap,
                         T_bar=tb, e=e)


def continued(v: float, alpha0: float, H: float, TE_bar: float, es: list[float],
              g: float = 9.81) -> list[StiffFountain | None]:
    """:func:`stiff_fountain` along the stiffnesses ``es`` (ascending), each solved from
    the last one found (``None`` where none was)."""
    out: list[StiffFountain | None] = []
    last: StiffFountain | None = None
    for e in es:
        try:
            last = stiff_fountain(v, alpha0, H, TE_bar, e, g, guess=last)
        except NoSteadyFountain:
            out.append(None)
            continue
        out.append(last)
    return out


