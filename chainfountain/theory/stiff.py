"""The steady fountain of a chain with stiff or damped joints, as a two-point boundary
value problem.

A chain moving steadily at speed ``v`` along a fixed curve ``(x(s), y(s))`` of tangent
angle ``alpha(s)`` (``s`` the arc length from the launch, ``y`` up, curvature
``kappa = alpha'``). Its momentum balance is the paper's Eq. (2) (section "Equations of
Motion"), tension ``T`` along the tangent and shear ``N`` along the left normal, the
acceleration of a link moving along the curve being ``v^2 kappa`` towards it::

    T' = N kappa + lambda g sin(alpha)                       (tangential)
    N' = lambda g cos(alpha) - (T - lambda v^2) kappa        (normal)

Where it departs from the paper: the shear is not the paper's ansatz
``Qbar = -(e0 + e1 Tbar) alpha' - (e2 + e3 Tbar) alpha''`` but follows from the moment
balance of links of rotary inertia ``j = lambda L^2/12`` per length, which turn at
``v kappa`` as they move along the curve (angular acceleration ``v^2 kappa'``), with the
bending moment of a rotary spring ``c`` and damper ``d`` between links ``L`` apart. A
joint's relative angle is ``L kappa`` and, carried along the curve, changes at
``L v kappa'``, so::

    M = c L kappa + d L v kappa',     M' + N = j v^2 kappa'
    =>   N = (j v^2 - c L) kappa' - d L v kappa''

Scaled by ``lambda v^2`` (``Tbar = T/(lambda v^2)``, ``k = g/v^2``), with
``e = c L/(lambda v^2) - L^2/12`` (:func:`scaled_stiffness`: the paper's ``e2``, less the
links' rotary inertia, which enters with the opposite sign to the stiffness) and
``delta = d L/(lambda v)`` (:func:`scaled_damping`, m^3: the damper acts through
``kappa''``, one order higher than the paper's ansatz has it; ``e0``, ``e1`` and ``e3``
have no origin in a bending moment and are not here)::

    x' = cos(alpha),  y' = sin(alpha),  alpha' = kappa,
    delta kappa''' + e kappa'' = (Tbar - 1) kappa - k cos(alpha),
    Tbar' = -(e kappa' + delta kappa'') kappa + k sin(alpha)

Boundary conditions, as the simulator poses them: at the launch the guide fixes the
position and the direction (``x = y = 0``, ``alpha = alpha0``; it takes whatever moment
and shear the chain needs); with a damper also the curvature, ``kappa = 0`` (the chain is
straight in the guide, and a jump of the curvature carried at ``v`` would be an infinite
damper moment). At the absorbing floor ``y = -H`` the end is pulled with ``Tbar_E`` and is
free of moment and shear (``ec kappa + delta kappa' = 0``, ``e kappa' + delta kappa'' = 0``,
``ec = c L/(lambda v^2)``; ``kappa = kappa' = 0`` without a damper); the arc length ``S``
is free. With ``e, delta -> 0`` the solution is the paper's catenary
(:class:`~chainfountain.theory.fountain.Fountain`) but for layers at both ends.

Where ``e > 0`` (joints stiffer than the links' rotary inertia, ``c > lambda L v^2/12``)
the bending modes of wavenumber ``sqrt((1 - Tbar)/e)`` do not decay without a damper:
they stand along the whole fountain, and the vertex lies above or below the catenary's
by their phase there; a damper makes them grow downstream at the rate
``delta (1 - Tbar)/(2 e^2)`` (so they die out towards the guide) and adds a layer of
length ``delta/e`` at the launch. Without a damper only ``e > 0`` is solved (at
``e <= 0`` the catenary holds to layers of width ``sqrt(|e|/(1 - Tbar))``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_bvp

from chainfountain.theory.fountain import Fountain

Array = NDArray[np.float64]

MAX_NODES = 20_000
"""Mesh nodes the solver may use (a fountain of ``e = 1e-4`` m^2, 36 standing waves,
converges on fewer than 5,000; a solve that needs more is failing)."""

LAYER_FRACTION = 0.5
"""A damper whose launch layer (:func:`damper_layer`) is shorter than this fraction of a
link, and which changes the standing waves by less than :data:`FAINT_GROWTH`
(:func:`damper_growth`), does not change the fountain the links can show:
:func:`stiff_fountain_of` leaves it out (``solver.wave_damping``'s damper, a 2-mm layer on
2-cm links, is one)."""
FAINT_GROWTH = 0.01


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
    """``kappa'`` (1/m^2)."""
    ddkappa: Array
    """``kappa''`` (1/m^3): the scaled shear is ``-(e kappa' + delta kappa'')``."""
    T_bar: Array
    """Scaled tension ``T/(lambda v^2)``."""
    e: float
    """``c L/(lambda v^2) - L^2/12`` (m^2)."""
    delta: float = 0.0
    """``d L/(lambda v)`` (m^3)."""
    ec: float = 0.0
    """``c L/(lambda v^2)`` (m^2): the spring's part of :attr:`e`."""

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

    @property
    def shear_bar(self) -> Array:
        """Scaled shear ``N/(lambda v^2) = -(e kappa' + delta kappa'')``."""
        return -(self.e * self.dkappa + self.delta * self.ddkappa)

    @property
    def moment_bar(self) -> Array:
        """Scaled bending moment ``M/(lambda v^2) = ec kappa + delta kappa'`` (m)."""
        return self.ec * self.kappa + self.delta * self.dkappa

    @property
    def damped(self) -> bool:
        """Whether the damper is part of the solution (else ``delta`` is 0)."""
        return self.delta > 0.0


