"""The :class:`Simulation`: builds a level from a :class:`SimConfig` and steps it.

Frame: the launch point (guide exit) is the origin, ``y`` up, the chain moves
in ``+x``. The absorbing (or solid) floor is at ``y = -H``. Runs are
deterministic: the same config (including ``initial.seed``) gives the same
trajectory bit for bit.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Mapping
from typing import Any, Protocol

import numpy as np
import pymunk

from chainfountain.fields import set_value
from chainfountain.sim import live
from chainfountain.sim.apparatus import Apparatus
from chainfountain.sim.beaker import Beaker
from chainfountain.sim.bodies import Cart, Floor, Roller, nudge_bodies
from chainfountain.sim.chain import Chain
from chainfountain.sim.config import SimConfig
from chainfountain.sim.ends import Ends
from chainfountain.sim.feed import Feed
from chainfountain.sim.kinds import kind_of, limits_for
from chainfountain.sim.machine_rules import keeps_any_speed
from chainfountain.sim.measure import ChainReader, ChainState, link_ends, polyline
from chainfountain.sim.piston import Piston
from chainfountain.sim.reference import LaunchReference
from chainfountain.sim.slide_away import SlideAway
from chainfountain.sim.stiff_reference import (
    Prediction,
    Reference,
    StiffReference,
    predict,
    stiff_applies,
)
from chainfountain.sim.watchdog import CHECK_INTERVAL, Limits, Watchdog

FOLLOW_TOLERANCE = 1e-3
"""The ideal full machine's reference follows its speed in steps of this fraction."""


class Observer(Protocol):
    """What the simulation calls to record a step (:attr:`Simulation.recorder`;
    :class:`chainfountain.sim.recorder.Recorder` is one)."""

    def wants(self, step_index: int) -> bool:
        """Whether step number ``step_index`` (1-based) is to be sampled."""
        ...

    def take(self, pre: ChainState, post: ChainState,
             contacts: np.ndarray | None = None) -> None:
        """The chain before and after a sampled step (and its contact impulses)."""
        ...

    def clear(self) -> None:
        """Forget everything recorded (the simulation was rebuilt)."""
        ...


class Probe(Protocol):
    """Read-only measurement around a physics step (:attr:`Simulation.probe`)."""

    def before(self) -> None: ...

    def after(self) -> None: ...


