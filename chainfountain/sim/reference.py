"""Theory reference for a fed fountain, expressed in the simulator's launch frame.

The simulator puts the launch point (guide exit) at the origin; the paper puts
the vertex there. :class:`LaunchReference` holds the paper's prediction for a
feed at speed ``v`` and angle ``alpha0`` with zero end tension ``H`` below the
launch point (section "Inverted Catenary")::

    Tbar_0 = k*H,   q = k/(cos(alpha0)*(1 - k*H)),   h = (1/cos(alpha0) - 1)/q,
    vertex at (acosh(1 + q*h)/q, h),  landing at x = (acosh(1 + q*h) + acosh(1 + q*(h+H)))/q,
    Tbar(y) = 1 - k/q + k*y  (y from the vertex).

It uses :class:`chainfountain.theory.Fountain` when that is importable and
the same closed forms otherwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from chainfountain.theory.tension import tension_bar

if TYPE_CHECKING:
    from chainfountain.sim.config import FeedConfig, SimConfig


@dataclass(frozen=True)
class LaunchReference:
    """Predicted steady fountain for a launch at the origin (y up, chain moving in +x)."""

    v: float
    alpha0: float
    H: float
    g: float
    k: float
    q: float
    h: float
    T0_bar: float
    TE_bar: float = 0.0

    theory: ClassVar[str] = "catenary"
    """Which theory: ``summary.json``'s ``theory.theory``."""
    label: ClassVar[str] = "the paper's catenary"
    """What the outputs call it."""

    @classmethod
    def from_launch(cls, v: float, alpha0: float, H: float, g: float = 9.81,
                    TE_bar: float = 0.0) -> LaunchReference:
        """The paper's fountain for a launch at ``v``, ``alpha0`` with end tension ``TE_bar``
        at the floor ``H`` below (:meth:`chainfountain.theory.Fountain.from_launch`)."""
        from chainfountain.theory import Fountain

        f = Fountain.from_launch(v=v, alpha0=alpha0, H=H, TE_bar=TE_bar, g=g)
        return cls(v=v, alpha0=alpha0, H=H, g=g, k=float(f.k), q=float(f.q), h=float(f.h),
                   T0_bar=float(f.T0_bar), TE_bar=float(TE_bar))

    @classmethod
    def of_feed(cls, feed: FeedConfig, g: float) -> LaunchReference:
        """The paper's fountain for a motor feed's speed, angle, drop and end tension
        (:meth:`from_launch`; ``ValueError`` when there is none)."""
        return cls.from_launch(feed.speed, feed.launch_angle, feed.drop, g,
                               TE_bar=feed.end_tension)

    @classmethod
    def of_level(cls, config: SimConfig, v: float | None = None) -> LaunchReference:
        """The paper's fountain for a fed level whose chain runs at ``v`` (default: the start
        speed ``feed.speed``). A motor feed runs at ``v`` with its floor's ``end_tension``;
        the idealized beaker with a real floor (``feed.drive = "ideal_floor"``) at the speed
        it selects, whatever ``v``; the ideal full machine (``"ideal_fold"``) at the speed it
        selects when its bearings drag, and at ``v`` when it is loss-free (it keeps any
        speed), with the end tension its lower half supplies there; the open arrangement
        (``"ideal_open"``) at the speed it selects, pulled by its turn's weight.
        ``ValueError`` when there is no fountain."""
        from chainfountain.theory.apparatus import (
            ideal_floor_speed,
            ideal_fold_speed,
            ideal_open_speed,
        )

        f = config.feed
        lam, g = config.chain.linear_density, config.gravity
        v = f.speed if v is None else v
        if f.drive == "ideal_floor":
            v = ideal_floor_speed(f.drop, f.xi2, f.cart_force, lam, g)
        elif f.drive == "ideal_open":
            v = ideal_open_speed(f.drop, f.xi2, f.cart_force, f.turn_drop, lam, g)
        elif f.drive == "ideal_fold" and f.bearing_drag > 0.0:
            v = ideal_fold_speed(f.cart_force, f.lower_cart_force, f.xi2, f.xi3,
                                 f.bearing_drag, lam, f.drop, g)
        if not math.isfinite(v):
            raise ValueError("the machine selects no speed")
        return cls.at_speed(config, v)

    @classmethod
    def at_speed(cls, config: SimConfig, v: float) -> LaunchReference:
        """The paper's fountain for a fed level whose chain runs at ``v``, whatever speed
        its machine selects: launched at ``v`` with the end tension the level's lower end
        supplies at ``v`` (a motor feed's ``end_tension``; the full machine's put-down law,
        ``ideal_fold_TE_bar``; the open arrangement's turn, ``k d``; none on the idealized
        beaker's floor). For a machine that selects its speed this is the fountain it
        flies at the speed it runs, beside :meth:`of_level`'s at the speed its laws
        select; ``ValueError`` when there is no fountain."""
        from chainfountain.theory.apparatus import ideal_fold_TE_bar, ideal_open_TE_bar

        if not (math.isfinite(v) and v > 0.0):
            raise ValueError(f"no fountain at a chain speed of {v:g} m/s")
        f = config.feed
        lam, g = config.chain.linear_density, config.gravity
        TE_bar = f.end_tension
        if f.drive == "ideal_floor":
            TE_bar = 0.0
        elif f.drive == "ideal_open":
            TE_bar = ideal_open_TE_bar(v, f.turn_drop, g)
        elif f.drive == "ideal_fold":
            TE_bar = max(0.0, ideal_fold_TE_bar(v, f.xi3, f.lower_cart_force, lam, f.drop, g,
                                                f.bearing_drag))
        return cls.from_launch(v, f.launch_angle, f.drop, g, TE_bar=TE_bar)

    @property
    def x_rise(self) -> float:
        """Horizontal distance launch -> vertex: ``acosh(1 + q*h)/q``."""
        return math.acosh(1.0 + self.q * self.h) / self.q

    @property
    def x_fall(self) -> float:
        """Horizontal distance vertex -> landing: ``acosh(1 + q*(h+H))/q``."""
        return math.acosh(1.0 + self.q * (self.h + self.H)) / self.q

    @property
    def vertex(self) -> tuple[float, float]:
        """Vertex position in the launch frame."""
        return (self.x_rise, self.h)

    @property
    def landing_x(self) -> float:
        """Landing point x (= the paper's ``l``) in the launch frame."""
        return self.x_rise + self.x_fall

    @property
    def arc_length(self) -> float:
        """Length of chain in flight: ``(sinh(q*x_rise) + sinh(q*x_fall))/q``."""
        return (math.sinh(self.q * self.x_rise) + math.sinh(self.q * self.x_fall)) / self.q

    def y_of_x(self, x: ArrayLike) -> NDArray[np.float64]:
        """Launch-frame height of the catenary ``q*y = 1 - cosh(q*x)`` (paper Eq. func_graph)."""
        xv = np.asarray(x, dtype=float) - self.x_rise
        return self.h + (1.0 - np.cosh(self.q * xv)) / self.q

    def tension_bar(self, y: ArrayLike) -> NDArray[np.float64]:
        """Scaled tension ``1 - k/q + k*y_vertex`` at launch-frame height ``y``."""
        return tension_bar(np.asarray(y, dtype=float) - self.h, self.q, self.k)

    def points_at_arc(self, s: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64],
                                                    NDArray[np.float64]]:
        """Position ``(x, y)`` and tangent angle at arc length ``s`` from the launch point.

        Arc length from the vertex is ``sinh(q*x)/q``, so ``x = asinh(q*s_v)/q``.
        """
        s_v = np.asarray(s, dtype=float) - math.sinh(self.q * self.x_rise) / self.q
        xv = np.arcsinh(self.q * s_v) / self.q
        x = xv + self.x_rise
        y = self.h + (1.0 - np.cosh(self.q * xv)) / self.q
        angle = -np.arctan(np.sinh(self.q * xv))
        return x, y, angle

    def tension_profile(self, x: ArrayLike, y: ArrayLike) -> NDArray[np.float64]:
        """Scaled tension at chain points ``(x, y)``: :meth:`tension_bar` of ``y`` (the
        catenary's tension depends on the height alone)."""
        return self.tension_bar(y)

    def curve(self, n: int = 200) -> NDArray[np.float64]:
        """``n`` points ``(x, y)`` along the catenary from the launch to the floor."""
        x, y, _ = self.points_at_arc(np.linspace(0.0, self.arc_length, n))
        return np.column_stack((x, y))

    def describe(self) -> str:
        """What the outputs call this theory."""
        return self.label
