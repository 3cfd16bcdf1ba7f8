"""A level simulated one call at a time: the stepping interface that headless runs, sweeps
and notebooks share (``chainfountain.start(level)`` gives one).

::

    sim = Stepper(level)                 # built from a level (any kind)
    sim.advance(2.0)                     # simulated seconds (None: it ran them all)
    sim.positions(), sim.velocities()    # link centres and their velocities, (n, 2) arrays
    sim.speeds(), sim.tensions()         # (n,) speeds; tensions (N) at the joints
    sim.probes()                         # a scene's probes now: {name: {column: value}}
    sim.set("feed.speed", 6.0)           # a live field, checked as a level file
    sim.series()                         # what was recorded: {name: array over samples}
    write_outputs(sim, out_dir)          # the outputs of a run (chainfountain.headless.run)

Every reading is a fresh array. A fountain (kinds 'feed', 'apparatus', 'beaker') records
its samples every ``recording.sample_interval`` (its :class:`Recorder`); a scene its
probes, at most :data:`~chainfountain.headless.stepping.MAX_SAMPLES` of them over the
duration it was built for.
"""

from __future__ import annotations

import copy
import dataclasses
import signal
import time
from typing import Any

import numpy as np

from chainfountain.errors import RunEnded, UserError
from chainfountain.fields import set_value
from chainfountain.headless.stepping import (
    MAX_PROFILES,
    MAX_SAMPLES,
    Ending,
    Interrupted,
    _progress,
    _signals_raise,
)
from chainfountain.level.model import Level, LevelError
from chainfountain.sim.kinds import kind_of
from chainfountain.sim.probe_log import ProbeLog
from chainfountain.sim.recorder import Recorder

FOUNTAIN_SERIES = ("t", "speed_mean", "speed_min", "speed_max", "vertex_x", "vertex_y",
                   "landing_x", "stretch", "n_free", "T0_bar")
"""The time series :meth:`Stepper.series` gives of a fountain (one value per sample); a
scene's are ``t`` and each probe's columns as ``"<probe>.<column>"``."""


@dataclasses.dataclass
class SceneRun:
    """What stepping a scene gave: the simulation, its probes' series, the chain at the
    start and at a few moments, the wall time and why it ended early (or ``None``)."""

    sim: Any
    log: ProbeLog
    start: np.ndarray
    shapes: list[tuple[float, np.ndarray]]
    interval: float
    wall: float
    ended: Ending | None


def seeded(level: Level, seed: int | None) -> Level:
    """``level`` with ``seed`` as its random seed (its kind's
    :attr:`~chainfountain.sim.kinds.base.Kind.seed_field`: ``initial.seed``, a scene's
    ``scene.seed``), as ``chainfountain run --seed`` runs it."""
    if seed is None:
        return level
    sim = copy.deepcopy(level.sim)
    set_value(sim, kind_of(sim).seed_field, int(seed))
    return dataclasses.replace(level, sim=sim)