class NoSteadyFountain(ValueError):
    """The boundary value problem found no steady fountain (the solver's message)."""


def scaled_stiffness(c: float, L: float, lam: float, v: float) -> float:
    """``e = c L/(lambda v^2) - L^2/12`` (m^2): the bending stiffness less the links'
    rotary inertia, scaled by ``lambda v^2``."""
    return c * L / (lam * v * v) - L * L / 12.0


def scaled_damping(d: float, L: float, lam: float, v: float) -> float:
    """``delta = d L/(lambda v)`` (m^3): the joint damper's moment ``d L v kappa'`` scaled by
    ``lambda v^2``."""
    return d * L / (lam * v)


def damper_layer(e: float, delta: float) -> float:
    """Length of the damper's layer at the launch (m): ``delta/e`` where the stiffness
    dominates (``e > delta^(2/3)``), ``delta^(1/3)`` where it does not."""
    if delta <= 0.0:
        return 0.0
    cube = delta ** (1.0 / 3.0)
    return min(delta / e, cube) if e > 0.0 else cube


def damper_growth(e: float, delta: float, length: float) -> float:
    """How much a damper changes the standing bending waves over ``length`` (m): their
    growth exponent ``delta (1 - Tbar) length/(2 e^2)`` at ``Tbar = 0`` (0 without
    stiffness, where there are no such waves)."""
    if delta <= 0.0 or e <= 0.0:
        return 0.0
    return delta * length / (2.0 * e * e)


SETTLES_AT = 2.2
"""Smallest :func:`damper_decay` at which the simulated stiff fountains settle: of 30 runs
on two launches (``docs/stiff_stability.md``) every steady one has ``A >= 2.2`` and every
one with ``A <= 1.8`` is not steady (one stiff run cycles at 3.1)."""


def damper_decay(e: float, delta: float, length: float, T_bar_mean: float) -> float:
    """``A = delta (1 - Tbar) S/(2 e^2)``: how much the damper decays the standing bending
    waves over one pass of a flight of arc length ``S`` (:data:`SETTLES_AT`); ``inf``
    without stiffness (no standing waves), 0 without a damper."""
    if e <= 0.0:
        return math.inf if delta > 0.0 else 0.0
    return delta * (1.0 - T_bar_mean) * length / (2.0 * e * e)


