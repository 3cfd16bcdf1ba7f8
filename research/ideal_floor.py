"""Prototype: the paper's idealized beaker with a real floor, the speed selected by the carts.

The paper's floor arrangement (section "Idealized beaker, real floor"): the chain is picked
up from rest at the loss-free rate (tension ``lambda v^2/2``), lifted ``xi2*H`` through a
loss-free guide and held back by a cart (force ``F_uc``); it lands on a floor that takes
it without end tension. The tension it arrives with at the start of the fountain is then
``T0 = lambda v^2/2 + F_uc + lambda g xi2 H``, and the fountain needs ``T0 = lambda g H``
(``Tbar_0 = k H`` with ``Tbar_E = 0``), which selects

    v^2 = 2 g (H (1 - xi2) - F_uc/(lambda g)).

Here the guide of a fed level becomes a *piston*: its links are dynamic bodies held on the
launch line by groove joints (no rotation), jointed to each other and to the fountain, so
the solver itself finds the tension at the launch point. The machine's law acts on them as
an external force ``-(lambda v^2/2 + F_uc + lambda g xi2 H)`` along the line (their own
weight cancelled: the law carries the lift), with the cart's and the upstream strand's
inertia ``M`` shared among them. A front guide link whose centre passes the launch point
is released into the fountain; a new one joins at the back.

Usage::

    python research/ideal_floor.py                       # H 1 m, xi2 0.3, no cart, from 3.5 m/s
    python research/ideal_floor.py --xi2 0.5 --cart 0.05 --v0 4 --seconds 20
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np
import pymunk


def build(H: float, alpha0: float, v0: float, L: float, lam: float):
    from chainfountain.sim import SimConfig, Simulation

    cfg = SimConfig()
    cfg.feed.drop, cfg.feed.speed, cfg.feed.launch_angle = H, v0, alpha0
    cfg.chain.link_length, cfg.chain.linear_density = L, lam
    cfg.feed.guide_links = 4
    cfg.initial.mode = "catenary"  # a formed fountain at v0: its weight drives the machine
    cfg.solver.wave_damping = 0.0  # no rotary dampers: the guide links cannot turn
    return Simulation(cfg)


class Piston:
    """Turns a fed level's kinematic guide into the idealized floor machine's piston."""

    def __init__(self, sim, xi2: float, F_uc: float, M: float) -> None:
        self.sim, self.xi2, self.F_uc, self.M = sim, xi2, F_uc, M
        feed, chain = sim.feed, sim.chain
        self.u = feed.u
        self.n_nominal = feed.n_guide
        self.grooves: dict[int, pymunk.GrooveJoint] = {}
        n = len(chain.links)
        for i in range(n - feed.n_guide, n):
            self._to_piston(chain.links[i])
        for i in range(n - feed.n_guide, n - 1):
            chain.join(i)
        feed.before_step = self.before_step
        feed.after_step = self.after_step

    def _to_piston(self, link) -> None:
        chain = self.sim.chain
        if link.body.body_type != pymunk.Body.DYNAMIC:
            chain.make_dynamic(link)
        b = link.body
        b.mass = chain.mass + self.M / self.n_nominal
        b.moment = float("inf")
        b.angular_velocity = 0.0
        ux, uy = self.u
        g = pymunk.GrooveJoint(self.sim.space.static_body, b, (-100 * ux, -100 * uy),
                               (100 * ux, 100 * uy), (0.0, 0.0))
        g.error_bias = self.sim.config.solver.joint_error_bias
        self.sim.space.add(g)
        self.grooves[link.id] = g

    def speed(self) -> float:
        b = self.sim.chain.links[-1].body
        return float(b.velocity.dot(self.u))

    def before_step(self) -> None:
        sim, chain = self.sim, self.sim.chain
        lam, g = chain.cfg.linear_density, sim.g
        v = self.speed()
        F = -(0.5 * lam * v * v + self.F_uc + lam * g * self.xi2 * sim.feed.cfg.drop)
        ux, uy = self.u
        guide = chain.links[len(chain.links) - sim.feed.n_guide:]
        for link in guide:  # the law carries the lift: cancel the guide links' weight
            b = link.body
            b.apply_force_at_world_point((0.0, b.mass * g), b.position)
        rear = guide[-1].body
        rear.apply_force_at_world_point((F * ux, F * uy), rear.position)

    def after_step(self, dt: float) -> None:
        chain, feed = self.sim.chain, self.sim.feed
        L = chain.L
        ux, uy = self.u
        v = self.speed()
        feed.cfg.speed = v
        n = len(chain.links)
        front = chain.links[n - feed.n_guide]
        if front.body.position.dot(self.u) >= 0.0:  # centre past the launch point: release
            self.sim.space.remove(self.grooves.pop(front.id))
            b = front.body
            b.mass, b.moment = chain.mass, chain.moment
            b.angular_velocity = feed.launch_omega
            feed.n_guide -= 1
            rear = chain.links[-1]
            s = rear.body.position.dot(self.u) - L
            new = chain.make_body((s * ux, s * uy), feed.cfg.launch_angle,
                                  velocity=(v * ux, v * uy))
            chain.append(new)
            self._to_piston(new)
            feed.n_guide += 1
            feed.fed_links += 1
        feed._absorb()


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--H", type=float, default=1.0)
    ap.add_argument("--xi2", type=float, default=0.3)
    ap.add_argument("--cart", type=float, default=0.0, help="F_uc (N)")
    ap.add_argument("--mass", type=float, default=0.05, help="M, cart + upstream strand (kg)")
    ap.add_argument("--v0", type=float, default=3.5)
    ap.add_argument("--angle", type=float, default=60.0, help="launch angle (deg)")
    ap.add_argument("--seconds", type=float, default=15.0)
    a = ap.parse_args(argv)
    lam, g, L = 0.05, 9.81, 0.02
    v_pred = math.sqrt(2 * g * (a.H * (1 - a.xi2) - a.cart / (lam * g)))
    sim = build(a.H, math.radians(a.angle), a.v0, L, lam)
    piston = Piston(sim, a.xi2, a.cart, a.mass)
    print(f"predicted v = {v_pred:.4f} m/s")
    vs, ts = [], []
    while sim.time < a.seconds:
        sim.advance(0.05)
        vs.append(piston.speed())
        ts.append(sim.time)
        if abs(sim.time * 10 - round(sim.time * 10)) < 1e-6:
            print(f"t = {sim.time:5.2f} s  v = {vs[-1]:.4f} ({vs[-1] / v_pred - 1:+.2%})  "
                  f"free links {sim.n_free}", flush=True)
    vs, ts = np.array(vs), np.array(ts)
    late = ts >= a.seconds / 2
    print(f"mean speed over the second half {vs[late].mean():.4f} m/s "
          f"({vs[late].mean() / v_pred - 1:+.2%} against the paper), sd {vs[late].std():.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