class Stepper:
    """``level`` built and ready to step (``seed``: its random seed instead of the
    level's). ``duration``: the simulated seconds a scene is sampled for (default its
    ``scene.duration``); a fountain records however long it runs.

    What steps is the level kind's body: a :class:`FountainBody` (a
    :class:`~chainfountain.sim.world.Simulation` and its :class:`Recorder`) or a
    :class:`SceneBody` (a :class:`~chainfountain.sim.scene_sim.SceneSimulation` and its
    probes), chosen by the kind's :attr:`~chainfountain.sim.kinds.base.Kind.fountain`."""

    def __init__(self, level: Level, *, seed: int | None = None,
                 duration: float | None = None) -> None:
        self.level = seeded(level, seed)
        self.ended: Ending | None = None
        """Why the run stopped before what was asked of it (``None`` while it goes on)."""
        self.wall = 0.0
        """Wall seconds spent stepping."""
        body = FountainBody if kind_of(self.level.sim).fountain else SceneBody
        self.body: FountainBody | SceneBody = body(self.level, duration)
        self.sim: Any = self.body.sim
        self.recorder: Recorder | None = self.body.recorder
        self.log: ProbeLog | None = self.body.log

    @property
    def fountain(self) -> bool:
        """Whether this steps a fountain (else a scene)."""
        return self.body.fountain

    # ------------------------------------------------------------------ stepping
    @property
    def time(self) -> float:
        """Simulated seconds since the start."""
        return float(self.sim.time)

    @property
    def dt(self) -> float:
        """The time step (s)."""
        return float(self.sim.dt)

    def advance(self, seconds: float, progress: Any = None) -> Ending | None:
        """Step for ``seconds`` of simulated time (whole steps). Returns why the run
        stopped early (a machine's table used up, divergence, Ctrl-C), else ``None``;
        ``progress.update(simulated seconds)`` as it goes. A run that has ended early
        goes no further (:class:`~chainfountain.errors.UserError`)."""
        from chainfountain.options import DURATION

        DURATION.check(seconds, "seconds")
        if self.ended is not None:
            raise UserError(f"{self.level.meta.name}: the run ended at t = {self.time:.3f} s "
                            f"({self.ended.reason}); allowed: a new Stepper to run again")
        n = int(round(seconds / self.dt))
        t0 = time.perf_counter()
        try:
            self.ended = self.body.advance(n, progress)
        except (Interrupted, KeyboardInterrupt) as exc:
            signum = exc.signum if isinstance(exc, Interrupted) else signal.SIGINT
            self.ended = Ending("interrupted", f"interrupted by {signal.Signals(signum).name} "
                                f"at t = {self.time:.3f} s", signum)
        finally:
            self.wall += time.perf_counter() - t0
        return self.ended

    # ------------------------------------------------------------------ reading
    def points(self) -> np.ndarray:
        """The chain as a polyline of its link ends, ``(n + 1, 2)`` (m)."""
        return self.body.points()

    def positions(self) -> np.ndarray:
        """The link centres, ``(n, 2)`` (m): a fountain's in chain order (the downstream
        end first), a scene's from point 0."""
        return self.body.positions()

    def velocities(self) -> np.ndarray:
        """The link centres' velocities, ``(n, 2)`` (m/s), in :meth:`positions`' order."""
        return self.body.velocities()

    def speeds(self) -> np.ndarray:
        """The link centres' speeds, ``(n,)`` (m/s)."""
        return np.hypot(*self.velocities().T)

    def tensions(self) -> np.ndarray:
        """Tensions (N, + = pull): a scene's at its interior points ``1 .. n-1`` after the
        last step; a fountain's at the joints of its free chain from the launch point
        downstream, at its last recorded sample (empty before the first)."""
        return self.body.tensions()

    def probes(self) -> dict[str, dict[str, float]]:
        """A scene's probes at their last sample: ``{name: {column: value}}`` (a fountain
        has none)."""
        return self.body.probes()

    def series(self) -> dict[str, np.ndarray]:
        """Everything recorded so far, one array per name (:data:`FOUNTAIN_SERIES`; a
        scene's ``t`` and ``"<probe>.<column>"``)."""
        return self.body.series()

    # ------------------------------------------------------------------ changing
    def set(self, path: str, value: Any) -> None:
        """Change the field ``path`` while running, as the window's sliders do: the value
        is checked as a level file would be (one line naming the field otherwise), and
        only fields a running simulation takes are allowed (``feed.speed``,
        ``chain.friction``, ``carts[0].mass``, ...; :meth:`Simulation.set_param`)."""
        from chainfountain.level.paths import changed

        where = f"{self.level.meta.name}: live change"
        new = changed(self.level, {path: value}, where)
        self.body.set(where, path, value)
        self.level = new

    # ------------------------------------------------------------------ a scene's
    def _scene(self) -> SceneBody:
        if not isinstance(self.body, SceneBody):
            raise TypeError(f"{self.level.meta.name} is not a scene")
        return self.body

    @property
    def shape_at(self) -> set[int]:
        """A scene's step numbers after which the chain's shape is kept."""
        return self._scene().shape_at

    @shape_at.setter
    def shape_at(self, steps: set[int]) -> None:
        self._scene().shape_at = steps

    def scene_run(self) -> SceneRun:
        """A scene's run as a :class:`SceneRun`."""
        body = self._scene()
        return SceneRun(sim=body.sim, log=body.log, start=body.start, shapes=body.shapes,
                        interval=body.every * body.sim.dt, wall=self.wall, ended=self.ended)


class FountainBody:
    """What steps a fountain (kinds whose :attr:`~chainfountain.sim.kinds.base.Kind.fountain`
    is true): its :class:`~chainfountain.sim.world.Simulation` and :class:`Recorder`."""

    fountain = True
    log = None

    def __init__(self, level: Level, duration: float | None) -> None:
        from chainfountain.sim.world import Simulation

        self.level = level
        self.sim = Simulation(level.sim)
        self.recorder = Recorder(self.sim, max_profiles=MAX_PROFILES,
                                 max_samples=MAX_SAMPLES)

    def advance(self, n_steps: int, bar: Any) -> Ending | None:
        """``n_steps`` steps; why the run ended early, or ``None``."""
        from chainfountain.sim.watchdog import Diverged

        sim, rec = self.sim, self.recorder
        chunk = max(1, int(round(0.05 / sim.dt)))
        done = 0
        step = sim.step
        try:
            while done < n_steps:
                m = min(chunk, n_steps - done)
                for _ in range(m):
                    step()
                done += m
                if bar is not None:
                    bar.update(m * sim.dt)
                if done % (20 * chunk) < chunk:  # analyse as we go: raw states are large
                    rec.samples  # noqa: B018 - property access processes the raw samples
        except Diverged as exc:
            return Ending("diverged", str(exc))
        except RunEnded as exc:
            return Ending("machine", str(exc))
        return None

    def points(self) -> np.ndarray:
        return self.sim.chain_polyline()

    def positions(self) -> np.ndarray:
        return self.sim.state().position.copy()

    def velocities(self) -> np.ndarray:
        return self.sim.state().velocity.copy()

    def tensions(self) -> np.ndarray:
        rec = self.recorder
        if not rec.profiles:
            return np.zeros(0)
        smp = rec.samples[-1]
        v = smp.speed_mean if smp.speed_mean > 0 else 1.0
        lam = self.level.sim.chain.linear_density
        return np.asarray(rec.profiles[-1].tension_bar, dtype=float) * lam * v * v

    def probes(self) -> dict[str, dict[str, float]]:
        return {}

    def series(self) -> dict[str, np.ndarray]:
        return {name: self.recorder.series(name) for name in FOUNTAIN_SERIES}

    def set(self, where: str, path: str, value: Any) -> None:
        try:
            self.sim.set_param(path, value)
        except KeyError:
            raise LevelError(f"{where}: {path}: cannot change while the level runs (it is "
                             "built into the simulation); allowed: a live field (marked "
                             "'live' in docs/levels.md), or build a new one with the "
                             "change") from None