def _guess(f: Fountain, n: int) -> tuple[Array, Array, float]:
    """The catenary ``f`` as a guess: ``sigma`` in [0, 1] and ``(x, y, alpha, kappa,
    kappa', kappa'', Tbar)`` from the launch, with its arc length."""
    xv, yv = f.curve(n)
    x0, y0 = f.start
    x, y = xv - x0, yv - y0
    ds = np.hypot(np.diff(x), np.diff(y))
    s = np.concatenate([[0.0], np.cumsum(ds)])
    alpha = -np.arctan(np.sinh(f.q * xv))  # the chain moves in +x, its tangent turns clockwise
    kappa = -f.q * np.cos(alpha) ** 2
    dkappa = np.gradient(kappa, s)
    ddkappa = np.gradient(dkappa, s)
    tbar = f.tension_bar(yv)
    return s / s[-1], np.vstack([x, y, alpha, kappa, dkappa, ddkappa, tbar]), float(s[-1])


def stiff_fountain(v: float, alpha0: float, H: float, TE_bar: float, e: float,
                   g: float = 9.81, guess: StiffFountain | None = None, n: int = 400,
                   tol: float = 1e-6, *, delta: float = 0.0,
                   ec: float | None = None) -> StiffFountain:
    """The steady fountain of scaled stiffness ``e`` (:func:`scaled_stiffness`) and damping
    ``delta`` (:func:`scaled_damping`) launched at ``v`` (m/s) and ``alpha0`` (rad) onto a
    floor ``H`` below pulling with ``TE_bar`` (the module docstring gives the equations and
    boundary conditions); ``ec``: the spring's part of ``e`` (default ``e``; it enters only
    the damped floor's moment). ``guess``: a solution nearby (continuation), else the
    paper's catenary. ``ValueError`` for ``e <= 0`` without a damper;
    :class:`NoSteadyFountain` when the solver does not converge."""
    if delta < 0.0:
        raise ValueError(f"delta = {delta:.3g} m^3: a damper cannot feed energy in")
    if not e > 0.0 and delta == 0.0:
        raise ValueError(f"e = {e:.3g} m^2: the joints are no stiffer than the links' "
                         "rotary inertia (c <= lambda L v^2/12); the paper's catenary holds "
                         "away from millimetre layers at the ends")
    ec = e if ec is None else ec
    k = g / (v * v)
    if guess is None:
        f = Fountain.from_launch(v=v, alpha0=alpha0, H=H, TE_bar=TE_bar, g=g)
        sigma, Y, S = _guess(f, n)
    else:
        S = float(guess.s[-1])
        sigma = guess.s / S
        Y = np.vstack([guess.x, guess.y, guess.alpha, guess.kappa, guess.dkappa,
                       guess.ddkappa, guess.T_bar])
    if delta > 0.0:
        sol = _solve_damped(Y, sigma, S, k, alpha0, H, TE_bar, e, ec, delta, tol)
    else:
        sol = _solve_stiff(Y[[0, 1, 2, 3, 4, 6]], sigma, S, k, alpha0, H, TE_bar, e, tol)
    if not sol.success:
        raise NoSteadyFountain(f"no steady stiff fountain found at e = {e:.3g} m^2, "
                               f"delta = {delta:.3g} m^3: {sol.message}")
    length = float(sol.p[0])
    sig = np.linspace(0.0, 1.0, max(n, 2000))
    Yv = sol.sol(sig)
    if not (length > 0.0 and np.isfinite(Yv).all() and Yv[1, :-1].min() > -H):
        raise NoSteadyFountain(f"no steady stiff fountain found at e = {e:.3g} m^2, "
                               f"delta = {delta:.3g} m^3: the solver's curve is not a "
                               "fountain (it runs backwards or meets the floor early)")
    if delta > 0.0:
        x, y, a, kap, dkap, ddkap, tb = Yv
    else:
        x, y, a, kap, dkap, tb = Yv
        with np.errstate(divide="ignore", invalid="ignore"):
            ddkap = ((tb - 1.0) * kap - k * np.cos(a)) / e
    return StiffFountain(s=sig * length, x=x, y=y, alpha=a, kappa=kap, dkappa=dkap,
                         ddkappa=ddkap, T_bar=tb, e=e, delta=delta, ec=ec)


