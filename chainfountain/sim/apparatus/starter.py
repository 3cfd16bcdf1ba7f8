"""Starting the machine from rest (``initial.mode = "stub"``, ``apparatus.starter > 0``).

A real chain-fountain machine is started by hand: at rest its carts hold the chain and
nothing falls. The starter is that hand, a motor in the upper joint guide: it runs the
links held there along the guide, from rest up to ``apparatus.speed`` over
:data:`RAMP` s, and holds that speed until the chain has landed and ``apparatus.starter``
seconds after. Then it lets go, and the carts and the fall alone drive the chain, which
settles at the speed the machine selects. A study's own start subclasses
:class:`Starter` and passes the class to :class:`~chainfountain.sim.apparatus.Apparatus`
(``research/hanging_start.py``).

'fold' (the gripped folding roller, :mod:`.grip`) has no floor to land on: the chain's
head must be threaded through the end guide and round the folding roller. Its head waits
:data:`~.core.HEAD_BACK` inside the upper guide; the starter runs it up within
:data:`THREAD_RAMP` to :attr:`Starter.launch_speed`, at which a free head flies onto
the predicted fountain end (faster, it would fly past the end guide: a free end carries no
tension, so it does not follow the fountain's curve). Once the end guide has caught the
head, the starter runs the chain up to ``apparatus.speed`` within :data:`CATCH_RAMP` (below
the paper's ``v(k_max)`` the fountain cannot stand, and it falls) and runs the links in the
end guide and the folding roller at that speed too, so that the head is carried round
the roller and pinned to the table. The end guide does not follow the landing while the
starter runs: with both ends driven the fountain's length is fixed, and moving the guide
would stretch it. ``apparatus.starter`` seconds after the first link is laid on the lower
table, or sooner once the fountain lands where the end guide is (:data:`HOME`), the starter
lets go, gradually (:data:`FADE`): its hold on both roller carriages fades out over 3 s.
"""

from __future__ import annotations

import math

from chainfountain.errors import RunEnded
from chainfountain.sim import fastbody
from chainfountain.sim.apparatus.ends import EndPart
from chainfountain.sim.apparatus.fold import FoldPart
from chainfountain.sim.apparatus.follow import FollowingEnd
from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.parts import Clock, RollerUnit
from chainfountain.sim.apparatus.upper_guide import UpperJointGuide

RAMP = 0.5
"""Time (s) over which the starter runs the chain up from rest to ``apparatus.speed``."""
THREAD_RAMP = 0.05
"""'fold': time (s) over which the starter runs the chain up from rest to the head's
launch speed (short: a slow head droops out of the guide instead of flying)."""
CATCH_RAMP = 0.2
"""'fold': time (s) over which the starter runs the chain up from the launch speed to
``apparatus.speed`` once the end guide has caught the head."""
STORE = 1.12
"""'fold': the least chain the starter keeps in flight, over the predicted fountain's
length, while it threads the head round the folding roller. With both ends driven at
one speed a fountain of about its own length falls: in ``apparatus_fold_gripped`` with
``apparatus.drop`` 0.55 m (a slower launch) it was caught with 1.07 times its length and
fell within 0.8 s, where the shipped drop of 0.5 m is caught with 1.10-1.15 times it and
stands. Below this the end guide's drive runs slower than the upper guide's until it is
in flight (:meth:`Starter.end_speed`). Holding an upper bound too (1.15-1.25) lost
starts that hold without one."""
STORE_GAIN = 3.0
"""'fold': how fast (per unit of the relative shortfall) the end guide's drive slows to
store chain: the shortfall closes with a time constant of ``length/(v*gain)``, about
0.1 s."""
HOME = 0.01
"""'fold': the starter lets go early once the fountain lands within this (m) of the end
guide's first turn (:meth:`Starter._landed_home`). It first lands long (the launch
stores more chain than the machine's fountain holds), and while both ends are driven two
drives set to one speed differ a little, so its length drifts; at about the machine's own
length a driven fountain falls (measured at a quarter of a millisecond: 44 links in
flight), while the machine, let go, holds it."""
SETTLE = 1.0
"""'fold': the least time (s) the starter drives on after the first link is laid."""
FADE = 3.0
"""'fold': time (s) over which the starter's hold on the roller carriages fades out after
it lets go (a sudden release leaves some starts swinging slowly, 3 % below the speed
the machine selects, for tens of seconds; docs/apparatus.md)."""
FADE_RATE = 40.0
"""'fold': the rate (1/s) at which the fading starter brings each roller carriage toward
half ``apparatus.speed`` when it lets go, falling linearly to 0 over :data:`FADE`."""
LAND_WITHIN = 10.0
"""Time (s) by which a started chain must have reached the floor (it takes about 1 s)."""


