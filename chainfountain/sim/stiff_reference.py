"""The steady stiff-chain fountain as a fed level's theory reference, in the launch frame.

A motor-fed chain with joint springs ``c`` or dampers ``d`` (``chain.bending_stiffness``,
``chain.bending_damping``) does not fly on the paper's catenary: its steady fountain is
the boundary value problem of :mod:`chainfountain.theory.stiff`. :class:`StiffReference`
wraps that solution in the interface of :class:`~chainfountain.sim.reference.
LaunchReference` (vertex, landing, arc length, ``y_of_x``, ``points_at_arc``, tensions),
by interpolation along the solution's arc length, with the catenary beside it
(:attr:`StiffReference.catenary`). :func:`predict` chooses the theory for a level:
the catenary, the stiff fountain, or none, with the reason (:class:`Prediction`).

The simulator's own use of the catenary (the floor's pull along its landing tangent,
the spin of links leaving the guide, the chain laid on it by ``initial.mode =
"catenary"``) stays with :attr:`Prediction.catenary`: what the chain is compared with
does not change how it is driven.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chainfountain.sim.reference import LaunchReference
from chainfountain.theory.stiff import (
    SETTLES_AT,
    NoSteadyFountain,
    StiffFountain,
    damper_decay,
    stiff_fountain_of,
)

if TYPE_CHECKING:
    from chainfountain.sim.config import SimConfig

Array = NDArray[np.float64]

GUESS_NODES = 400
"""Nodes of a previous solution passed on as the next solve's guess (continuation): the
solution's 2000 output points as a guess cost the solver about three times as long."""


