"""The divergence watchdog: stops a run whose numbers have left physics.

An explicit integrator driven past its stability limit (links too short for the
time step, a slider pushed to an extreme) does not fail gently: link speeds grow
by orders of magnitude within a few milliseconds of simulated time, and once the
coordinates are astronomically large the physics engine's collision index can
exhaust the machine's memory. :class:`Watchdog` reads every body of the space every
:data:`CHECK_INTERVAL` of simulated time (one batch call and one reduction, about
1 % of a step's cost) and raises :class:`Diverged` (a
:class:`~chainfountain.errors.RunEnded`: the window pauses with the message, a
headless run writes the part simulated and exits with status 3) as soon as a body

- has a non-finite position or velocity,
- moves faster than :attr:`Limits.speed`, or
- is farther than :attr:`Limits.radius` from the origin.

The limits are far outside anything the level can do physically (ten times the
fastest speed the level's energy allows), so a healthy run never trips them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pymunk
import pymunk.batch as pb

from chainfountain.errors import RunEnded

CHECK_INTERVAL = 2e-3
"""Simulated seconds between two checks (a diverging run is stopped within this)."""


class Diverged(RunEnded):
    """The simulation's numbers blew up (see the module docstring)."""


@dataclass(frozen=True)
class Limits:
    """Bounds a healthy run of a level never reaches."""

    speed: float
    """Largest link speed (m/s)."""
    radius: float
    """Largest distance of a link from the origin (m)."""

    @classmethod
    def for_level(cls, speed: float, height: float, g: float) -> Limits:
        """Limits for a level whose chain moves at ``speed`` (m/s) in a scene of
        ``height`` (m, the drop and rise together): ten times the fastest speed
        energy allows, ``sqrt(speed**2 + 2*g*height)``, at least 50 m/s; a radius of
        ten times the scene plus 20 m."""
        v_max = math.sqrt(speed**2 + 2.0 * max(g, 0.0) * max(height, 0.0))
        return cls(speed=max(50.0, 10.0 * v_max), radius=20.0 + 10.0 * max(height, 1.0))


class Watchdog:
    """Checks the bodies of a space against :class:`Limits` (see the module docstring)."""

    def __init__(self, space: pymunk.Space, limits: Limits) -> None:
        self.space = space
        self.limits = limits
        self._buf = pb.Buffer()

    def check(self, t: float) -> None:
        """Raise :class:`Diverged` if a body breaks the limits (``t``: simulated time, s)."""
        buf = self._buf
        buf.clear()
        pb.get_space_bodies(self.space, pb.BodyFields.POSITION | pb.BodyFields.VELOCITY, buf)
        data = np.frombuffer(buf.float_buf(), dtype=np.float64)
        if len(data) == 0:
            return
        lim = self.limits
        biggest = float(np.max(np.abs(data)))  # NaN propagates
        if biggest < min(lim.speed, lim.radius) / 2.0:  # the common case: one reduction
            return
        d = data.reshape(-1, 4)
        check(d[:, 0:2], d[:, 2:4], lim, t)


def check(pos: np.ndarray, vel: np.ndarray, limits: Limits, t: float) -> None:
    """Raise :class:`Diverged` if positions ``pos`` or velocities ``vel`` (each ``(n, 2)``)
    break ``limits`` (``t``: simulated time, s)."""
    if not (np.isfinite(pos).all() and np.isfinite(vel).all()):
        raise Diverged(f"the simulation diverged at t = {t:.3f} s (a position or speed "
                       f"is not a number); {_ADVICE}")
    speed = float(np.sqrt(np.max(np.einsum("ij,ij->i", vel, vel))))
    if speed > limits.speed:
        raise Diverged(f"the simulation diverged at t = {t:.3f} s: a link moves at "
                       f"{speed:.3g} m/s (a healthy run stays below {limits.speed:.0f} m/s); "
                       f"{_ADVICE}")
    r = float(np.sqrt(np.max(np.einsum("ij,ij->i", pos, pos))))
    if r > limits.radius:
        raise Diverged(f"the simulation diverged at t = {t:.3f} s: a link is {r:.3g} m from "
                       f"the start (a healthy run stays within {limits.radius:.0f} m); "
                       f"{_ADVICE}")


_ADVICE = "a smaller solver.dt or longer chain links keep it stable"