class SceneBody:
    """What steps a scene: its :class:`~chainfountain.sim.scene_sim.SceneSimulation` and
    its probes, sampled at most :data:`~chainfountain.headless.stepping.MAX_SAMPLES` times
    over ``duration``."""

    fountain = False
    recorder = None

    def __init__(self, level: Level, duration: float | None) -> None:
        from chainfountain.headless import scene_compare
        from chainfountain.sim.scene_sim import SceneSimulation

        self.level = level
        cfg = level.sim
        self.sim = SceneSimulation(cfg)
        span = float(cfg.scene.duration if duration is None else duration)
        n_steps = int(round(span / self.sim.dt))
        self.every = max(1, int(round(max(cfg.recording.sample_interval,
                                          span / MAX_SAMPLES) / self.sim.dt)))
        self.log = ProbeLog(cfg.scene.probes + scene_compare.probes(cfg),
                            n_steps // self.every + 1)
        self.start = self.sim.scene.points()
        self.shapes: list[tuple[float, np.ndarray]] = [(0.0, self.start)]
        self.shape_at: set[int] = set()
        """Step numbers after which the chain's shape is kept in :attr:`shapes`."""
        self._k = 0

    def advance(self, n_steps: int, bar: Any) -> Ending | None:
        """``n_steps`` steps; why the run ended early, or ``None``."""
        sim, log = self.sim, self.log
        for _ in range(n_steps):
            sim.step()
            self._k += 1
            k = self._k
            if k % self.every == 0:
                sim.end_sample()
                log.sample(sim)
                if not sim.finite():
                    return Ending("diverged", f"the chain blew up at t = {sim.time:.3f} s (a "
                                  "link end is not a finite number); try a smaller "
                                  "solver.dt or more solver.substeps")
            if k in self.shape_at:
                self.shapes.append((sim.time, sim.scene.points()))
            if k % 200 == 0 and bar is not None:
                bar.update(200 * sim.dt)
        return None

    def points(self) -> np.ndarray:
        return self.sim.scene.points()

    def positions(self) -> np.ndarray:
        p = self.sim.scene.points()
        return 0.5 * (p[1:] + p[:-1])

    def velocities(self) -> np.ndarray:
        return self.sim.scene.velocities()

    def tensions(self) -> np.ndarray:
        return self.sim.scene.tensions()

    def probes(self) -> dict[str, dict[str, float]]:
        if not self.log.n:
            return {}
        return {p.name: {c: float(v[-1]) for c, v in self.log.columns(i).items()}
                for i, p in enumerate(self.level.sim.scene.probes)}

    def series(self) -> dict[str, np.ndarray]:
        log = self.log
        out = {"t": log.t[: log.n].copy()}
        for i, probe in enumerate(self.level.sim.scene.probes):
            out.update({f"{probe.name}.{c}": v.copy() for c, v in log.columns(i).items()
                        if c != "t"})
        return out

    def set(self, where: str, path: str, value: Any) -> None:
        raise LevelError(f"{where}: {path}: a scene takes no change while it runs; "
                         "allowed: build a new one with the change")


def simulate(level: Level, duration: float, *, seed: int | None = None,
             progress: bool = True, label: str | None = None
             ) -> tuple[Any, Recorder, float, Ending | None]:
    """Build and run a level for ``duration`` simulated seconds (a :class:`Stepper`,
    with a progress display, SIGINT and SIGTERM ending it early).

    Returns sim, recorder, wall seconds and why the run ended early (a
    :class:`~chainfountain.errors.RunEnded`: a table used up, the fold collapsed, the
    watchdog; or SIGINT/SIGTERM), or None if it ran for the whole ``duration``."""
    run = Stepper(level, seed=seed)
    with _progress(duration, progress, label or level.meta.name) as bar, _signals_raise():
        run.advance(duration, bar)
    return run.sim, run.recorder, run.wall, run.ended
