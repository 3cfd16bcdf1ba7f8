"""A step in the upper cart's force, measured against the energy balance.

The ``floor`` variant of the apparatus runs to ``t_switch``; then the upper cart's mass
is changed live and the run is compared with an unswitched one over ``window`` s
(``docs/apparatus.md``). Tensions come from the solver's pivot
impulses: on the grooved upper plate they are the strand tension itself (the grooves add
no horizontal force), at the fountain start they are the joint forces' size.

The prediction is :func:`chainfountain.theory.apparatus.cart_step_speed`: the strand
between the pick-up and the fountain start (the chain in flight does not take part) with
the roller unit referred to the chain speed, the cart force passed on with ``gain`` and
the pick-up's own speed dependence (the rig law, :func:`pickup_rig_2cm_drag`) as ``drag``.
"""

from __future__ import annotations

import copy
import dataclasses
from dataclasses import dataclass

import numpy as np

from chainfountain.sim.apparatus import pickup_rig_2cm_drag
from chainfountain.sim.config import SimConfig
from chainfountain.sim.measure import ChainState
from chainfountain.sim.world import Simulation
from chainfountain.theory.apparatus import cart_step_speed, referred_mass


def upstream_mass(st: ChainState, link_mass: float, v_min: float = 1.0) -> tuple[float, int]:
    """Mass (kg) of the links upstream of the fountain start (the origin) moving faster
    than ``v_min`` (the strand the pick-up drives along its fixed path), and the index of
    the link nearest the start."""
    i0 = int(np.argmin(np.hypot(st.position[:, 0], st.position[:, 1])))
    speed = np.hypot(st.velocity[i0 + 1:, 0], st.velocity[i0 + 1:, 1])
    return float(np.count_nonzero(speed > v_min)) * link_mass, i0


@dataclass
class CartStepRun:
    """One run: samples after ``t_switch`` (N, m/s, s) and the masses at the switch."""

    t: np.ndarray
    v: np.ndarray
    """Strand speed (mean of the links in the plate grooves)."""
    T_exit: np.ndarray
    """Pick-up exit tension: pivots of the grooved links 2-5 from the roller."""
    T_launch: np.ndarray
    """Launch tension: pivots of the 4 joints nearest the fountain start."""
    M_up: np.ndarray
    """:func:`upstream_mass` at each sample (kg)."""
    dF: float
    """Change of the upper cart's force at the switch (N)."""
    m_carriage: float
    m_roller: float


def run(cfg: SimConfig, mass: float | None, t_switch: float, window: float,
        every: int = 2, seed: int = 0) -> CartStepRun:
    """Run ``cfg`` to ``t_switch``, set ``carts[0].mass`` to ``mass`` (``None``: leave it)
    and sample every ``every`` steps for ``window`` s. ``seed > 0`` nudges the start
    (:meth:`Simulation.nudge`)."""
    a = cfg.apparatus
    if cfg.kind != "apparatus" or a is None or a.variant != "floor" or a.plate != "groove":
        raise ValueError("a cart step needs an apparatus level with variant = 'floor' and "
                         "plate = 'groove'")
    if not cfg.carts:
        raise ValueError("a cart step needs an upper cart ([[carts]])")
    sim = Simulation(copy.deepcopy(cfg))  # a live cart change must not reach the caller's cfg
    if seed:
        sim.nudge(seed)
    app = sim.apparatus
    sim.advance(t_switch)
    F0 = app.upper.force
    if mass is not None:
        sim.set_param("carts[0].mass", mass)
    dt, h, links = sim.dt, sim.h, sim.chain.links  # joint impulses are per pymunk step h
    t, v, T_exit, T_launch, M_up = [], [], [], [], []
    for k in range(int(round(window / dt))):
        sim.step()
        if (k + 1) % every:
            continue
        g = app.plate_grooves  # the newest, at the roller, last
        m_up, i0 = upstream_mass(sim.state(), sim.chain.mass)
        M_up.append(m_up)
        t.append(sim.time - t_switch)
        v.append(app.strand_speed)
        T_exit.append(np.mean([abs(g[-i][0].up_joint.impulse) for i in range(3, 7)]) / h)
        T_launch.append(np.mean([abs(links[i].up_joint.impulse)
                                 for i in range(i0 - 3, i0 + 1)]) / h)
    return CartStepRun(t=np.array(t), v=np.array(v), T_exit=np.array(T_exit),
                       T_launch=np.array(T_launch), M_up=np.array(M_up),
                       dF=app.upper.force - F0,
                       m_carriage=app.upper.carriage.mass, m_roller=a.roller_mass)


