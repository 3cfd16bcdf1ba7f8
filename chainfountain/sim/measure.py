"""Measurements on a running chain: batch readout, signed joint tension, geometry, recording.

All readouts use :mod:`pymunk.batch` (one C call for all bodies) and numpy.

Signed tension (momentum balance). Chipmunk integrates semi-implicitly:
velocities get gravity first, then the constraint and contact impulses, then
positions move. So for one link over one step ``dt``::

    m*(v_new - v_old) - m*g*dt = J_joints + J_contacts

exactly. Summing from the free (downstream) end, link 0, gives the force that
link ``j+1`` exerts on link ``j`` at their joint::

    F_j = sum_{i<=j} (m*(v_new_i - v_old_i)/dt - m*g - C_i/dt)

(rotary springs apply pure torques and drop out). Its component along the
chain, pointing upstream, is the signed tension ``T_j`` (negative = push); the
normal component is the shear force ``Q`` of the paper's belt model. Scaled as
in the paper: ``Tbar = T/(lambda*v^2)``, compared with ``Tbar(y) = 1 - k/q + k*y``.

Re-touching contacts. pymunk keeps a contact that stops touching for
``Space.collision_persistence`` steps (3). When the shapes touch again within that
window, Chipmunk copies the old accumulated impulses into the new contact points
(``cpArbiterUpdate``) but skips their warm start (a first contact), so
``Arbiter.total_impulse`` reports an impulse that this step never applied. Call
:meth:`ChainReader.arm` before the step whose contacts are read: it captures those
starting impulses in a pre-solve callback (during that step only) and
:meth:`ChainReader.contact_impulses` subtracts them (``docs/apparatus.md``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pymunk
import pymunk.batch as pb
from numpy.typing import NDArray

from chainfountain.sim.chain import Chain

_FIELDS = (pb.BodyFields.BODY_ID | pb.BodyFields.POSITION | pb.BodyFields.ANGLE
           | pb.BodyFields.VELOCITY | pb.BodyFields.ANGULAR_VELOCITY)
_ARB_FIELDS = pb.ArbiterFields.BODY_A_ID | pb.ArbiterFields.BODY_B_ID | \
    pb.ArbiterFields.TOTAL_IMPULSE

Array = NDArray[np.float64]


@dataclass
class ChainState:
    """State of all links in chain order (index 0 = downstream end)."""

    position: Array  # (n, 2) centres
    angle: Array  # (n,)
    velocity: Array  # (n, 2)
    angular_velocity: Array  # (n,)


class ChainReader:
    """Reads the state of a :class:`Chain`'s links with one batch call.

    The order of bodies in the space changes whenever bodies are added,
    removed or change type (Chipmunk swap-removes), so bodies are matched by
    id; the permutation is cached and verified on every read.
    """

    def __init__(self, space: pymunk.Space, chain: Chain) -> None:
        self.space = space
        self.chain = chain
        self._buf = pb.Buffer()
        self._abuf = pb.Buffer()
        self._version = -1
        self._ids: NDArray[np.uintp] = np.zeros(0, dtype=np.uintp)
        self._perm: NDArray[np.intp] | None = None
        self._armed = False
        self._stale: list[tuple[int, int, float, float]] = []

    def _chain_ids(self) -> NDArray[np.uintp]:
        if self._version != self.chain.version:
            self._ids = np.array(self.chain.ids, dtype=np.uintp)
            self._version = self.chain.version
            self._perm = None
        return self._ids

    def read(self) -> ChainState:
        """Positions, angles, velocities of every link, chain order."""
        buf = self._buf
        buf.clear()
        pb.get_space_bodies(self.space, _FIELDS, buf)
        ids = np.frombuffer(buf.int_buf(), dtype=np.uintp)
        data = np.frombuffer(buf.float_buf(), dtype=np.float64).reshape(-1, 6)
        want = self._chain_ids()
        perm = self._perm
        if perm is None or len(perm) != len(want) or perm.max(initial=-1) >= len(ids) \
                or not np.array_equal(ids[perm], want):
            order = np.argsort(ids, kind="stable")
            pos = np.searchsorted(ids, want, sorter=order)
            perm = order[pos]
            if not np.array_equal(ids[perm], want):
                raise RuntimeError("chain bodies missing from the space")
            self._perm = perm
        d = data[perm]
        return ChainState(position=d[:, 0:2], angle=d[:, 2], velocity=d[:, 3:5],
                          angular_velocity=d[:, 5])

    def arm(self) -> None:
        """Capture, during the next step only, the impulses that re-touching contacts
        start from (see the module docstring); :meth:`contact_impulses` then reports
        the impulses that step applied. Costs one Python call per touching pair in
        that step; the physics is not changed (the callback only reads). Does nothing
        for a chain without shapes (no contacts to read)."""
        self._stale.clear()
        if not self._armed and self.chain.shapes:
            self.space.on_collision(pre_solve=self._capture)
            self._armed = True

    def _disarm(self) -> None:
        if self._armed:
            self.space.on_collision(pre_solve=pymunk.empty_callback)
            self._armed = False

    def _capture(self, arb: pymunk.Arbiter, space: pymunk.Space, data: object) -> None:
        if arb.is_first_contact:
            imp = arb.total_impulse
            if imp.x or imp.y:
                a, b = arb.bodies
                self._stale.append((a.id, b.id, imp.x, imp.y))

    def contact_impulses(self) -> Array:
        """Net contact impulse of the last step on every link, chain order, shape ``(n, 2)``.

        From the space's arbiters: the impulse on body A is ``+total_impulse``,
        on body B ``-total_impulse`` (checked in ``tests/sim/test_measure.py``).
        If :meth:`arm` was called before the step, the impulses that re-touching
        contacts started from (reported, never applied) are taken out; otherwise
        they are included, as pymunk reports them.
        """
        want = self._chain_ids()
        out = np.zeros((len(want), 2))
        stale, armed = list(self._stale), self._armed
        self._stale.clear()
        self._disarm()
        if not self.chain.shapes:
            return out
        buf = self._abuf
        buf.clear()
        pb.get_space_arbiters(self.space, _ARB_FIELDS, buf)
        ab = np.frombuffer(buf.int_buf(), dtype=np.uintp).reshape(-1, 2)
        if len(ab) == 0:
            return out
        imp = np.frombuffer(buf.float_buf(), dtype=np.float64).reshape(-1, 2)
        if armed and stale:
            ab = np.vstack((ab, np.array([r[:2] for r in stale], dtype=np.uintp)))
            imp = np.vstack((imp, -np.array([r[2:] for r in stale])))
        order = np.argsort(want)
        sw = want[order]
        for col, sign in ((0, 1.0), (1, -1.0)):
            idx = np.searchsorted(sw, ab[:, col])
            idx = np.clip(idx, 0, len(sw) - 1)
            hit = sw[idx] == ab[:, col]
            np.add.at(out, order[idx[hit]], sign * imp[hit])
        return out


def link_ends(state: ChainState, L: float) -> tuple[Array, Array]:
    """Front (downstream) and back (upstream) end points of every link, each ``(n, 2)``."""
    u = np.column_stack((np.cos(state.angle), np.sin(state.angle)))
    h = 0.5 * L
    return state.position + h * u, state.position - h * u


def polyline(state: ChainState, L: float) -> Array:
    """Chain as a polyline ``(n+1, 2)``: front end of link 0, then joint midpoints, back end."""
    front, back = link_ends(state, L)
    if len(front) == 0:
        return np.zeros((0, 2))
    mid = 0.5 * (back[:-1] + front[1:])
    return np.vstack((front[:1], mid, back[-1:]))


def joint_forces(pre: ChainState, post: ChainState, mass: float, dt: float, g: float,
                 n_dyn: int, contacts: Array | None = None) -> Array:
    """Force ``F_j`` (N) that link ``j+1`` exerts on link ``j``, ``j = 0 .. n_dyn-1``.

    Momentum balance summed from the free end (module docstring). ``n_dyn`` is
    the number of dynamic links counted from the downstream end; links beyond
    (kinematic guide, anchors) are the supports.
    """
    dv = post.velocity[:n_dyn] - pre.velocity[:n_dyn]
    imp = mass * dv
    imp[:, 1] += mass * g * dt
    if contacts is not None:
        imp -= contacts[:n_dyn]
    return np.cumsum(imp, axis=0) / dt


def signed_tension(forces: Array, state: ChainState, n_dyn: int) -> tuple[Array, Array]:
    """Tension (along the chain, + = pull) and shear at joints ``0 .. n_dyn-1``.

    The chain direction at joint ``j`` is the mean of links ``j`` and ``j+1``
    (the last joint uses link ``j`` alone when there is no upstream neighbour).
    """
    ang = state.angle
    u = np.column_stack((np.cos(ang), np.sin(ang)))
    n = len(ang)
    e = u[:n_dyn].copy()
    m = min(n_dyn, n - 1)
    e[:m] += u[1:m + 1]
    e /= np.linalg.norm(e, axis=1)[:, None]
    up = -e  # upstream direction
    tension = np.einsum("ij,ij->i", forces, up)
    shear = forces[:, 0] * up[:, 1] - forces[:, 1] * up[:, 0]
    return tension, shear


def vertex_of(points: Array) -> tuple[float, float]:
    """Highest point of a polyline, refined by the parabola through it and its two neighbours."""
    y = points[:, 1]
    i = int(np.argmax(y))
    if i == 0 or i == len(points) - 1:
        return float(points[i, 0]), float(y[i])
    (x0, y0), (x1, y1), (x2, y2) = points[i - 1], points[i], points[i + 1]
    # parabola y = a*(x - x1)^2 + b*(x - x1) + y1 through the three points
    d0, d2 = x0 - x1, x2 - x1
    den = d0 * d2 * (d0 - d2)
    if den == 0.0:
        return float(x1), float(y1)
    a = ((y0 - y1) * d2 - (y2 - y1) * d0) / den
    b = ((y2 - y1) * d0 * d0 - (y0 - y1) * d2 * d2) / den
    if a >= 0.0:
        return float(x1), float(y1)
    xv = -b / (2.0 * a)
    if not (min(d0, d2) <= xv <= max(d0, d2)):
        return float(x1), float(y1)
    return float(x1 + xv), float(y1 - b * b / (4.0 * a))


def fit_catenary(points: Array, x_v: float, y_v: float, q0: float,
                 iterations: int = 8) -> tuple[float, float, float]:
    """Least-squares fit of ``q*(y - y_v) = 1 - cosh(q*(x - x_v))`` (paper Eq. func_graph).

    Gauss-Newton on ``(x_v, y_v, q)`` starting from the given values; returns
    the fitted ``(x_v, y_v, q)``. A shape no catenary fits (a fountain that has fallen
    into a line) drives the iteration to overflow: it stops there and raises
    :class:`FloatingPointError`, which the caller records as a failed fit.
    """
    x, y = points[:, 0], points[:, 1]
    p = np.array([x_v, y_v, max(q0, 1e-6)])
    for _ in range(iterations):
        xv, yv, q = p
        with np.errstate(over="ignore", invalid="ignore"):
            z = q * (x - xv)
            ch, sh = np.cosh(z), np.sinh(z)
            model = yv + (1.0 - ch) / q
            r = y - model
            # d model / d(xv, yv, q)
            jac = np.column_stack((sh, np.ones_like(x),
                                   -(1.0 - ch) / q**2 - sh * (x - xv) / q))
        if not (np.all(np.isfinite(jac)) and np.all(np.isfinite(r))):
            raise FloatingPointError("the catenary fit diverged (no catenary fits this shape)")
        step, *_ = np.linalg.lstsq(jac, r, rcond=None)
        p = p + step
        p[2] = max(p[2], 1e-6)
        if np.all(np.abs(step) < 1e-10):
            break
    return float(p[0]), float(p[1]), float(p[2])


def landing_x(state: ChainState, L: float, floor_y: float) -> float:
    """Where the downstream end link, extended as a line, crosses the floor height."""
    if len(state.angle) == 0:
        return math.nan
    front, back = link_ends(state, L)
    dx, dy = front[0] - back[0]
    if dy > -1e-9:
        return float(front[0, 0])
    return float(back[0, 0] + (floor_y - back[0, 1]) * dx / dy)


@dataclass
class Sample:
    """One recorded measurement of the free chain."""

    t: float
    vertex_x: float
    vertex_y: float
    landing_x: float
    speed_mean: float
    speed_min: float
    speed_max: float
    stretch: float
    n_free: int
    T0_bar: float
    plate_reaction: float = math.nan
    """The open arrangement with ideal rollers (``feed.drive = "ideal_open"``): the lower
    plate's reaction force (N), the weight of the chain landed on it; nan otherwise."""


