"""The app's model side: one running level and the commands the window sends it.

No pygame here. :class:`Session` owns the :class:`~chainfountain.level.io.Level`
being shown, the :class:`~chainfountain.sim.world.Simulation` built from it and
a :class:`~chainfountain.sim.recorder.Recorder`. The view calls :meth:`Session.tick`
once per frame with the wall time that passed and a time budget; the session
steps the physics at its fixed ``dt`` (an accumulator), never spends more than
the budget, and reports the real-time factor it achieved. Setting a field
(:meth:`Session.set_field`) clamps to the schema limits, applies live changes
through the simulation's commands and rebuilds for the rest.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import sys
import threading
import time
import tomllib
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from chainfountain.app import cost, interactive, paths
from chainfountain.app.controls import FieldSpec, spec_for
from chainfountain.app.readout import (
    History,
    Readout,
    compute_readout,
)
from chainfountain.errors import RunEnded, UserError
from chainfountain.fields import get_value, set_value
from chainfountain.level import io, library, resolve
from chainfountain.level.io import Level, LevelError
from chainfountain.sim.config import SimConfig
from chainfountain.sim.live import plan
from chainfountain.sim.recorder import Recorder
from chainfountain.sim.stiff_reference import Prediction, predict
from chainfountain.sim.world import Simulation

SLOW_FACTORS: tuple[float, ...] = (1.0, 0.5, 0.25)
"""Slow-motion cycle of the ``S`` key."""

CATCH_UP = 0.25
"""Wall seconds of physics a window may fall behind and still make up in later frames."""
THEORY_EVERY = 0.3
"""Wall seconds between the starts of two solves of a stiff chain's theory while its
joints' slider moves (the first change is solved at once, the last one within this time):
a solve takes about 0.05-0.5 s (:mod:`chainfountain.sim.stiff_reference`), and where there
is no steady fountain up to tens of seconds, so it runs in a thread beside the window."""
APP_SAMPLE_INTERVAL = 0.04
"""The app samples measurements at most this often (s): 25 a second are enough for the
graphs (redrawn 15 times a second) and the readout (a 0.25-s mean), and each sample costs
two batch reads and a catenary fit (a machine's also its sample's analysis, about 1 ms)."""


def default_level() -> Level:
    """The built-in default level (``chainfountain.level.library`` when present)."""
    try:
        from chainfountain.level import library  # type: ignore[attr-defined]

        return library.default_level()
    except (ImportError, AttributeError):
        from chainfountain.sim.config import SimConfig

        return io.make_level("default", "A chain fed at 5 m/s, 75 degrees, falling 1 m "
                             "onto an absorbing floor", SimConfig())


def paused_message(reason: str) -> str:
    """The status line for a run that stopped itself: ``reason`` (the exception's text),
    that the window is paused and how to go on."""
    return f"{reason.rstrip('.')}; paused: press R to start again"


HAND_SETTINGS = resolve.CHOSEN
"""Fields ``solver.accuracy`` chooses; setting one by hand turns the accuracy off."""


def changed_fields(before: SimConfig, after: SimConfig) -> list[tuple[str, Any, Any]]:
    """Every level field whose value differs, as ``(dotted path, before, after)``."""
    def flat(sim: SimConfig) -> dict[str, Any]:
        out: dict[str, Any] = {}

        def walk(prefix: str, obj: Any) -> None:
            if isinstance(obj, dict):
                for k, v in obj.items():
                    walk(f"{prefix}.{k}" if prefix else k, v)
            elif isinstance(obj, list) and obj and all(isinstance(x, dict) for x in obj):
                for i, v in enumerate(obj):
                    walk(f"{prefix}[{i}]", v)
            else:
                out[prefix] = obj

        data = tomllib.loads(io.dumps(io.make_level("x", "", sim)))
        data.pop("meta", None)
        walk("", data)
        return out

    a, b = flat(before), flat(after)
    return [(k, a.get(k), b.get(k)) for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]


def saved_description(origin: Level, sim: SimConfig) -> str:
    """The description a saved level gets: the original one when nothing changed, else a
    first sentence naming the level it came from and each changed field (the original
    description, kept after it, describes the original settings)."""
    changes = changed_fields(origin.sim, sim)
    if not changes:
        return origin.meta.description
    listed = "; ".join(f"{k} {old!r} -> {new!r}" for k, old, new in changes[:12])
    more = f" and {len(changes) - 12} more" if len(changes) > 12 else ""
    return (f"Level {origin.meta.name!r} with changes ({listed}{more}). Its description, "
            f"for the original settings: {origin.meta.description}")


@dataclass
class Applied:
    """Result of :meth:`Session.set_field`."""

    path: str
    value: float
    """The value now in the level (schema units)."""
    ok: bool
    """False when the change was refused (the old value stays)."""
    live: bool
    """True when applied to the running simulation without a rebuild."""
    message: str


class _TheoryJob:
    """A stiff chain's theory solved in a daemon thread (:meth:`Session.refresh_theory`):
    a closing window never waits for it."""

    def __init__(self, sim: Simulation) -> None:
        self.sim = sim
        self.changes = sim.theory_changes
        self.problem = sim.theory_problem()
        self.result: Prediction | None = None
        self.seconds = math.nan
        self.thread = threading.Thread(target=self._run, name="stiff theory", daemon=True)

    @classmethod
    def start(cls, sim: Simulation) -> _TheoryJob:
        job = cls(sim)
        job.thread.start()
        return job

    def _run(self) -> None:
        t0 = time.perf_counter()
        try:
            self.result = predict(*self.problem)
        except Exception:  # noqa: BLE001 - a bug: on the terminal, the old theory stays
            traceback.print_exc(file=sys.stderr)
        self.seconds = time.perf_counter() - t0


class Session:
    """A level running in the app; all commands of the window go through here."""

    def __init__(self, level: Level, source: Path | None = None,
                 clock: Callable[[], float] = time.perf_counter) -> None:
        self.clock = clock
        self.paused = False
        self.slow_index = 0
        self.rtf = 1.0
        """Smoothed real-time factor achieved (simulated seconds per wall second)."""
        self.behind = False
        """True when the last frames could not keep up with the requested speed."""
        self.messages: list[tuple[float, str]] = []
        self.stopped: str | None = None
        """Why the run cannot go on (a table used up, the fold collapsed): shown while
        paused until the scene is rebuilt."""
        self.dirty = False
        """The setup differs from the last loaded or saved file."""
        self.history = History()
        self._readout = Readout()
        self._readout_key: tuple = ()
        self._acc = 0.0
        self._drag_target: tuple[float, float] | None = None
        self._drag_prev: tuple[float, float] | None = None
        self._consumed = 0
        self.level = copy.deepcopy(level)
        self.source = source
        self._origin = copy.deepcopy(level)
        """The level as loaded or last saved (what its description describes)."""
        self._build()

    # ------------------------------------------------------------------ building
    def _build(self) -> None:
        self.runs_at = interactive.window_settings(self.level.sim)
        """The settings the window runs (the level's, or a coarser accuracy's to keep real
        time: :mod:`chainfountain.app.interactive`)."""
        self.sim = Simulation(self.runs_at.config, defer_theory=True)  # see refresh_theory
        self._theory_at = -math.inf
        self._solving: _TheoryJob | None = None
        self.theory_solve_s: float | None = None
        """Wall seconds the last solve of a stiff chain's theory took (in its thread)."""
        rc = self.level.sim.recording
        interval = max(rc.sample_interval, APP_SAMPLE_INTERVAL)
        self.recorder = Recorder(self.sim, dataclasses.replace(rc, sample_interval=interval))
        self.history.clear()
        self._consumed = 0
        self._acc = 0.0
        self._drag_target = self._drag_prev = None
        self._readout_key = ()
        self.stopped = None
        if self.runs_at.coarsened:
            self.say(interactive.coarsened_message(self.runs_at))

    @property
    def name(self) -> str:
        return self.level.meta.name

    def say(self, text: str) -> str:
        """Queue a status message (the window shows the newest ones for a few seconds)."""
        self.messages.append((self.clock(), text))
        del self.messages[:-20]
        return text

    def reset(self) -> None:
        """Rebuild the scene from the current setup (time back to 0); a run that had
        stopped itself starts again."""
        stopped = self.stopped is not None
        self._build()
        if stopped:
            self.paused = False
        self.say("reset: t = 0")

    def load_level(self, level: Level, source: Path | None = None) -> bool:
        """Replace the running level; on failure keep the old one and say why. After a run
        that stopped itself the new level runs (a pause the user chose stays)."""
        stopped = self.stopped is not None
        old = (self.level, self.source)
        self.level = copy.deepcopy(level)
        self.source = source
        try:
            self._build()
        except (ValueError, LevelError) as exc:
            self.level, self.source = old
            self._build()
            self.say(f"cannot open {level.meta.name!r}: {exc}")
            return False
        self.dirty = False
        self._origin = copy.deepcopy(level)
        if stopped:
            self.paused = False
        self.say(f"opened level {level.meta.name!r}" + (f" ({source})" if source else ""))
        return True

    def restore(self, level: Level, source: Path | None, opened: Level, dirty: bool) -> bool:
        """Go back to a setup left for another level: ``level`` running, ``opened`` the
        level as it was opened (what Reset all restores), ``dirty`` whether ``level``
        has changes not saved."""
        if not self.load_level(opened, source):
            return False
        self.level = copy.deepcopy(level)
        self._build()
        self.dirty = dirty
        return True

    def load_path(self, path: Path) -> bool:
        """Load a level file (errors are reported, never raised)."""
        try:
            level = io.load(path)
        except LevelError as exc:
            self.say(str(exc))
            return False
        return self.load_level(level, Path(path))

    def save(self, name: str, folder: Path | None = None) -> Path | None:
        """Save the current setup as ``<folder>/<name>.toml`` (default: the user's folder)."""
        name = name.strip()
        if not name:
            self.say("save: give a name")
            return None
        folder = folder if folder is not None else paths.user_levels_dir(create=True)
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f"{paths.safe_name(name)}.toml"
        level = self.saved_level(name, name)
        try:
            io.save(level, path)
        except (LevelError, OSError) as exc:
            self.say(f"save failed: {exc}")
            return None
        self.level = level
        self.source = path
        self.dirty = False
        self._origin = copy.deepcopy(level)
        self.say(f"saved {path}")
        return path

    def keep_copy(self, name: str, folder: Path | None = None) -> Path | None:
        """Write the present setup as ``<folder>/<name>.toml`` (default: the user's
        folder) and change nothing else: the level, its source and whether it has
        unsaved changes stay (an autosave)."""
        folder = folder if folder is not None else paths.user_levels_dir(create=True)
        path = folder / f"{paths.safe_name(name)}.toml"
        level = self.saved_level(name, f"{self._origin.meta.shown_title} (kept {name[-15:]})")
        try:
            folder.mkdir(parents=True, exist_ok=True)
            io.save(level, path)
        except (LevelError, OSError) as exc:
            self.say(f"could not keep the changes: {exc}")
            return None
        return path

    def saved_level(self, name: str, title: str) -> Level:
        """The present setup as a level named ``name`` with ``title``: its description
        says what changed from the level opened, its student sliders are that level's."""
        level = io.make_level(name, saved_description(self._origin, self.level.sim),
                              copy.deepcopy(self.level.sim))
        level.meta.title = title
        level.meta.controls = self._origin.meta.controls
        return level

    @property
    def opened(self) -> Level:
        """The level as it was opened (or last saved): what Reset all restores."""
        return self._origin

    # ------------------------------------------------------------------ fields
    def spec(self, path: str) -> FieldSpec:
        return spec_for(self.level.sim, path)

    @property
    def origin(self) -> SimConfig:
        """The level's setup as loaded (or last saved): the window's budget is set by it."""
        return self._origin.sim

    def value(self, path: str) -> float:
        return float(get_value(self.level.sim, path))

    def set_field(self, path: str, value: float) -> Applied:
        """Set a schema field: clamp to its limits, then apply live or rebuild.

        A change that the level's cross-field checks reject (e.g. a feed too
        slow to reach the floor) is refused and the old value stays.
        """
        try:
            spec = self.spec(path)
        except KeyError:
            return Applied(path, math.nan, False, False, self.say(f"no such field {path}"))
        old = self.value(path)
        v, clamp_msg = spec.clamp(value)
        if spec.integer:
            v = int(v)
        changes = plan(self.level.sim, path, v)  # with what follows it (the upper cart)
        cand = copy.deepcopy(self.level.sim)
        for p, value in changes.items():
            set_value(cand, p, value)
        followed = changes.get("feed.cart_force") if path != "feed.cart_force" else None
        by_hand = path in HAND_SETTINGS and cand.solver.accuracy > 0.0 and v != old
        if by_hand:
            # the user takes over what solver.accuracy chose; saved, the level keeps it
            cand.solver.accuracy = 0.0
        try:
            io.check_consistency(Level(meta=self.level.meta, sim=cand), "setting")
        except LevelError as exc:
            msg = str(exc).removeprefix("setting: ")
            return Applied(path, old, False, False, self.say(f"refused: {msg}"))
        why = interactive.over_budget(cand, self._origin.sim)
        if why is not None and path == "feed.speed" and v > old:
            fast = cost.fastest_feed(self.level.sim, self._origin.sim, v)
            if fast is not None and fast > old:
                rail = (f"{spec.label}: {spec.fmt(v)}{spec.shown_unit}: {why}; set to the "
                        f"fastest the window runs, {spec.fmt(fast)}{spec.shown_unit}")
                clamp_msg = f"{clamp_msg}; {rail}" if clamp_msg else rail
                v = fast
                changes = plan(self.level.sim, path, v)
                for p, value in changes.items():
                    set_value(cand, p, value)
                why = None
        if why is not None:
            return Applied(path, old, False, False, self.say(f"refused: {why}"))
        if v == old:
            return Applied(path, old, True, True, self.say(clamp_msg) if clamp_msg else "")
        self.level.sim = cand
        self.dirty = True
        shown = f"{spec.label} = {spec.fmt(spec.to_display(v))}{spec.shown_unit}"
        if spec.live and self._apply_live(changes):
            msg = f"{shown} (live)"
            live = True
        else:
            was_paused = self.paused
            self._build()
            self.paused = was_paused
            msg = f"{shown}: scene rebuilt (t = 0)"
            live = False
        if clamp_msg:
            msg = f"{clamp_msg}; {msg}"
        if by_hand:
            msg += "; solver.accuracy off (settings by hand)"
        if followed is not None:
            msg += f"; the upper cart follows to {followed:.4g} N to keep the machine balanced"
        return Applied(path, float(v), True, live, self.say(msg))

    def _apply_live(self, changes: dict[str, float]) -> bool:
        """Apply planned live ``changes`` to the running simulation (one path:
        :meth:`~chainfountain.sim.world.Simulation.apply`); ``False``: a field needs a rebuild."""
        try:
            self.sim.apply(changes)
        except KeyError:
            return False
        return True

    # ------------------------------------------------------------------ time
    @property
    def speed_factor(self) -> float:
        """Requested speed relative to real time (1, 1/2 or 1/4)."""
        return SLOW_FACTORS[self.slow_index]

    def cycle_slow(self) -> float:
        """Next slow-motion factor (1 -> 1/2 -> 1/4 -> 1)."""
        self.slow_index = (self.slow_index + 1) % len(SLOW_FACTORS)
        f = self.speed_factor
        self.say("speed: real time" if f == 1 else f"slow motion: 1/{round(1 / f)}")
        return f

    def toggle_pause(self) -> bool:
        """Pause or run; a run that stopped itself stays paused and says how to go on."""
        if self.stopped is not None:  # a run that stopped itself is paused
            self.say(paused_message(self.stopped))
            return True
        self.paused = not self.paused
        self._acc = 0.0
        self.say("paused" if self.paused else "running")
        return self.paused

    def hold(self, notice: str) -> None:
        """Pause at the start with ``notice`` over the scene (as a run that stopped itself
        keeps its reason) until R starts the level."""
        self.paused = True
        self.stopped = notice
        self.say(paused_message(notice))

    def _step(self, n: int) -> None:
        try:
            self._step_n(n)
        except RunEnded as exc:  # the machine cannot go on (a table used up, the fold collapsed)
            self.paused = True
            self.stopped = exc.plain + self._twin_hint()
            if exc.plain != str(exc):  # the long explanation, for whoever wants it
                print(f"chainfountain: {exc}", file=sys.stderr)
            self.say(paused_message(self.stopped))
        except UserError as exc:
            self.paused = True
            self.stopped = str(exc)
            self.say(paused_message(str(exc)))
        except Exception as exc:  # noqa: BLE001 - a bug: said plainly, details on stderr
            traceback.print_exc(file=sys.stderr)
            self.paused = True
            self.stopped = (f"the simulation stopped on an internal error "
                            f"({type(exc).__name__}; the details are on the terminal)")
            self.say(paused_message(self.stopped))

    def _twin_hint(self) -> str:
        """For a machine preset with a twin: that M opens it (the ideal machine runs where
        the contact one fails, and the other way round)."""
        other = library.twin(self.level.meta.name)
        if other is None:
            return ""
        kind = "ideal" if other.startswith("ideal") else "contact"
        return f"; M opens {other}, the {kind} machine"

    def _step_n(self, n: int) -> None:
        sim = self.sim
        tgt, prev = self._drag_target, self._drag_prev
        if tgt is not None and sim.dragging:
            p0 = prev if prev is not None else tgt
            for i in range(n):
                f = (i + 1) / n
                sim.drag_to((p0[0] + f * (tgt[0] - p0[0]), p0[1] + f * (tgt[1] - p0[1])))
                sim.step()
            self._drag_prev = tgt
            return
        step = sim.step
        for _ in range(n):
            step()

    def step_frame(self, frame_time: float = 1.0 / 60.0, budget: float = 0.25) -> int:
        """Single step: advance by one frame of simulated time (whole physics steps), or
        by as many steps as fit in ``budget`` wall seconds when a frame costs more (a
        fine chain at a tiny step), so the window never freezes. Returns the steps taken."""
        n = max(1, int(round(frame_time / self.sim.dt)))
        t0 = self.clock()
        done = 0
        while done < n and self.stopped is None:
            m = min(32, n - done)
            self._step(m)
            done += m
            if self.clock() - t0 > budget:
                break
        if done < n and self.stopped is None:
            self.say(f"one frame is {n} physics steps here; stepped {done} "
                     f"({done * self.sim.dt * 1e3:.2g} ms) to keep the window responsive")
        self._consume()
        return done

    def step_physics(self) -> None:
        """Advance by exactly one physics step ``dt``."""
        self._step(1)
        self._consume()

    def advance(self, seconds: float) -> int:
        """Advance by ``seconds`` of simulated time regardless of wall time (off-screen runs)."""
        n = int(round(seconds / self.sim.dt))
        if n > 0:
            self._step(n)
            self._consume()
        return n

    def tick(self, wall_dt: float, budget: float) -> int:
        """Run the physics for one frame: ``wall_dt`` s of wall time passed, spend <= ``budget``.

        Returns the number of physics steps taken. When the budget runs out the
        backlog is carried to the next frames, up to :data:`CATCH_UP` s of wall time (one
        slow frame, a collection or a busy display, is made up); beyond that it is
        dropped (the fountain slows down instead of stalling) and :attr:`rtf` falls below
        the requested factor.
        """
        if self.paused:
            self.rtf = 0.0
            self.behind = False
            return 0
        wall_dt = min(max(wall_dt, 0.0), 0.1)
        dt = self.sim.dt
        self._acc += wall_dt * self.speed_factor
        want = int(self._acc / dt)
        t0 = self.clock()
        done = 0
        chunk = max(1, min(want, 8))
        while done < want and self.stopped is None:
            n = min(chunk, want - done)
            self._step(n)
            done += n
            if self.clock() - t0 > budget:
                break
        self._acc -= done * dt
        self.behind = done < want
        if self._acc > CATCH_UP * self.speed_factor:
            self._acc = 0.0
        if wall_dt > 0:
            inst = done * dt / wall_dt
            self.rtf += 0.1 * (inst - self.rtf)
        self._consume()
        return done

    # ------------------------------------------------------------------ dragging
    def grab(self, point: tuple[float, float], max_dist: float) -> bool:
        """Grab the free link nearest to ``point`` when it is within ``max_dist`` (m)."""
        sim = self.sim
        n = sim.n_free
        if n == 0:
            return False
        pos = sim.state().position[:n]
        d = np.hypot(pos[:, 0] - point[0], pos[:, 1] - point[1])
        if float(d.min()) > max_dist:
            return False
        sim.grab(point)
        self._drag_target = self._drag_prev = point
        return sim.dragging

    def drag_to(self, point: tuple[float, float]) -> None:
        self._drag_target = point

    def release(self) -> None:
        self.sim.release()
        self._drag_target = self._drag_prev = None

    @property
    def dragging(self) -> bool:
        return self.sim.dragging

    # ------------------------------------------------------------------ measurements
    def _consume(self) -> None:
        """Move new recorder samples into the plot history and trim the recorder."""
        rec = self.recorder
        samples, profiles = rec.samples, rec.profiles
        # apparatus levels: one ApparatusSample per Sample, appended and trimmed together
        ap = rec.apparatus_samples if self.sim.apparatus is not None else []
        for i in range(self._consumed, len(samples)):
            s = samples[i]
            te = math.nan
            if i < len(profiles) and len(profiles[i].tension_bar):
                te = float(profiles[i].tension_bar[-1])
            v_in = v_out = math.nan
            reaction = s.plate_reaction  # the ideal open arrangement's (nan otherwise)
            if i < len(ap):
                v_in = 2.0 * ap[i].v_roller_up
                if self.sim.apparatus.lower is not None:
                    v_out = 2.0 * ap[i].v_roller_lo
                reaction = ap[i].tail_reaction
            self.history.append(s.t, s.speed_mean, s.T0_bar, te, s.vertex_y, s.landing_x,
                                v_in, v_out, reaction)
        self._consumed = len(samples)
        keep = max(64, int(2.0 * rec.cfg.window / rec.cfg.sample_interval))
        if len(samples) > 2 * keep:
            cut = len(samples) - keep
            del samples[:cut]
            if len(profiles) >= cut:
                del profiles[:cut]
            if len(ap) >= cut:
                del ap[:cut]
            self._consumed -= cut

    def refresh_theory(self, wait: bool = False) -> bool:
        """A stiff chain's theory, solved again in a thread when its joints or speed
        changed (:attr:`~chainfountain.sim.world.Simulation.theory_stale`), a solve started
        at most every :data:`THEORY_EVERY` s; a finished solve is taken unless the sim
        changed again meanwhile. ``wait``: start one now and wait for it (tests).
        ``True`` when a solve was taken."""
        sim = self.sim
        job = self._solving
        if job is not None:
            if wait:
                job.thread.join()
            if job.thread.is_alive():
                return False
            self._solving = None
            if job.sim is sim and job.changes == sim.theory_changes:
                if job.result is None:  # it failed (on the terminal): the old theory stays
                    sim.theory_stale = False
                    return False
                sim.set_theory(job.result)
                self.theory_solve_s = job.seconds
                return True
        if not sim.theory_stale or (not wait and self.clock() - self._theory_at
                                    < THEORY_EVERY):
            return False
        self._solving = _TheoryJob.start(sim)
        self._theory_at = self.clock()
        return self.refresh_theory(wait=True) if wait else False


    def readout(self) -> Readout:
        """Current numbers and theory overlay (recomputed when a new sample arrived or the
        theory moved)."""
        self.refresh_theory()
        key = (id(self.sim), len(self.history.t), self.history.t[-1] if self.history.t else -1,
               self.sim.dragging, self.sim.theory_version)
        if key == self._readout_key:
            self._readout.t = self.sim.time
            return self._readout
        was = self._readout.steady and self._readout_key[:1] == key[:1]  # the same run
        self._readout_key = key
        self._readout = compute_readout(self.sim, self.recorder, self.history,
                                        self.runs_at.asked, was_steady=was)
        return self._readout

    def setup_copy(self) -> Level:
        """A copy of the current setup as a level (what Ctrl+S writes)."""
        return dataclasses.replace(self.level, sim=copy.deepcopy(self.level.sim))
