"""Where the apparatus's chain loses energy: an exact impulse sweep, by region.

The paper's apparatus is loss-free apart from the unfolding and folding; the simulated
one also loses energy in its frictionless guides, because a velocity-level constraint
on a discrete, curved path is not energy-neutral. This module measures that loss
without reading any single joint's tension (docs/apparatus.md).

For every sampled step the sweep starts at the free end (a 'floor' apparatus with the
absorbing end, or the 'open' one's lumped tail end, whose end pull is an external
force) and walks upstream to the last link held in the upper plate's groove.
Each link has three unknowns: its upstream pivot impulse ``J`` (2) and, if a guide or
groove holds it, that constraint's impulse along the constraint's known normal (1,
applied at the link centre, so no torque). Its momentum and angular momentum changes
over the step give three equations, so the sweep is exact. (For a free link the
rotation equation is left over: its residual checks the sweep, ``rotation_residual``.)
Since ``m (v1**2 - v0**2)/2 = (m dv) . (v0 + v1)/2`` per body, the work of each impulse
at the mid-step velocity of its anchor splits the chain's energy change exactly:

- a pivot between links ``i`` and ``i+1`` does ``J . (u_back_i - u_front_i+1)``, the
  solver's own dissipation at that joint;
- a guide or groove impulse ``g n`` does ``g n . v_i``; a frictionless path does none
  in the continuum.

The losses are summed by region (free flight, the upper guide's arcs and straights,
the plate grooves; for 'open' also the turn after landing and the tail's grooves) and
given per unit time in units of ``lambda v**3``, i.e. as the tension the steady balance
must supply beyond the loss-free one: the speed the rig law selects with the loss added
to its ``p_inf`` is ``selected_speed(..., dp=loss)``
(:func:`chainfountain.sim.apparatus.selected_speed`). For the non-stationary 'open'
variant the loss enters the momentum law of the moving chain as a force
(:func:`open_windows`): the paper's use for such runs, "to quantify dissipative
influences".
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from chainfountain.sim.apparatus import (
    CART_GAIN_2CM,
    Apparatus,
    rig_exit_tension,
    selected_speed,
)

if TYPE_CHECKING:
    from chainfountain.sim.config import SimConfig
    from chainfountain.sim.world import Simulation

REGIONS = ("flight", "arc", "line", "plate", "turn", "tail")
"""Free flight (and the free end); the upper joint guide's arcs and straight lines; the
upper plate's grooves; 'open' only: the turn after landing (slide joints to its centre)
and the tail's grooves on the lower plate (with the lumped end link)."""
_RADIAL = ("arc", "turn")
"""Regions whose joints push along the radius from a centre (the others: a fixed normal)."""
EXACT = 1e-12
"""Largest free-link rotation residual (N m s) of a sweep that closes (rounding gives
about 1e-19; a link's angular impulse ``I dw`` is of order 1e-6)."""


@dataclass
class BudgetResult:
    """Time-averaged losses (positive: energy taken out of the chain), per region."""

    v: float
    """Mean speed of the 40 links nearest the free end (m/s)."""
    seconds: float
    """Simulated time the averages cover (sampled pymunk steps times their step ``h``,
    times ``every``)."""
    steps: int
    pivots: dict[str, float] = field(default_factory=dict)
    """Loss in the pivots whose downstream link is in the region (``lambda v**3``)."""
    guides: dict[str, float] = field(default_factory=dict)
    """Loss in the region's guide or groove joints (``lambda v**3``)."""
    rotation_residual: float = 0.0
    """Largest |angular momentum residual| of a free link (N m s): the sweep's check."""

    @property
    def exact(self) -> bool:
        """Did the sweep close? A free link that touched anything (a contact the sweep
        does not know) leaves a rotation residual far above rounding."""
        return self.steps > 0 and self.rotation_residual < EXACT

    @property
    def total(self) -> float:
        """All losses between the plate's upstream end and the free end (``lambda v**3``)."""
        return sum(self.pivots.values()) + sum(self.guides.values())

    def region(self, name: str) -> float:
        return self.pivots.get(name, 0.0) + self.guides.get(name, 0.0)