def _solve_stiff(Y: Array, sigma: Array, S: float, k: float, alpha0: float, H: float,
                 TE_bar: float, e: float, tol: float):  # noqa: ANN202 - scipy's result
    """Without a damper: state ``(x, y, alpha, kappa, kappa', Tbar)``, unknown ``S``."""

    def rhs(sig: Array, Yv: Array, p: Array) -> Array:
        x, y, a, kap, dkap, tb = Yv
        return p[0] * np.vstack([np.cos(a), np.sin(a), kap, dkap,
                                 ((tb - 1.0) * kap - k * np.cos(a)) / e,
                                 -e * dkap * kap + k * np.sin(a)])

    def bc(ya: Array, yb: Array, p: Array) -> Array:
        return np.array([ya[0], ya[1], ya[2] - alpha0, yb[1] + H, yb[5] - TE_bar,
                         yb[3], yb[4]])

    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # trial steps
        return solve_bvp(rhs, bc, sigma, Y, p=[S], tol=tol, max_nodes=MAX_NODES)


def _solve_damped(Y: Array, sigma: Array, S: float, k: float, alpha0: float, H: float,
                  TE_bar: float, e: float, ec: float, delta: float, tol: float):  # noqa: ANN202
    """With a damper: state ``(x, y, alpha, kappa, kappa', kappa'', Tbar)``, unknown ``S``;
    the launch's ``kappa = 0`` is the damper's extra condition."""

    def rhs(sig: Array, Yv: Array, p: Array) -> Array:
        x, y, a, kap, dkap, ddkap, tb = Yv
        return p[0] * np.vstack([np.cos(a), np.sin(a), kap, dkap, ddkap,
                                 ((tb - 1.0) * kap - k * np.cos(a) - e * ddkap) / delta,
                                 -(e * dkap + delta * ddkap) * kap + k * np.sin(a)])

    def bc(ya: Array, yb: Array, p: Array) -> Array:
        return np.array([ya[0], ya[1], ya[2] - alpha0, ya[3], yb[1] + H, yb[6] - TE_bar,
                         ec * yb[3] + delta * yb[4], e * yb[4] + delta * yb[5]])

    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # trial steps
        return solve_bvp(rhs, bc, sigma, Y, p=[S], tol=tol, max_nodes=MAX_NODES)


def stiff_fountain_of(c: float, d: float, L: float, lam: float, v: float, alpha0: float,
                      H: float, TE_bar: float, g: float = 9.81,
                      guess: StiffFountain | None = None) -> StiffFountain | None:
    """The steady fountain of a chain of links ``L`` (m) and ``lam`` (kg/m) with joint
    springs ``c`` (N*m/rad) and dampers ``d`` (N*m*s/rad), launched at ``v``, ``alpha0``
    onto a floor ``H`` below pulling with ``TE_bar``: :func:`stiff_fountain` at
    :func:`scaled_stiffness` and :func:`scaled_damping`. ``None`` where neither matters
    (``e <= 0`` and a damper too faint to show, :data:`LAYER_FRACTION`): the paper's
    catenary is then the fountain.
    Tries the catenary's guess (or ``guess``) first, then continues from the loose chain
    (stiffness first, then the damper), giving up at the first step that fails;
    :class:`NoSteadyFountain` when none of these converges."""
    e = scaled_stiffness(c, L, lam, v)
    delta = scaled_damping(d, L, lam, v)
    ec = c * L / (lam * v * v)
    if delta > 0.0 and damper_layer(e, delta) < LAYER_FRACTION * L:
        span = Fountain.from_launch(v=v, alpha0=alpha0, H=H, TE_bar=TE_bar, g=g).length
        if damper_growth(e, delta, span) < FAINT_GROWTH:
            delta = 0.0
    if delta == 0.0 and not e > 0.0:
        return None
    try:
        return stiff_fountain(v, alpha0, H, TE_bar, e, g, guess=guess, delta=delta, ec=ec)
    except NoSteadyFountain as first:
        last: StiffFountain | None = None
        for e_i, d_i, ec_i in _ramp(e, delta):  # stops at the first step it cannot take
            try:
                last = stiff_fountain(v, alpha0, H, TE_bar, e_i, g, guess=last, delta=d_i,
                                      ec=ec_i)
            except NoSteadyFountain:
                raise first from None
        if last is None:
            raise first from None
        return stiff_fountain(v, alpha0, H, TE_bar, e, g, guess=last, delta=delta, ec=ec)