@dataclass
class Profiles:
    """Per-link arrays of one sample, ordered from the launch point downstream."""

    tension_bar: Array  # at joints, starting with the guide joint
    x: Array  # joint positions
    y: Array
    speed: Array  # per free link
    t: float = math.nan
    """Time of the sample the profile belongs to (s)."""


def steady_time(t: Array, series: Array, tol: float, smoothing: float = 0.0,
                window: float = 1.0) -> float | None:
    """Earliest time from which ``series`` stays within ``tol`` (relative) of its final mean.

    The series is first smoothed with a centred moving average over ``smoothing`` seconds
    (near the ends, over the samples within reach); the reference value is the mean over
    the final ``window`` seconds. Returns ``None`` when the last sample is outside.
    """
    t = np.asarray(t, dtype=float)
    s = np.asarray(series, dtype=float)
    if len(t) < 2:
        return None
    dt = float(np.median(np.diff(t)))
    n = max(1, int(round(smoothing / dt))) if smoothing > 0 else 1
    if n > 1 and len(s) >= n:
        kernel = np.ones(n)
        # near the ends the average is over the samples there are (a raw end sample would
        # decide alone, and a chaotic fountain's raw top is never within a tight band)
        sm = np.convolve(s, kernel, mode="same") / np.convolve(np.ones(len(s)), kernel,
                                                                mode="same")
    else:
        sm = s
    ref = float(np.mean(s[t >= t[-1] - window]))
    bad = np.abs(sm - ref) > tol * abs(ref)
    if bad[-1]:
        return None
    idx = np.flatnonzero(bad)
    return float(t[0]) if len(idx) == 0 else float(t[idx[-1] + 1])