@dataclass(frozen=True)
class StiffReference:
    """The steady stiff fountain of a fed level (launch at the origin, ``y`` up, the chain
    moving in ``+x``), read like a :class:`~chainfountain.sim.reference.LaunchReference`."""

    fountain: StiffFountain
    """The boundary value problem's solution (:func:`chainfountain.theory.stiff.
    stiff_fountain`)."""
    catenary: LaunchReference
    """The paper's catenary for the same launch (what a chain without joint resistance
    flies on)."""
    c: float
    """Joint spring (N*m/rad)."""
    d: float
    """Joint damper (N*m*s/rad)."""

    theory: ClassVar[str] = "stiff"
    """Which theory: ``summary.json``'s ``theory.theory``."""
    label: ClassVar[str] = "stiff-chain theory"
    """What the outputs call it."""

    # ------------------------------------------------------------------ launch data
    @property
    def v(self) -> float:
        return self.catenary.v

    @property
    def alpha0(self) -> float:
        return self.catenary.alpha0

    @property
    def H(self) -> float:
        return self.catenary.H

    @property
    def g(self) -> float:
        return self.catenary.g

    @property
    def k(self) -> float:
        """``g/v^2`` (1/m)."""
        return self.catenary.k

    @property
    def q(self) -> float:
        """The catenary's parameter (1/m): a stiff fountain has none; the catenary fit to a
        measured shape starts from it."""
        return self.catenary.q

    @property
    def TE_bar(self) -> float:
        return self.catenary.TE_bar

    @property
    def e(self) -> float:
        """Scaled stiffness ``c L/(lambda v^2) - L^2/12`` (m^2)."""
        return float(self.fountain.e)

    @property
    def delta(self) -> float:
        """Scaled damping ``d L/(lambda v)`` (m^3; 0 where the damper is too faint to
        show and the solution leaves it out)."""
        return float(self.fountain.delta)

    # ------------------------------------------------------------------ figures
    @property
    def h(self) -> float:
        """Vertex height above the launch (m)."""
        return self.fountain.h

    @property
    def T0_bar(self) -> float:
        """Scaled tension at the launch."""
        return self.fountain.T0_bar

    @property
    def x_rise(self) -> float:
        """Horizontal distance launch -> vertex (m)."""
        return self.fountain.vertex_x

    @property
    def x_fall(self) -> float:
        """Horizontal distance vertex -> landing (m)."""
        return self.landing_x - self.x_rise

    @property
    def vertex(self) -> tuple[float, float]:
        """Vertex position in the launch frame."""
        return (self.x_rise, self.h)

    @property
    def landing_x(self) -> float:
        """Where the chain reaches the floor, horizontally from the launch (m)."""
        return self.fountain.l

    @property
    def arc_length(self) -> float:
        """Length of chain in flight (m)."""
        return float(self.fountain.s[-1])

    @property
    def landing_angle(self) -> float:
        """Tangent angle at the floor (rad, from ``+x``; negative: falling)."""
        return float(self.fountain.alpha[-1])

    def damper_decay(self) -> float:
        """How much the damper decays the standing bending waves over one pass of the
        flight (:func:`chainfountain.theory.stiff.damper_decay`)."""
        f = self.fountain
        return damper_decay(f.e, f.delta, float(f.s[-1]), float(np.mean(f.T_bar)))

    @property
    def settles(self) -> bool:
        """Whether a simulated chain settles on this fountain (the damper's decay at least
        :data:`chainfountain.theory.stiff.SETTLES_AT`; ``docs/stiff_stability.md``)."""
        return self.damper_decay() >= SETTLES_AT

    def describe(self) -> str:
        """``stiff-chain theory at c = ..., d = ...`` with the scaled figures."""
        scaled = f"e = {self.e:.3g} m^2" + (f", delta = {self.delta:.3g} m^3"
                                             if self.delta > 0.0 else "")
        return f"{self.label} at {joints(self.c, self.d)} ({scaled})"

    # ------------------------------------------------------------------ the curve
    def _x(self) -> Array:
        """The solution's ``x`` made non-decreasing (it is, but for round-off where the
        chain would fly back)."""
        return np.maximum.accumulate(self.fountain.x)

    def y_of_x(self, x: ArrayLike) -> Array:
        """Launch-frame height of the stiff curve over ``x`` (interpolated)."""
        return np.interp(np.asarray(x, dtype=float), self._x(), self.fountain.y)

    def points_at_arc(self, s: ArrayLike) -> tuple[Array, Array, Array]:
        """Position ``(x, y)`` and tangent angle at arc length ``s`` from the launch
        (interpolated; clamped to the ends)."""
        f = self.fountain
        sv = np.asarray(s, dtype=float)
        return np.interp(sv, f.s, f.x), np.interp(sv, f.s, f.y), np.interp(sv, f.s, f.alpha)

    def curve(self, n: int = 200) -> Array:
        """``n`` points ``(x, y)`` along the curve from the launch to the floor."""
        x, y, _ = self.points_at_arc(np.linspace(0.0, self.arc_length, n))
        return np.column_stack((x, y))

    def tension_bar(self, y: ArrayLike) -> Array:
        """Scaled tension at launch-frame height ``y`` on the falling side (vertex to
        floor). The rising side's differs by the bending term (``Tbar' = -(e kappa' +
        delta kappa'') kappa + k sin(alpha)``); :meth:`tension_profile` reads the tension
        where the chain is."""
        f = self.fountain
        i = int(np.argmax(f.y))
        yy, tb = f.y[i:][::-1], f.T_bar[i:][::-1]  # increasing height
        return np.interp(np.asarray(y, dtype=float), np.maximum.accumulate(yy), tb)

    def tension_profile(self, x: ArrayLike, y: ArrayLike) -> Array:
        """Scaled tension of the stiff fountain at chain points ``(x, y)``, read over
        ``x`` (the curve is single-valued in ``x``, not in ``y``)."""
        return np.interp(np.asarray(x, dtype=float), self._x(), self.fountain.T_bar)

    def tension_curve(self, n: int = 60) -> tuple[Array, Array]:
        """Heights and scaled tensions along the curve, launch to floor (``n`` points)."""
        s = np.linspace(0.0, self.arc_length, n)
        f = self.fountain
        return np.interp(s, f.s, f.y), np.interp(s, f.s, f.T_bar)

    def thinned(self, n: int = GUESS_NODES) -> StiffFountain:
        """The solution on about ``n`` of its points: the next solve's guess."""
        f = self.fountain
        m = len(f.s)
        if m <= n:
            return f
        idx = np.unique(np.linspace(0, m - 1, n).round().astype(int))
        return dataclasses.replace(f, **{
            fd.name: getattr(f, fd.name)[idx] for fd in dataclasses.fields(f)
            if isinstance(getattr(f, fd.name), np.ndarray) and len(getattr(f, fd.name)) == m})