def run_along(guide: list, queues: list, v: float) -> None:
    """Set the links held in a joint guide (``guide``'s elements, ``queues`` their held
    ``(link, joint)`` pairs) moving along it at ``v``: along a straight's line, on a bend
    along its tangent. (Before every pymunk step while the starter runs, over every held
    link: it reads and writes through :mod:`~chainfountain.sim.fastbody`.)"""
    get_p, set_v, handle = fastbody.get_position, fastbody.set_velocity, fastbody.handle
    for el, q in zip(guide, queues, strict=True):
        if el.form == "line":
            (ax, ay), (bx, by) = el.a, el.b
            ln = math.hypot(bx - ax, by - ay)
            vel = (v * (bx - ax) / ln, v * (by - ay) / ln)
            for link, _ in q:
                set_v(handle(link.body), vel)
            continue
        cx, cy = el.a
        turn = 1.0 if el.ccw else -1.0
        for _, j in q:  # an arc's joint caches the held body's handle (guide.ArcJoint)
            h = j.handle
            p = get_p(h)
            dx, dy = p.x - cx, p.y - cy
            d = math.hypot(dx, dy) or 1.0
            set_v(h, (-turn * v * dy / d, turn * v * dx / d))


class StarterFailed(RunEnded):
    """The starter could not run the chain up to the floor (raised by
    :meth:`Starter.check`)."""


