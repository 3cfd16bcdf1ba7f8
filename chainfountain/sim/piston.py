"""The paper's idealized beaker with a real floor as a guide the chain itself moves.

With ``feed.drive = "ideal_floor"`` a fed level's guide is a *piston*: its links are
dynamic bodies held on the launch line by groove joints (they cannot turn), jointed to
each other and to the fountain, so the solver finds the tension at the launch point. The
machine's law acts on them as an external force along the line,

    -(lambda v^2/2 + F_uc + lambda g xi2 H),

the loss-free pick-up from rest, the upper cart and the lift to the start (paper, section
"Idealized beaker, real floor"; their own weight is cancelled: the law carries the lift),
with the cart's and upstream strand's inertia (``feed.machine_mass``) shared among them.
The fountain's ``Tbar_0 = k H`` then selects ``v^2 = 2 g (H (1 - xi2) - F_uc/(lambda g))``
(:func:`chainfountain.theory.apparatus.ideal_floor_speed`). A guide link whose centre
passes the launch point is released into the fountain; a new one joins at the back.
"""

from __future__ import annotations

import math
from typing import Any

import pymunk

from chainfountain.errors import RunEnded
from chainfountain.sim.apparatus.stall_watch import STALL_FRACTION, STALL_TIME, ChainStalled
from chainfountain.sim.chain import Link
from chainfountain.sim.feed import Feed

RUNAWAY_FACTOR = 2.5
"""The chain counts as running away above this multiple of its start speed, for
:data:`~chainfountain.sim.apparatus.stall_watch.STALL_TIME` without a break (it counts as
stopping below ``STALL_FRACTION`` of it, as in the contact machine)."""

GROOVE_REACH = 100.0
"""Half-length of the guide's groove along the launch line (m): far beyond any guide."""