class Simulation:
    """A running level (``kind = "feed"``).

    Attributes
    ----------
    config:
        The live configuration (live changes are written back into it, and
        :meth:`reset` rebuilds from it).
    space, chain, feed, floor, rollers, carts:
        The pymunk objects; read them, change them through the methods here.
    reference:
        The theory this feed is compared with: the paper's catenary
        (:class:`~chainfountain.sim.reference.LaunchReference`), or for a motor-fed chain
        with joint springs or dampers the steady stiff fountain
        (:class:`~chainfountain.sim.stiff_reference.StiffReference`). ``None`` for an
        apparatus level, for a configuration that has no fountain (``Tbar_E + k*H >= 1``),
        which the level check (:func:`chainfountain.level.io.check_consistency`) refuses,
        and for a stiff chain that has no steady fountain (:attr:`reference_note` says so).
    catenary:
        The paper's catenary for this feed, whichever theory :attr:`reference` is: the feed
        aims the floor's pull and spins the released links by it.
    time, steps:
        Simulated time (s) and number of physics steps since the last build.
    """

    def __init__(self, config: SimConfig, *,
                 builders: Mapping[str, Callable[..., Any]] | None = None,
                 defer_theory: bool = False) -> None:
        """``builders``: a study's own builders of a kind's parts by name, used instead of
        the kind's (``{"apparatus": functools.partial(Apparatus, tuning=...)}``), here and
        in every :meth:`reset`. ``defer_theory``: see :attr:`defer_theory` (the build too
        leaves a stiff chain's theory to :meth:`refresh_theory`)."""
        self.builders: dict[str, Callable[..., Any]] = dict(builders or {})
        self.kind = kind_of(config)
        """The level's :class:`~chainfountain.sim.kinds.base.Kind` (it builds the chain and
        its ends)."""
        if self.kind.build is None:
            raise ValueError(f"{config.name or 'this level'} is {self.kind.title} (kind "
                             f"{config.kind!r}): {config.kind}s run headless only, with "
                             f"chainfountain run {config.name or 'LEVEL'}")
        self.config = copy.deepcopy(config)
        self.recorder: Observer | None = None
        self.probe: Probe | None = None
        """Optional measurement called around each physics step (read only), e.g.
        :class:`chainfountain.sim.budget.EnergyBudget`."""
        self.defer_theory = defer_theory
        """When true, a build or a live change of the joints or the speed only marks a
        stiff chain's theory stale (:attr:`theory_stale`) and :meth:`refresh_theory` (or
        the window, in the background) solves it: a solve takes 0.05-0.5 s, and up to
        tens of seconds where there is no steady fountain; else it is solved at once."""
        self.theory_version = 0
        """Counts the references taken (the window redraws the theory when it moves)."""
        self.theory_changes = 0
        """Counts the changes that made the theory stale (a solve elsewhere is taken only
        when none came after it started)."""
        self._build()

    # ------------------------------------------------------------------ building
    def _build(self) -> None:
        cfg = self.config
        space = pymunk.Space()
        space.gravity = (0.0, -cfg.gravity)
        space.iterations = cfg.solver.iterations
        space.collision_slop = cfg.solver.collision_slop
        space.damping = 1.0
        self.space = space
        self._dt = float(cfg.solver.dt)
        self._substeps = int(cfg.solver.substeps)
        self._h = self._dt / self._substeps
        self._check_every = max(1, int(round(CHECK_INTERVAL / self._dt)))
        self.watchdog = Watchdog(space, self._limits())
        """Stops the run when it diverges (:mod:`chainfountain.sim.watchdog`)."""
        self.chain: Chain
        """The chain (every kind builds one)."""
        self.ends: Ends
        """What drives the chain's two ends (:class:`~chainfountain.sim.ends.Ends`): the
        feed, the ideal machine's piston, the apparatus or the beaker."""
        self.feed: Feed | None = None
        """A fed level's guide and floor (its motor's feed, or the feed an ideal machine's
        piston holds); ``None`` for other kinds."""
        self.apparatus: Apparatus | None = None
        self.piston: Piston | None = None
        self.slide_away: SlideAway | None = None
        """The open arrangement's lower half (``feed.drive = "ideal_open"``), else ``None``."""
        self.beaker: Beaker | None = None
        self.floor: Floor | None = None
        self.rollers: list[Roller] = []
        self.carts: list[Cart] = []
        self.reference: Reference | None = None
        """The theory a fed level is compared with (``None`` for an apparatus or a beaker;
        see the class docstring)."""
        self.catenary: LaunchReference | None = None
        """The paper's catenary for a fed level, whichever theory :attr:`reference` is."""
        self.reference_note = ""
        """Why :attr:`reference` is ``None`` for a fed level with a catenary ("no steady
        stiff fountain at c = ..., d = ..."), or ''."""
        self.theory_stale = False
        """The joints changed and the stiff theory waits for :meth:`refresh_theory`."""
        build = self.kind.build
        assert build is not None  # checked in __init__
        build(self)
        self._start()

    def _start(self) -> None:
        """Time back to zero, nothing held, the recorder emptied: the end of every build."""
        self.reader = ChainReader(self.space, self.chain)
        self.time = 0.0
        self.steps = 0
        self._mouse_body: pymunk.Body | None = None
        self._mouse_joint: pymunk.PivotJoint | None = None
        self._grabbed: int | None = None
        if self.recorder is not None:
            self.recorder.clear()

    def wave_damping_at(self, speed: float) -> float:
        """The numerical joint damper ``D*lambda*v*L**2`` (N*m*s/rad) at chain speed ``v``
        (:attr:`chainfountain.sim.config.SolverConfig.wave_damping`)."""
        cfg = self.config
        L = float(cfg.chain.link_length)
        return float(cfg.solver.wave_damping) * cfg.chain.linear_density * abs(speed) * L * L

    def _limits(self) -> Limits:
        """Watchdog limits from the level's speed and size (:func:`limits_for`)."""
        return limits_for(self.config)

    def reset(self) -> None:
        """Rebuild from the current configuration (time back to 0, recorder cleared)."""
        self._build()

    # ------------------------------------------------------------------ stepping
    @property
    def dt(self) -> float:
        """Time step (s) of the bookkeeping, the samples and :meth:`step`."""
        return float(self.config.solver.dt)

    @property
    def h(self) -> float:
        """pymunk's step (s): ``dt / solver.substeps``."""
        return self._h

    @property
    def g(self) -> float:
        return float(self.config.gravity)

    def step(self) -> None:
        """Advance by one time step ``dt``: ``solver.substeps`` pymunk steps of :attr:`h`
        (external forces applied before each), then the bookkeeping.

        Raises :class:`~chainfountain.sim.watchdog.Diverged` when the run has left
        physics (checked every :data:`~chainfountain.sim.watchdog.CHECK_INTERVAL`), and
        an apparatus's :class:`~chainfountain.errors.RunEnded` when the machine cannot
        go on."""
        rec = self.recorder
        sample = rec is not None and rec.wants(self.steps + 1)
        pre: ChainState | None = self.reader.read() if sample else None
        read_contacts = sample and self.chain.shapes
        contacts: np.ndarray | None = None
        before = self.ends.before_step
        probe = self.probe
        space_step, h = self.space.step, self._h
        for _ in range(self._substeps):
            before()
            if read_contacts:
                self.reader.arm()  # this pymunk step's contact impulses, stale ones out
            if probe is not None:
                probe.before()
            space_step(h)
            if probe is not None:
                probe.after()
            if read_contacts:
                c = self.reader.contact_impulses()
                contacts = c if contacts is None else contacts + c
        self.steps += 1
        self.time = self.steps * self._dt
        if pre is not None and rec is not None:
            rec.take(pre, self.reader.read(), contacts)
        if self.steps % self._check_every == 0:
            self.watchdog.check(self.time)
        self.ends.after_step(self._dt)

    def advance(self, seconds: float) -> int:
        """Step for ``seconds`` of simulated time (rounded to whole steps); returns steps taken."""
        n = int(round(seconds / self.dt))
        step = self.step
        for _ in range(n):
            step()
        return n

    # ------------------------------------------------------------------ commands
    def nudge(self, seed: int | tuple[int, ...], rel: float = 1e-12) -> None:
        """Change every moving body's velocity by about ``rel`` of itself (seeded).

        Far below anything physical, as another machine or library build changes the
        last bits of a run: runs of one level nudged with different seeds sample the
        spread of its chaotic quantities (ensembles in the tests and studies). Call it
        right after building or resetting; the same seed gives the same run.
        """
        nudge_bodies(self.space, seed, rel)

    def reference_at(self, v: float) -> Reference | None:
        """The theory's fountain for this level at chain speed ``v`` (:meth:`predict_at`);
        ``None`` when there is none."""
        return self.predict_at(v).reference

    def predict_at(self, v: float) -> Prediction:
        """What this level at chain speed ``v`` is compared with: the paper's catenary
        (:meth:`LaunchReference.of_level`), or the stiff fountain for a motor-fed chain
        with joint resistance (:func:`~chainfountain.sim.stiff_reference.predict`, solved
        from the present one)."""
        guess = self.reference if isinstance(self.reference, StiffReference) else None
        return predict(self.config, self._catenary_at(v), guess)

    def _catenary_at(self, v: float) -> LaunchReference | None:
        """The paper's catenary for this level at chain speed ``v`` (``None``: none)."""
        try:
            return LaunchReference.of_level(self.config, v)
        except ValueError:
            return None

    def set_theory(self, pred: Prediction) -> None:
        """Take ``pred`` as the level's theory (:attr:`reference`, :attr:`catenary`,
        :attr:`reference_note`); the feed follows the catenary."""
        self.catenary = pred.catenary
        self.reference = pred.reference
        self.reference_note = pred.note
        self.theory_stale = False
        self.theory_version += 1
        if self.feed is not None:
            self.feed.set_reference(pred.catenary)

    def theory_at(self, v: float) -> None:
        """The theory at a new speed ``v``: the catenary (the feed's) at once, a stiff
        chain's theory too unless :attr:`defer_theory` (then :meth:`refresh_theory`)."""
        if not (self.defer_theory and stiff_applies(self.config)):
            self.set_theory(self.predict_at(v))
            return
        self.catenary = self._catenary_at(v)
        if self.feed is not None:
            self.feed.set_reference(self.catenary)
        self.theory_stale = True
        self.theory_changes += 1

    def joints_changed(self) -> None:
        """The joints' spring or damper changed live: the stiff theory is solved again
        (at once, or by :meth:`refresh_theory` when :attr:`defer_theory`); nothing for a
        kind whose chain is compared with the string model whatever its joints."""
        if self.feed is None or not self.kind.stiff_theory:
            return
        if self.defer_theory:
            self.theory_stale = True
            self.theory_changes += 1
        else:
            self.refresh_theory()

    def theory_problem(self) -> tuple[SimConfig, LaunchReference | None,
                                      StiffReference | None]:
        """What :meth:`refresh_theory` solves, to solve elsewhere (another thread) with
        :func:`~chainfountain.sim.stiff_reference.predict`: a copy of the configuration,
        the catenary and the present stiff fountain (the guess)."""
        guess = self.reference if isinstance(self.reference, StiffReference) else None
        return copy.deepcopy(self.config), self.catenary, guess

    def refresh_theory(self) -> None:
        """Solve the theory for the present joints at the catenary's speed, continued from
        the present stiff fountain."""
        self.set_theory(predict(*self.theory_problem()))

    def follow_speed(self, v: float) -> None:
        """Keep the reference on the loss-free full machine's present speed ``v`` (it keeps
        whatever speed it has, so the paper's fountain moves with it): recomputed when ``v``
        has moved by :data:`FOLLOW_TOLERANCE` of the reference's speed."""
        if not keeps_any_speed(self.config) or self.feed is None:
            return
        ref = self.catenary
        if ref is not None and abs(v - ref.v) <= FOLLOW_TOLERANCE * ref.v:
            return
        self.set_theory(self.predict_at(v))

    def set_feed_speed(self, v: float) -> None:
        """Change the feed speed live (m/s); the reference is recomputed. With the ideal
        floor machine this pushes the chain to ``v``, and the machine settles back."""
        if self.feed is None:
            raise KeyError("feed.speed: this level has no feed")
        if self.piston is not None:
            self.piston.set_speed(v)
        else:
            self.feed.set_speed(v)
        self.watchdog.limits = self._limits()
        self.theory_at(v)
        self.chain.wave_damping = self.wave_damping_at(v)
        self.chain.set_bending()  # refits every damper to the new speed

    def machine_changed(self) -> None:
        """An ideal machine's offset, cart or bearing drag (:data:`MACHINE_FIELDS`) has
        changed in :attr:`config`: the laws read them every step, so the chain feels the
        change at once; the reference moves to the paper's fountain at the present speed."""
        if self.feed is None:
            return
        v = self.piston.chain_speed if self.piston is not None else self.feed.speed
        self.set_theory(self.predict_at(v))

    def set_bending(self, stiffness: float | None = None, damping: float | None = None) -> None:
        """Change the joint spring ``c`` (N*m/rad) and/or damper ``d`` (N*m*s/rad) live."""
        self.apply({p: v for p, v in (("chain.bending_stiffness", stiffness),
                                      ("chain.bending_damping", damping)) if v is not None})

    def set_param(self, path: str, value: float) -> dict[str, float]:
        """Change the level field ``path`` (e.g. ``"chain.friction"``) live: the change and
        what follows it (:func:`chainfountain.sim.live.plan`), applied by :meth:`apply`;
        returns the fields written. ``KeyError`` for a field that needs a rebuild (change
        :attr:`config` and call :meth:`reset` instead)."""
        if live.setter_for(self.config, path) is None:
            raise KeyError(f"{path} cannot be changed while running; change the config and "
                           "reset()")
        changes = live.plan(self.config, path, live.number(path, value))
        self.apply(changes)
        return changes

    def apply(self, changes: dict[str, float]) -> None:
        """Write planned live ``changes`` (field path -> value, :func:`chainfountain.sim.live.plan`)
        into :attr:`config` and run each field's setter once. ``KeyError`` (nothing
        changed) when one of them needs a rebuild."""
        setters = []
        for path in changes:
            setter = live.setter_for(self.config, path)
            if setter is None:
                raise KeyError(f"{path} cannot be changed while running; change the config "
                               "and reset()")
            setters.append((setter, live.split(path)[1]))
        for path, value in changes.items():
            set_value(self.config, path, value)
        for (setter, index), value in zip(setters, changes.values(), strict=True):
            setter(self, index, value)

    def nearest_link(self, point: tuple[float, float]) -> int:
        """Index (chain order) of the link whose centre is nearest to ``point``."""
        st = self.reader.read()
        d = np.hypot(st.position[:, 0] - point[0], st.position[:, 1] - point[1])
        return int(np.argmin(d))

    def grab(self, point: tuple[float, float], max_force: float | None = None) -> int | None:
        """Start dragging the free link nearest to ``point``; returns its index or ``None``.

        A kinematic mouse body is pinned to the link by a pivot joint whose
        force is capped at ``max_force`` (default: 50 times the weight of the
        chain in flight). While a link is held, tension readings are invalid
        (the drag force is not in the momentum balance).
        """
        self.release()
        if self.n_free == 0:
            return None
        st = self.reader.read()
        pos = st.position[: self.n_free]
        i = int(np.argmin(np.hypot(pos[:, 0] - point[0], pos[:, 1] - point[1])))
        body = self.chain.links[i].body
        mouse = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        mouse.position = point
        joint = pymunk.PivotJoint(mouse, body, point)
        if max_force is None:
            max_force = 50.0 * self.chain.mass * max(self.n_free, 1) * max(self.g, 1.0)
        joint.max_force = max_force
        joint.error_bias = 0.1 ** 60
        self.space.add(joint)
        self._mouse_body, self._mouse_joint, self._grabbed = mouse, joint, i
        return i

    def drag_to(self, point: tuple[float, float]) -> None:
        """Move the drag target to ``point`` (call every frame while dragging)."""
        if self._mouse_body is None:
            return
        old = self._mouse_body.position
        self._mouse_body.position = point
        self._mouse_body.velocity = ((point[0] - old.x) / self.dt, (point[1] - old.y) / self.dt)

    def release(self) -> None:
        """Stop dragging."""
        if self._mouse_joint is not None and self._mouse_joint in self.space.constraints:
            self.space.remove(self._mouse_joint)
        self._mouse_body = self._mouse_joint = self._grabbed = None

    @property
    def dragging(self) -> bool:
        """True while a link is held."""
        return self._mouse_joint is not None and self._mouse_joint in self.space.constraints

    # ------------------------------------------------------------------ views
    @property
    def n_free(self) -> int:
        """Number of dynamic (free) links, counted from the downstream end."""
        return self.ends.n_free

    @property
    def n_links(self) -> int:
        """All links in the space (free plus guide)."""
        return len(self.chain.links)

    def state(self) -> ChainState:
        """Positions, angles and velocities of all links (chain order, downstream first)."""
        return self.reader.read()

    def chain_polyline(self) -> np.ndarray:
        """All links as one polyline ``(n+1, 2)`` (free chain first, then the guide links)."""
        return polyline(self.reader.read(), self.chain.L)

    def link_endpoints(self) -> tuple[np.ndarray, np.ndarray]:
        """Front and back end of every link, each ``(n, 2)``, chain order."""
        return link_ends(self.reader.read(), self.chain.L)

    @property
    def drop(self) -> float:
        """The fountain's drop ``H`` (m): ``apparatus.drop`` or ``feed.drop`` by level kind."""
        if self.apparatus is not None:
            return float(self.apparatus.H)
        if self.beaker is not None:
            return float(self.config.beaker.drop)
        return float(self.config.feed.drop)

    def kinetic_energy(self) -> float:
        """Kinetic energy of the free links (J)."""
        st = self.reader.read()
        n = self.n_free
        m, moment = self.chain.mass, self.chain.moment
        v2 = np.sum(st.velocity[:n] ** 2)
        return float(0.5 * m * v2 + 0.5 * moment * np.sum(st.angular_velocity[:n] ** 2))

    def describe(self) -> str:
        """One line about the running level."""
        app = self.apparatus
        if app is not None:
            return (f"{self.config.name or 'apparatus'} ({app.variant}): t={self.time:.3f} s, "
                    f"{self.n_links} links of {self.chain.L * 1e3:.1f} mm, "
                    f"v={app.speed:.2f} m/s (twice the pick-up roller speed), "
                    f"H={app.H:g} m, xi2={self.config.apparatus.xi2:g}")
        r = self.reference
        pred = "" if r is None else f", predicted h={r.h:.3f} m, l={r.landing_x:.3f} m"
        if isinstance(r, StiffReference):
            pred += f" ({r.label})"
        elif r is None and self.reference_note:
            pred = f", {self.reference_note}"
        return (f"{self.config.name or 'feed'}: t={self.time:.3f} s, {self.n_free} free links "
                f"of {self.chain.L * 1e3:.1f} mm, v={self.ends.speed:.2f} m/s, "
                f"alpha0={math.degrees(self.config.feed.launch_angle):.1f} deg{pred}")