@dataclass
class CartStep:
    """A switched run against an unswitched one."""

    base: CartStepRun
    step: CartStepRun
    lam: float

    @property
    def t(self) -> np.ndarray:
        return self.step.t

    @property
    def dv(self) -> np.ndarray:
        """Speed difference, switched minus unswitched (m/s)."""
        return self.step.v - self.base.v

    @property
    def dF(self) -> float:
        return self.step.dF

    @property
    def m_up(self) -> float:
        """Mean upstream moving mass over the window (kg)."""
        return float(np.mean(self.step.M_up))

    @property
    def mass(self) -> float:
        """Referred mass of the strand and roller unit (kg; :func:`referred_mass`)."""
        s = self.step
        return referred_mass(self.m_up, s.m_carriage, s.m_roller)

    @property
    def drag(self) -> float:
        """:func:`pickup_rig_2cm_drag` at the speed at the switch (N s/m)."""
        return pickup_rig_2cm_drag(float(self.base.v[0]), self.lam)

    @property
    def deceleration(self) -> float:
        """Slope of :attr:`dv` over the window (m/s^2; a straight-line fit)."""
        return float(np.polyfit(self.t, self.dv, 1)[0])

    @property
    def dT_exit(self) -> float:
        return float(np.mean(self.step.T_exit - self.base.T_exit))

    @property
    def dT_launch(self) -> float:
        return float(np.mean(self.step.T_launch - self.base.T_launch))

    @property
    def closure_mass(self) -> float:
        """``(Delta T_launch - Delta T_exit) / Delta a`` (kg): the mass the two tensions
        decelerate; :attr:`m_up` if the strand obeys its momentum balance."""
        return (self.dT_launch - self.dT_exit) / self.deceleration

    @property
    def pickup_gain(self) -> float:
        """Exit tension's rise over ``Delta F``, less the pick-up's speed dependence and
        the roller unit's inertia (energy balance of a rolling pulley: 1/2)."""
        m_unit = self.mass - self.m_up
        return (self.dT_exit - self.drag * float(np.mean(self.dv))
                - m_unit * self.deceleration) / self.dF

    def until(self, window: float) -> CartStep:
        """The same pair over its first ``window`` s."""
        def cut(r: CartStepRun) -> CartStepRun:
            m = r.t <= window + 1e-9
            return dataclasses.replace(r, t=r.t[m], v=r.v[m], T_exit=r.T_exit[m],
                                       T_launch=r.T_launch[m], M_up=r.M_up[m])
        return CartStep(base=cut(self.base), step=cut(self.step), lam=self.lam)

    def predicted(self, gain: float = 0.5, drag: bool = True) -> np.ndarray:
        """:func:`cart_step_speed` on :attr:`t` (m/s)."""
        return cart_step_speed(self.t, self.dF, self.mass, gain=gain,
                               drag=self.drag if drag else 0.0)

    def ratio(self, gain: float = 0.5, drag: bool = True) -> float:
        """Measured over predicted slope across the window."""
        return self.deceleration / float(np.polyfit(self.t, self.predicted(gain, drag), 1)[0])


def cart_step(cfg: SimConfig, mass: float, t_switch: float = 1.0, window: float = 0.6,
              every: int = 2, seed: int = 0) -> CartStep:
    """Run ``cfg`` twice, with the upper cart switched to ``mass`` at ``t_switch`` and
    without, and compare them over ``window`` s (both runs from the same start, nudged by
    ``seed`` if it is not 0)."""
    base = run(cfg, None, t_switch, window, every, seed)
    step = run(cfg, mass, t_switch, window, every, seed)
    return CartStep(base=base, step=step, lam=cfg.chain.linear_density)