Reference = LaunchReference | StiffReference
"""A fed level's theory reference: the paper's catenary or the stiff fountain."""


def joints(c: float, d: float) -> str:
    """``c = 0.1 N*m/rad, d = 0.002 N*m*s/rad``."""
    return f"c = {c:.4g} N*m/rad, d = {d:.4g} N*m*s/rad"


def headline(note: str) -> str:
    """A :attr:`Prediction.note` without the solver's message (for the window)."""
    return note.split(" (", 1)[0]


@dataclass(frozen=True)
class Prediction:
    """What a fed level is compared with: :attr:`reference` (``None`` where no theory
    predicts a steady fountain, :attr:`note` says why), and the paper's catenary for
    the same launch (``None`` when there is no fountain at all)."""

    reference: Reference | None
    catenary: LaunchReference | None
    note: str = ""
    """Why :attr:`reference` is ``None`` although :attr:`catenary` is not ("no steady
    stiff fountain at c = ..., d = ..."), or ''."""

    @property
    def theory(self) -> str:
        """``"catenary"``, ``"stiff"`` (a reference or, with :attr:`note`, none), or
        ``"none"`` (no fountain at all)."""
        if self.reference is not None:
            return self.reference.theory
        return "stiff" if self.catenary is not None else "none"


def stiff_applies(config: SimConfig) -> bool:
    """Whether a level's chain is compared with the stiff theory: a motor-fed fountain
    (:attr:`~chainfountain.sim.kinds.base.Kind.stiff_theory`) whose joints have a spring
    or a damper (physical ``c`` or ``d``; the numerical ``solver.wave_damping`` is not the
    chain's)."""
    from chainfountain.sim.kinds import kind_of

    ch = config.chain
    return kind_of(config).stiff_theory and (ch.bending_stiffness > 0.0
                                             or ch.bending_damping > 0.0)


def solve(c: float, d: float, L: float, lam: float, v: float, alpha0: float, H: float,
          TE_bar: float, g: float, guess: StiffFountain | None = None) -> StiffFountain | None:
    """The steady stiff fountain of joints ``c``, ``d`` (the one call of the theory,
    :func:`~chainfountain.theory.stiff.stiff_fountain_of`); ``None`` where neither spring
    nor damper matters (the catenary holds);
    :class:`~chainfountain.theory.stiff.NoSteadyFountain` where none is found."""
    return stiff_fountain_of(c, d, L, lam, v, alpha0, H, TE_bar, g, guess=guess)


def predict(config: SimConfig, catenary: LaunchReference | None,
            guess: StiffReference | None = None) -> Prediction:
    """The theory a fed level at the catenary's speed is compared with: the catenary, or
    for a motor-fed chain with joint resistance (:func:`stiff_applies`) the steady stiff
    fountain, solved from ``guess`` (the last one, continuation) when given."""
    if catenary is None or not stiff_applies(config):
        return Prediction(catenary, catenary)
    ch = config.chain
    c, d = float(ch.bending_stiffness), float(ch.bending_damping)
    try:
        f = solve(c, d, ch.link_length, ch.linear_density, catenary.v, catenary.alpha0,
                  catenary.H, catenary.TE_bar, catenary.g,
                  guess=None if guess is None else guess.thinned())
    except NoSteadyFountain as exc:
        return Prediction(None, catenary, f"no steady stiff fountain at {joints(c, d)} "
                          f"({exc})")
    if f is None:
        return Prediction(catenary, catenary)
    if not (math.isfinite(f.h) and math.isfinite(f.l)):
        return Prediction(None, catenary, f"no steady stiff fountain at {joints(c, d)}")
    return Prediction(StiffReference(f, catenary, c, d), catenary)