class Starter:
    """The starter motor: it drives the links in the upper joint guide (and in 'fold'
    the end guide and the folding roller) while :attr:`starting`, then lets go."""

    def __init__(self, layout: Layout, clock: Clock, upper: RollerUnit,
                 upper_guide: UpperJointGuide | None, end: EndPart, fold: FoldPart | None,
                 follow: FollowingEnd) -> None:
        self.layout = layout
        self.cfg = layout.cfg
        self.clock = clock
        self.upper = upper
        self.upper_guide = upper_guide
        self.end = end
        self.fold = fold
        """The fold whose end guide and roller the starter drives ('fold' only)."""
        self.lower = fold.lower if fold is not None else None
        self.follow = follow
        self._store = STORE * layout.fountain.length if layout.fold_guided else math.nan
        """'fold': the least chain (m) kept in flight while threading (:data:`STORE`)."""
        self.starting = layout.from_rest
        """True while the starter drives the chain."""
        self.fading = False
        """'fold': True while the starter's hold fades after it let go (:meth:`fade`)."""
        self._caught_t: float | None = None
        """'fold': when the end guide caught the head (s)."""
        self._laid_t = math.inf
        """When the first link was laid on the floor or the lower table (s)."""
        self._hand_over: float | None = None
        """When the starter lets go (s): set once the first link reaches the floor, and
        to the moment it does let go (:meth:`fade` counts from it)."""

    @property
    def speed(self) -> float:
        """The speed (m/s) the starter runs the chain at now. 'fold': first the speed
        :attr:`launch_speed` at which the free head flies onto the end guide's mouth,
        reached within :data:`THREAD_RAMP`, and once the end guide has caught the head
        ``apparatus.speed``, reached within :data:`CATCH_RAMP`."""
        v = float(self.cfg.speed)
        t = self.clock.t
        if not self.layout.fold_guided:
            return v * min(1.0, t / RAMP)
        v1 = self.launch_speed
        if self._caught_t is None:
            return v1 * min(1.0, t / THREAD_RAMP)
        return v1 + (v - v1) * min(1.0, (t - self._caught_t) / CATCH_RAMP)

    @property
    def head_caught_at(self) -> float:
        """'fold' from rest: when the end guide caught the chain's head (s; nan before)."""
        return math.nan if self._caught_t is None else self._caught_t

    @property
    def launch_speed(self) -> float:
        """'fold' from rest: the speed (m/s) at which a free head leaving the upper guide
        at ``launch_angle`` flies onto the predicted fountain end ``(x_E, -H)``:
        ``v^2 = g x_E^2 / (2 cos^2(alpha0) (x_E tan(alpha0) + H))`` (a projectile; the
        chain behind a free head pulls on it little)."""
        lay = self.layout
        xe, a = self.end.end[0] - self.follow.end_shift, lay.alpha0
        return math.sqrt(lay.g * xe * xe
                         / (2.0 * math.cos(a) ** 2 * (xe * math.tan(a) + lay.H)))

    def before_step(self) -> None:
        """Before each pymunk step: drive while starting, fade once let go."""
        if self.starting:
            self.drive()
        elif self.fading:
            self.fade()

    def drive(self) -> None:
        """Set the links held in the upper guide moving along it at :attr:`speed` (before
        each step; the solver passes the pull on): along a straight's line, on a bend
        along its tangent. (The last straight alone holds one link when the rise
        ``xi2*H`` is short, too little to pull the chain.)"""
        fold = self.fold
        if (self.layout.fold_guided and fold is not None and self._caught_t is None
                and fold.mouth_t is not None):
            self._caught_t = self.clock.t  # the end guide has caught the head
        v = self.speed
        if self.upper_guide is not None:
            run_along(self.upper_guide.elements, self.upper_guide.held, v)
        if self.layout.fold_guided:  # 'fold': the head threads through the end guide
            self._drive_fold(v)

    def _drive_fold(self, v: float) -> None:
        """'fold' from rest: the end guide's starter runs the links it holds along it at
        ``v``, and the folding roller rolls at ``v/2`` on its table (its top at ``v``), so
        that the fountain's head, caught at the mouth, is carried to the roller and round
        it onto the table."""
        fold = self.fold
        assert fold is not None
        v = self.end_speed(v)
        run_along(fold.guide, fold.held, v)
        lo = fold.lower
        u = 0.5 * v
        lo.carriage.velocity = (u, 0.0)
        lo.roller.velocity = (u, 0.0)
        lo.roller.angular_velocity = -u / self.layout.R_lo

    def end_speed(self, v: float) -> float:
        """'fold' from rest: the speed of the end guide's drive (and twice the folding
        roller's) when the upper guide runs at ``v``. From the catch until the first link
        is laid on the lower table it runs slower while less than :data:`STORE` times the
        predicted fountain's length is in flight, by :data:`STORE_GAIN` times the
        relative shortfall (at most half ``v``), so that a narrow fountain starts with
        the excess the shipped one has; otherwise at ``v``."""
        fold = self.fold
        if self._caught_t is None or fold is None or self._laid_t < math.inf:
            return v
        want = self._store
        have = (fold.fly_next - fold.cap_next + 1) * self.layout.L
        return v * max(0.5, 1.0 - STORE_GAIN * max(0.0, (want - have) / want))

    def fade(self) -> None:
        """'fold', for :data:`FADE` s after the starter lets go (before each pymunk step):
        bring each roller carriage's speed toward half ``apparatus.speed`` at a rate that
        falls from :data:`FADE_RATE` to 0, so that the carts and the brake take the
        machine over gradually."""
        assert self._hand_over is not None and self.lower is not None
        t = self.clock.t - self._hand_over
        if t >= FADE:
            self.fading = False
            return
        k = 1.0 - math.exp(-FADE_RATE * (1.0 - t / FADE) * self.layout.h)
        u_s = 0.5 * float(self.cfg.speed)
        for body in (self.upper.carriage, self.lower.carriage):
            u, w = body.velocity
            body.velocity = (u + k * (u_s - u), w)

    def _landed_home(self) -> bool:
        """'fold': whether the fountain, its length drifting while both ends are driven,
        has come to land within :data:`HOME` of the end guide's first turn, at least
        :data:`SETTLE` after the first link was laid: the starter then lets go at once
        (a driven fountain shorter than that falls)."""
        return (self.layout.fold_guided and self.clock.t >= self._laid_t + SETTLE
                and self.follow.landing_offset > -HOME)

    def check(self, absorbed: int, chain_speed: float) -> None:
        """Let go :attr:`~chainfountain.sim.config.ApparatusConfig.starter` seconds after
        the first link has reached the floor (or the lower table; ``absorbed`` links have
        left the chain there); end the run with one sentence if the chain has not landed
        within :data:`LAND_WITHIN` s (the starter could not run it up, or could not thread
        it; the chain runs at ``chain_speed``)."""
        t = self.clock.t
        fold_guided = self.layout.fold_guided
        if self._hand_over is None and absorbed > 0:
            self._hand_over = t + float(self.cfg.starter)
            self._laid_t = t
        if self._hand_over is not None and (t >= self._hand_over or self._landed_home()):
            self._hand_over = min(self._hand_over, t)  # sooner if it landed home
            self.starting = False
            self.fading = fold_guided
        elif self._hand_over is None and t > LAND_WITHIN and fold_guided:
            where = ("the end guide has not caught its head" if self._caught_t is None
                     else "its head has not reached the lower table")
            raise StarterFailed(
                f"t = {t:.2f} s: the starter could not thread the chain through the "
                f"machine ({where} within {LAND_WITHIN:g} s): the carts hold it harder than "
                "the starter pulls, or the fountain misses the end guide; make the upper "
                "cart lighter (carts[0].mass), or start it laid along its path "
                "(initial.mode = 'catenary')",
                plain=f"At {t:.1f} s the starter had not threaded the chain through "
                "the machine; press R to try again, or make the upper cart lighter")
        elif self._hand_over is None and t > LAND_WITHIN:
            raise StarterFailed(
                f"t = {t:.2f} s: the starter could not run the chain up (it moves at "
                f"{chain_speed:.2g} m/s and has not reached the floor): the carts hold it "
                "harder than the starter pulls; make the upper cart lighter (carts[0].mass) "
                "or lift the chain less (a smaller apparatus.xi2)")