def lower_kinds(app: Apparatus, n_tail: int, n_turn: int) -> list:
    """:func:`sweep` kinds of an 'open' chain's first ``n_tail + n_turn`` links: the tail in
    the lower plate's grooves (normal up), then the links the turn's slide joints hold
    (radial from the turn's centre). The guide always holds the chain's leading links."""
    up = np.array([0.0, 1.0])
    centre = np.array(app.guide_centre, dtype=float)
    return [("tail", up)] * n_tail + [("turn", centre)] * n_turn


def sweep(kinds: list, position: np.ndarray, angle: np.ndarray, dp: np.ndarray,
          dL: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """The exact impulse sweep over links ``0 .. n-1`` from the free end (module docstring).

    ``kinds[i]`` is None for a free link, else ``(region, a)``: a joint through the link
    centre pushing along the radius from centre ``a`` (regions in ``arc``, ``turn``) or
    along the fixed normal ``a``. ``dp`` is each link's momentum change plus its weight's
    impulse less any external impulse (``m dv + m g dt - F dt``), ``dL`` its angular
    momentum change, ``h`` half the link length.

    Returns ``J`` (n, 2), the impulse link ``i+1`` applies to link ``i`` at its back
    anchor (``-h u``); ``gn`` (n), each joint's impulse along its normal ``nrm`` (n, 2;
    zero rows for free links); and the largest rotation residual of a free link."""
    n = len(kinds)
    u = np.column_stack((np.cos(angle), np.sin(angle)))
    wv = np.column_stack((-u[:, 1], u[:, 0]))
    J = np.zeros((n, 2))
    gn = np.zeros(n)
    nrm = np.zeros((n, 2))
    resid = 0.0
    Jx = Jy = 0.0  # upstream pivot impulse of the previous (downstream) link
    for i in range(n):
        ux, uy = u[i]
        # link i gets -J_prev at its front anchor (+h u): torque h*(u x -J_prev)
        tq = -h * (ux * Jy - uy * Jx)
        bx, by = dp[i, 0] + Jx, dp[i, 1] + Jy  # = J + g n
        k = kinds[i]
        if k is None:
            jx, jy = bx, by
            # rotation: dL = (-h u) x J + tq
            resid = max(resid, abs(dL[i] - (-h * (ux * jy - uy * jx) + tq)))
        else:
            reg, a = k
            nx, ny = (position[i] - a) / np.hypot(*(position[i] - a)) if reg in _RADIAL \
                else a
            jw = -(dL[i] - tq) / h  # J . w from the rotation equation
            rx, ry = bx - jw * wv[i, 0], by - jw * wv[i, 1]
            det = ux * ny - uy * nx
            a_par = (rx * ny - ry * nx) / det
            gn[i] = (ux * ry - uy * rx) / det
            nrm[i] = nx, ny
            jx = a_par * ux + jw * wv[i, 0]
            jy = a_par * uy + jw * wv[i, 1]
        J[i] = Jx, Jy = jx, jy
    return J, gn, nrm, float(resid)


class EnergyBudget:
    """Attach to a 'floor' (absorbing end) or 'open' (joint turn, lumped tail)
    :class:`~chainfountain.sim.world.Simulation` with the upper joint guide and plate
    grooves; sampled steps from ``start`` (s), every ``every``-th.

    ``sim.probe`` is set to this object; the simulation calls :meth:`before` and
    :meth:`after` around each physics step. Physics is unchanged (only reads).
    """

    def __init__(self, sim: Simulation, start: float = 0.0, every: int = 1) -> None:
        app = sim.apparatus
        floor = app is not None and app.variant == "floor" and app.end_mode == "absorbing"
        if not (floor or (app is not None and app.variant == "open" and app.guided)):
            raise ValueError("EnergyBudget needs an apparatus of variant 'floor' with the "
                             "absorbing end, or 'open' with plate = 'groove' (the sweep "
                             "starts at the free end)")
        if not app.upper_guided:
            raise ValueError("EnergyBudget needs apparatus.upper_guide = 'joints' (with the "
                             "walls the guide's contacts act off the link centres, which "
                             "the sweep does not handle)")
        if app.plate_mode != "groove":
            raise ValueError("EnergyBudget needs apparatus.plate = 'groove' (the sweep ends "
                             "at the plate's last grooved link)")
        if every < 1:
            raise ValueError(f"every must be >= 1 (got {every})")
        self.sim, self.app = sim, app
        self.start, self.every = float(start), int(every)
        self._work = {f"{r}:{k}": 0.0 for r in REGIONS for k in ("pivot", "guide")}
        self._steps = 0
        self._vsum = 0.0
        self._resid = 0.0
        self._pending: tuple | None = None
        sim.probe = self

    # ------------------------------------------------------------------ hooks
    def before(self) -> None:
        """Called after the apparatus's ``before_step``, before the physics step."""
        sim, app = self.sim, self.app
        self._pending = None
        if sim.apparatus is not app:
            raise RuntimeError("EnergyBudget: the simulation was rebuilt (reset); attach a "
                               "new EnergyBudget to measure the new run")
        if sim.time < self.start - 1e-12 or (sim.steps + 1) % self.every:
            return
        links = app.chain.links
        kind: dict[int, tuple[str, np.ndarray]] = {}  # arc: centre; line, plate: normal
        for el, q in zip(app.up_guide, app.upper_held, strict=True):
            if el.form == "arc":
                c = np.array(el.a, dtype=float)
                for lk, _ in q:
                    kind[id(lk.body)] = ("arc", c)
            else:
                (ax, ay), (bx, by) = el.a, el.b
                t = np.array([bx - ax, by - ay], dtype=float)
                t /= np.hypot(*t)
                n = np.array([-t[1], t[0]])
                for lk, _ in q:
                    kind[id(lk.body)] = ("line", n)
        up = np.array([0.0, 1.0])
        for lk, _ in app.plate_grooves:
            kind[id(lk.body)] = ("plate", up)
        last = -1
        for i, lk in enumerate(links):
            k = kind.get(id(lk.body))
            if k is not None and k[0] == "plate":
                last = i
        if last < 1:
            return
        pre = sim.reader.read()  # the chain does not change during the physics step
        n = last + 1
        kinds = [kind.get(id(lk.body)) for lk in links[:n]]
        if app.variant == "open":
            low = lower_kinds(app, app.tail_grooved, len(app.turn_held))
            kinds[:len(low)] = low
        end = links[0].body  # the lumped tail's end link is heavier ('open')
        self._pending = (kinds, pre.velocity[:n].copy(), pre.angular_velocity[:n].copy(),
                         end.mass, end.moment)

    def after(self) -> None:
        """Called after the physics step, before the apparatus's ``after_step``."""
        if self._pending is None:
            return
        kinds, v0, w0, m_end, I_end = self._pending
        self._pending = None
        sim, app = self.sim, self.app
        dt, g = sim.h, sim.g  # one pymunk step (``solver.dt / solver.substeps``)
        h = 0.5 * app.L
        n = len(kinds)
        m = np.full(n, app.chain.mass)
        I = np.full(n, app.chain.moment)
        m[0], I[0] = m_end, I_end
        post = sim.reader.read()
        v1, w1 = post.velocity[:n], post.angular_velocity[:n]
        P, th = post.position[:n], post.angle[:n]
        u = np.column_stack((np.cos(th), np.sin(th)))
        wv = np.column_stack((-u[:, 1], u[:, 0]))
        vm, om = 0.5 * (v0 + v1), 0.5 * (w0 + w1)
        back = vm - (om * h)[:, None] * wv   # velocity of the anchor at -h u
        front = vm + (om * h)[:, None] * wv  # ... at +h u
        dp = m[:, None] * (v1 - v0)
        dp[:, 1] += m * g * dt
        dp[0, 0] -= app.end_pull * dt  # external ('open'), on the end link's centre
        J, gn, nrm, resid = sweep(kinds, P, th, dp, I * (w1 - w0), h)
        self._resid = max(self._resid, resid)
        work = self._work
        guide = gn * np.einsum("ij,ij->i", nrm, vm)
        pivot = np.einsum("ij,ij->i", J[:-1], back[:-1] - front[1:])
        for i, k in enumerate(kinds):
            reg = "flight" if k is None else k[0]
            if k is not None:
                work[f"{reg}:guide"] += guide[i]
            if i < n - 1:
                work[f"{reg}:pivot"] += pivot[i]
        self._steps += 1
        k = min(40, n)
        self._vsum += float(np.mean(np.hypot(v1[:k, 0], v1[:k, 1])))

    # ------------------------------------------------------------------ result
    def result(self) -> BudgetResult:
        """Averages so far (nan speed if nothing was sampled)."""
        if not self._steps:
            return BudgetResult(v=float("nan"), seconds=0.0, steps=0)
        v = self._vsum / self._steps
        secs = self._steps * self.sim.h  # sampled pymunk steps
        scale = -1.0 / (secs * self.sim.config.chain.linear_density * v ** 3)
        return BudgetResult(
            v=v, seconds=secs * self.every, steps=self._steps,
            pivots={r: self._work[f"{r}:pivot"] * scale + 0.0 for r in REGIONS},
            guides={r: self._work[f"{r}:guide"] * scale + 0.0 for r in REGIONS},
            rotation_residual=self._resid)


def rig_law_speed(cfg: SimConfig, loss: float = 0.0) -> float:
    """Speed (m/s) the rig law selects for a 'floor' level ``cfg`` (its first cart is the
    upper cart) with ``loss`` (``lambda v**3``, e.g. :attr:`BudgetResult.total`) added to
    the pick-up's ``p_inf``: :func:`~chainfountain.sim.apparatus.selected_speed` with
    ``dp = loss`` and the rig's cart gain."""
    a, cart = cfg.apparatus, cfg.carts[0]
    F_uc = cart.mass * cfg.gravity * math.sin(cart.incline)
    return selected_speed(cfg.gravity, a.drop, a.xi2, F_uc, cfg.chain.linear_density,
                          gain=CART_GAIN_2CM, dp=loss, drag=a.bearing_drag)


@dataclass(frozen=True)
class OpenWindow:
    """One window of an 'open' run: the measured acceleration of the chain against the
    momentum law of the moving chain, ``M dv/dt = F_drive - T_exit(v) - D/v``."""

    t0: float
    t1: float
    v: float
    """Mean speed of the upper plate's strand (m/s)."""
    mass: float
    """Mean moving mass (kg; links faster than 0.5 m/s and the lumped tail)."""
    budget: BudgetResult
    a_measured: float
    """Slope of the strand speed over the window (m/s^2)."""
    a_law: float
    """``(F_drive - T_exit(v))/M`` with the rig law's exit tension (m/s^2): loss-free."""
    a_law_loss: float
    """The same with the budget's loss ``D/v = loss lambda v_end**3 / v`` taken off."""


def open_windows(sim: Simulation, start: float, end: float, width: float,
                 every: int = 1) -> list[OpenWindow]:
    """Advance an 'open' :class:`~chainfountain.sim.world.Simulation` (joint guides, plate
    grooves) from ``start`` to ``end`` (s) in windows of ``width`` (s), with an
    :class:`EnergyBudget` over each, and compare the chain's acceleration with the
    momentum law (docs/apparatus.md).

    The moving chain (roller exit to the lumped tail's end) on its fixed path obeys
    ``M(t) dv/dt = lambda g (y_up - y_lo) + F_pull - T_exit(v) - D/v``, where ``T_exit``
    is the rig law (:func:`~chainfountain.sim.apparatus.rig_exit_tension`) and ``D`` the
    power the budget finds lost between the plate and the free end."""
    app = sim.apparatus
    if app is None or app.variant != "open":
        raise ValueError("open_windows needs an apparatus of variant 'open'")
    if not (width > 0 and sim.time <= start + 1e-9 and start < end):
        raise ValueError(f"open_windows: need time {sim.time:g} <= start {start:g} < end "
                         f"{end:g} and width {width:g} > 0")
    lam = sim.config.chain.linear_density
    sim.advance(start - sim.time)
    out = []
    t = start
    while t < end - 1e-9:
        t1 = min(end, t + width)
        eb = EnergyBudget(sim, start=t, every=every)
        rows = []
        while sim.time < t1 - 1e-9:
            sim.advance(min(0.01, t1 - sim.time))
            rows.append((sim.time, app.strand_speed, app.moving_mass(0.5)))
        sim.probe = None
        r = eb.result()
        a = np.array(rows)
        v, M = float(a[:, 1].mean()), float(a[:, 2].mean())
        base = app.open_drive - rig_exit_tension(
            v, lam, app.upper.force + 0.5 * app.cfg.bearing_drag * v)
        loss = r.total * lam * r.v ** 3 / v
        out.append(OpenWindow(t, t1, v, M, r, float(np.polyfit(a[:, 0], a[:, 1], 1)[0]),
                              base / M, (base - loss) / M))
        t = t1
    return out