class Piston:
    """Turns the fed level's kinematic guide of ``sim`` into the ideal machine's piston."""

    def __init__(self, sim: Any, feed: Feed, tail: Any = None) -> None:
        """``sim``: the :class:`~chainfountain.sim.world.Simulation` being built, ``feed``
        its laid-out :class:`~chainfountain.sim.feed.Feed` (the piston drives the guide
        and keeps the feed's floor: it is the level's :class:`~chainfountain.sim.ends.Ends`);
        ``tail``: the open arrangement's
        :class:`~chainfountain.sim.slide_away.SlideAway`, told after each step how many
        links the floor has taken."""
        self.sim = sim
        self.feed = feed
        chain = sim.chain
        self.u = feed.u
        self.n_nominal = feed.n_guide
        self.grooves: dict[int, pymunk.GrooveJoint] = {}
        self.v_start = float(feed.cfg.speed)
        """The speed the run started at (the stall and runaway checks' scale)."""
        self._off_t = 0.0
        self.starting = float(feed.cfg.starter) > 0.0
        """True while the starter runs the guide as a motor (``feed.starter``)."""
        self.carried = 0.0
        """Mass (kg) the piston moves besides the machine's own (``feed.machine_mass``):
        the open arrangement's chain sliding on its plate (:meth:`carry`)."""
        self.tail = tail
        self._hand_over: float | None = None
        n = len(chain.links)
        for i in range(n - feed.n_guide, n):
            self._hold(chain.links[i])
        for i in range(n - feed.n_guide, n - 1):
            chain.join(i)  # no spring: neither link can turn (Chain refits none)

    def _hold(self, link: Link) -> None:
        """Make ``link`` a piston link: dynamic, on the groove, unable to turn."""
        chain, cfg = self.sim.chain, self.sim.config
        if link.body.body_type != pymunk.Body.DYNAMIC:
            chain.make_dynamic(link)
        b = link.body
        b.mass = self._link_mass()
        b.moment = float("inf")
        b.angular_velocity = 0.0
        ux, uy = self.u
        groove = pymunk.GrooveJoint(self.sim.space.static_body, b,
                                    (-GROOVE_REACH * ux, -GROOVE_REACH * uy),
                                    (GROOVE_REACH * ux, GROOVE_REACH * uy), (0.0, 0.0))
        groove.error_bias = cfg.solver.joint_error_bias
        self.sim.space.add(groove)
        self.grooves[link.id] = groove

    @property
    def hand_over(self) -> float:
        """Time (s) from which the machine's laws drive the chain: 0 without a starter,
        ``inf`` while the starter still runs."""
        if not float(self.sim.config.feed.starter) > 0.0:
            return 0.0
        if self.starting or self._hand_over is None:
            return math.inf
        return self._hand_over

    def _link_mass(self) -> float:
        """A piston link's mass: its own and its share of the machine's inertia."""
        m = self.sim.config.feed.machine_mass + self.carried
        return self.sim.chain.mass + m / self.n_nominal

    def carry(self, mass: float) -> None:
        """Move ``mass`` (kg) more with the chain from now on, at its present speed (the
        piston links' velocities stay, so the speed and the energy the mass had stay)."""
        self.carried += float(mass)
        m = self._link_mass()
        for link in self.held_links():
            link.body.mass = m

    def held_links(self) -> list[Link]:
        """The piston's links (those held on the launch line)."""
        chain = self.sim.chain
        return chain.links[len(chain.links) - self.feed.n_guide:]

    @property
    def chain_speed(self) -> float:
        """The chain's speed in the guide (m/s), measured now."""
        return float(self.sim.chain.links[-1].body.velocity.dot(self.u))

    # ------------------------------------------------------------------ the ends
    @property
    def speed(self) -> float:
        """The chain's speed (m/s) at the end of the last step (the feed's)."""
        return self.feed.speed

    @property
    def n_free(self) -> int:
        return self.feed.n_free

    @property
    def absorbed(self) -> int:
        return self.feed.absorbed

    @property
    def floor_y(self) -> float:
        return self.feed.floor_y

    @property
    def end_force(self) -> tuple[float, float] | None:
        """The floor's pull on the end link in the last step (the feed's)."""
        return self.feed.end_force

    def law_force(self, v: float) -> float:
        """The machine's pull back on the chain at speed ``v`` (N, along the launch line)."""
        f = self.sim.config.feed
        lam = self.sim.chain.cfg.linear_density
        drag = 0.5 * f.bearing_drag * v  # the pick-up roller's bearing (drive 'ideal_fold')
        return 0.5 * lam * v * v + f.cart_force + drag + lam * self.sim.g * f.xi2 * f.drop

    def set_speed(self, v: float) -> None:
        """Push the chain to ``v`` (m/s): every link's velocity and turning rate scale by
        ``v`` over the present speed (the whole chain speeds up along itself, as a push
        on the machine does); the machine then settles back to its own speed."""
        now = self.chain_speed
        if now <= 0.0 or v <= 0.0:
            return
        f = v / now
        for link in self.sim.chain.links:
            b = link.body
            b.velocity = (f * b.velocity.x, f * b.velocity.y)
            b.angular_velocity = f * b.angular_velocity
        self.feed.cfg.speed = float(v)

    def before_step(self) -> None:
        chain, g = self.sim.chain, self.sim.g
        guide = chain.links[len(chain.links) - self.feed.n_guide:]
        if self.starting:  # the starter: a motor at the start speed
            vx, vy = self.v_start * self.u[0], self.v_start * self.u[1]
            for link in guide:
                link.body.velocity = (vx, vy)
            self.feed.before_step()
            return
        for link in guide:  # the law carries the lift: cancel the guide links' weight
            b = link.body
            b.apply_force_at_world_point((0.0, b.mass * g), b.position)
        F = -self.law_force(self.chain_speed)
        ux, uy = self.u
        rear = guide[-1].body
        rear.apply_force_at_world_point((F * ux, F * uy), rear.position)
        self.feed.before_step()

    def after_step(self, dt: float) -> None:
        chain, feed = self.sim.chain, self.feed
        L = chain.L
        ux, uy = self.u
        v = self.chain_speed
        feed.cfg.speed = v
        front = chain.links[len(chain.links) - feed.n_guide]
        if front.body.position.dot(self.u) >= 0.0:  # centre past the launch point: release
            self.sim.space.remove(self.grooves.pop(front.id))
            b = front.body
            b.mass, b.moment = chain.mass, chain.moment
            b.angular_velocity = feed.launch_omega
            feed.n_guide -= 1
            i = len(chain.links) - feed.n_guide - 1
            chain.refit_spring(i - 1)  # the fountain's last joint
            chain.refit_spring(i)  # the released link to the next piston link
            s = chain.links[-1].body.position.dot(self.u) - L
            new = chain.make_body((s * ux, s * uy), feed.cfg.launch_angle,
                                  velocity=(v * ux, v * uy))
            chain.append(new)
            self._hold(new)
            chain.refit_spring(len(chain.links) - 2)  # none between two piston links
            feed.n_guide += 1
            feed.fed_links += 1
        if feed.cfg.floor == "absorbing":
            feed._absorb()
        if self.tail is not None:
            self.tail.landed(feed.absorbed)
        self._table(feed)
        if self.starting:
            self._start_up()
            return
        self.sim.follow_speed(v)
        self._watch(v, dt)

    def _table(self, feed: Any) -> None:
        """End the run once the upper table's chain (``feed.chain_length``, 0: endless;
        counted in links as the motor's feed counts it) has all been picked up."""
        most = feed._max_links()
        if most is not None and feed.fed_links >= most:
            raise RunEnded(f"t = {self.sim.time:.2f} s: the upper table is empty: all "
                           f"{feed.cfg.chain_length:g} m of chain has been picked up, so the "
                           "machine stops here; a longer run needs a larger "
                           "feed.chain_length (0: an endless table)")

    def _start_up(self) -> None:
        """Hand the chain to the machine's laws ``feed.starter`` seconds after it landed."""
        sim = self.sim
        if self._hand_over is None and self.feed.absorbed > 0:
            self._hand_over = sim.time + float(sim.config.feed.starter)
        if self._hand_over is not None and sim.time >= self._hand_over:
            self.starting = False

    def _watch(self, v: float, dt: float) -> None:
        """End the run with one sentence when the chain stops or runs away (an unbalanced
        full machine does either: it is neutral in the speed)."""
        slow, fast = v < STALL_FRACTION * self.v_start, v > RUNAWAY_FACTOR * self.v_start
        self._off_t = self._off_t + dt if slow or fast else 0.0
        if self._off_t < STALL_TIME:
            return
        f, t = self.sim.config.feed, self.sim.time
        if slow:
            raise ChainStalled(f"t = {t:.2f} s: the chain has stopped: the upper cart "
                               f"({f.cart_force:.3g} N) and the lift xi2*H hold it back "
                               "harder than the falling chain pulls it on; make the upper "
                               "cart lighter (feed.cart_force) or lower xi2")
        raise RunEnded(f"t = {t:.2f} s: the chain runs away ({v:.3g} m/s, "
                       f"{v / self.v_start:.2g} times its start speed): the upper cart "
                       f"({f.cart_force:.3g} N) is too light to balance the lower half; "
                       "change xi2, xi3 or the lower cart to let it follow, or make it heavier")