def _ramp(e: float, delta: float, steps: int = 12) -> list[tuple[float, float, float]]:
    """``(e, delta, ec)`` from nearly loose joints to ``(e, delta)``: the stiffness
    first, at the spring's own ``ec``, then the damper."""
    out = []
    if e > 0.0:
        out += [(float(x), 0.0, float(x)) for x in np.geomspace(e * 1e-2, e, steps)]
    if delta > 0.0:
        out += [(e, float(x), max(e, 0.0)) for x in np.geomspace(delta * 1e-3, delta, steps)]
    return out


def continued(v: float, alpha0: float, H: float, TE_bar: float,
              path: list[tuple[float, float, float]] | list[float],
              g: float = 9.81) -> list[StiffFountain | None]:
    """:func:`stiff_fountain` along ``path`` (stiffnesses ``e``, or ``(e, delta, ec)``),
    each solved from the last one found (``None`` where none was)."""
    out: list[StiffFountain | None] = []
    last: StiffFountain | None = None
    for p in path:
        e, delta, ec = (p, 0.0, p) if isinstance(p, float | int) else p
        try:
            last = stiff_fountain(v, alpha0, H, TE_bar, e, g, guess=last, delta=delta, ec=ec)
        except NoSteadyFountain:
            out.append(None)
            continue
        out.append(last)
    return out


@dataclass(frozen=True)
class Branch:
    """One family of steady stiff fountains found by continuation in ``e``."""

    e: Array
    """Scaled stiffnesses (m^2) where the branch was followed."""
    h: Array
    """Vertex height there (m); ``nan`` where the branch was lost."""
    l: Array  # noqa: E741 - the paper's name
    """Landing distance there (m)."""


def branches(v: float, alpha0: float, H: float, TE_bar: float, es: list[float],
             g: float = 9.81, delta: float = 0.0, rel: float = 1e-3) -> list[Branch]:
    """The steady fountains over the stiffnesses ``es`` (ascending) at damping ``delta``:
    continued upwards from the loosest, downwards from the stiffest, and solved afresh from
    the catenary at each. Solutions more than ``rel`` apart in vertex height at the same
    ``e`` are distinct branches, and where a branch ends between two ``es`` (``nan``) it
    folds or is lost there. Returns the distinct branches (the first: the upward one)."""
    es = sorted(float(x) for x in es)
    runs = [
        continued(v, alpha0, H, TE_bar, [(e, delta, e) for e in es], g),
        continued(v, alpha0, H, TE_bar, [(e, delta, e) for e in es[::-1]], g)[::-1],
    ]
    fresh: list[StiffFountain | None] = []
    for e in es:
        try:
            fresh.append(stiff_fountain(v, alpha0, H, TE_bar, e, g, delta=delta))
        except (NoSteadyFountain, ValueError):
            fresh.append(None)
    runs.append(fresh)
    found: list[Branch] = []
    for run in runs:
        h = np.array([np.nan if s is None else s.h for s in run])
        l_ = np.array([np.nan if s is None else s.l for s in run])
        if not any(_same(h, b.h, rel) for b in found):
            found.append(Branch(e=np.array(es), h=h, l=l_))
    return found


def _same(a: Array, b: Array, rel: float) -> bool:
    """Whether two branches agree wherever both exist (and overlap somewhere)."""
    both = np.isfinite(a) & np.isfinite(b)
    return bool(both.any() and np.all(np.abs(a[both] - b[both]) <= rel * np.abs(b[both])))