@dataclass
class Summary:
    """Time averages over a window ``[t0, t1]`` and comparison with the reference."""

    t0: float
    t1: float
    samples: int
    vertex_x: float
    vertex_y: float
    landing_x: float
    q_fit: float
    """Catenary fit (paper Eq. func_graph) to the time-averaged free-chain shape."""
    speed_mean: float
    speed_uniformity: float
    """max |mean speed of a link position - overall mean| / overall mean (time-averaged)."""
    speed_spread_inst: float
    """mean over samples of (max - min)/mean link speed."""
    stretch_max: float
    T0_bar: float
    tension_rms: float
    """RMS over the free chain of (time-averaged Tbar - reference Tbar(y)); nan if no reference."""
    steady_from: float | None
    extras: dict = field(default_factory=dict)
    failed: dict[str, str] = field(default_factory=dict)
    """Analyses that failed on this window's data (name: reason); their figures are nan."""

    def errors(self, ref) -> dict[str, float]:
        """Errors against a :class:`~chainfountain.sim.reference.LaunchReference`, named as
        in ``summary.json``'s ``theory``: relative (``measured / predicted - 1``) for the
        vertex height ``h``, ``vertex_x``, the landing ``l``, ``q`` and the speed ``v``;
        absolute for ``T0_bar``; ``tension_rms`` as is."""
        return {
            "h": self.vertex_y / ref.h - 1.0,
            "vertex_x": self.vertex_x / ref.x_rise - 1.0,
            "l": self.landing_x / ref.landing_x - 1.0,
            "q": self.q_fit / ref.q - 1.0,
            "v": self.speed_mean / ref.v - 1.0,
            "T0_bar": self.T0_bar - ref.T0_bar,
            "tension_rms": self.tension_rms,
        }
