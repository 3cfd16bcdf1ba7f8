"""A headless run: defaults, the output folder, running and writing, the exit status and
the terminal's lines about it."""

from __future__ import annotations

import shutil
import signal
import textwrap
from collections.abc import Callable
from pathlib import Path
from typing import Any

from chainfountain import atomic
from chainfountain.errors import UserError
from chainfountain.exits import ENDED_EARLY, EXIT_STATUS, WRITE_FAILED
from chainfountain.headless import apparatus_refine, files
from chainfountain.headless.report import Ended, RunSummary, json_safe
from chainfountain.headless.scene import _write, describe_scene, run_scene
from chainfountain.headless.section_text import section_lines, steadiness
from chainfountain.headless.stepper import SceneRun, Stepper, simulate
from chainfountain.headless.stepping import Ending, _signals_deferred
from chainfountain.headless.summary import _attempt, _f, summarize
from chainfountain.level.io import Level
from chainfountain.sim.kinds import kind_of
from chainfountain.sim.kinds.base import (  # noqa: F401 - the kinds' durations, re-exported
    DEFAULT_DURATION,
    FORMING_DURATION,
    MACHINE_FORMING_DURATION,
)
from chainfountain.sim.recorder import Recorder
from chainfountain.sim.world import Simulation

DEFAULT_OUTPUTS = ("summary.json", "tensions.csv", "speed.csv", "snapshot.png")
"""What every run writes (``summary.json`` lists its own files under ``outputs``)."""


def default_duration(level: Level) -> float:
    """Simulated seconds of a headless run of ``level`` when none is given: its kind's
    (:attr:`~chainfountain.sim.kinds.base.Kind.default_duration`)."""
    return kind_of(level.sim).default_duration(level.sim)


def check_run(level: Level, duration: float | None = None, seed: int | None = None, *,
              where: str = "", names: tuple[str, str] = ("duration", "seed")) -> float:
    """Check a run's options against ``level`` before anything is written, as the command
    line and the Python API both do; returns the duration the run takes (``None``: the
    level's default). :class:`~chainfountain.errors.UserError` naming the option
    (``names``: how the caller calls them, e.g. ``--duration``), or
    :class:`~chainfountain.level.model.LevelError` naming the field, in one line."""
    from chainfountain.level.model import LevelError
    from chainfountain.options import DURATION, SEED

    d = default_duration(level) if duration is None else DURATION.check(duration, names[0])
    if seed is not None:
        SEED.check(seed, names[1])
        why = kind_of(level.sim).unseeded(level.sim)
        if why is not None:
            raise UserError(
                f"{names[1]}: {seed} has no effect on {level.meta.name!r} ({why}); allowed: "
                "only with a level that has random choices to seed (a scene: scene.jitter "
                "above 0)")
    interval = level.sim.recording.sample_interval
    if interval > d:
        at = f"{where}: " if where else f"{level.meta.name}: "
        if duration is None:
            raise LevelError(f"{at}recording.sample_interval: {interval:g} s is longer than "
                             f"the run ({d:g} s), which would record nothing; allowed: at "
                             "most the run's duration")
        raise LevelError(f"{names[0]}: {d:g} s is shorter than {at}recording.sample_interval "
                         f"({interval:g} s), so the run would record nothing; allowed: a "
                         f"duration of at least {interval:g} s")
    return d


def default_out_dir(level: Level) -> Path:
    """Where a headless run of ``level`` writes by default: ``./runs/<name>``."""
    from chainfountain.level.library import safe_name

    return Path("runs") / safe_name(level.meta.name)


def exit_status(summary: RunSummary | dict[str, Any]) -> int:
    """The exit status (:data:`chainfountain.exits.EXITS`) of a run with this summary (a
    :class:`~chainfountain.headless.report.RunSummary` or its ``summary.json`` object):
    0 for a complete run; 3 if it ended early (the machine stopped, the run diverged);
    128 + the signal's number (130 for Ctrl-C, 143 for SIGTERM) if it was interrupted;
    4 if an output could not be written. The outputs cover the part simulated."""
    s = summary if isinstance(summary, RunSummary) else RunSummary.from_json(summary)
    if s.write_failed:
        return WRITE_FAILED
    ended = s.ended_early
    if ended is None:
        return 0
    if ended.cause == "interrupted":
        return 128 + int(ended.signal_number or signal.SIGINT)
    return EXIT_STATUS.get(ended.cause, ENDED_EARLY)


def prepare_out_dir(out_dir: Path, option: str = "--out") -> Path:
    """Create ``out_dir`` and make sure a file can be written there, before any simulating:
    a folder that cannot be written is bad input (one line naming ``option``)."""
    out_dir = Path(out_dir)
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        with atomic.atomic_path(out_dir / ".write-test") as tmp:
            tmp.write_bytes(b"")
        (out_dir / ".write-test").unlink()
    except OSError as exc:
        raise UserError(f"{option}: cannot write to {str(out_dir)!r} "
                        f"({exc.strerror or exc}); allowed: a folder you can write to") from None
    return out_dir


def run_level(level: Level, out_dir: Path, duration: float | None = None, *,
              seed: int | None = None, progress: bool = True,
              error_bars: dict | None = None, half_step: bool | str = False) -> Path:
    """Run ``level`` headless and write the outputs into ``out_dir``; returns summary.json.

    Raw outputs (the CSVs) are written before the analyses that could fail (figures,
    fits); a failed analysis is named in ``summary.json`` (``analysis_failed``) and the
    rest is still written. SIGINT or SIGTERM while simulating ends the run like a
    stopped machine: its part is written completely (a second signal while writing is
    noted, not obeyed). :func:`exit_status` gives the command's status. Raises
    :class:`OutputError` when ``summary.json`` itself cannot be written. ``error_bars``
    (:meth:`chainfountain.refine.Refinement.as_dict`) goes into ``summary.json`` as is.
    ``half_step``: the level is also run at half its step for its figures' step error:
    a scene's closed-form figures (:mod:`chainfountain.headless.scene_refine`;
    ``chainfountain run`` does), a contact machine's flight
    (:mod:`chainfountain.headless.apparatus_refine`; ``run --error-bars``); a sentence:
    not, and ``summary.json`` says why (``chainfountain run --no-refine``)."""
    return run_and_record(level, out_dir, duration, seed=seed, progress=progress,
                          error_bars=error_bars, half_step=half_step)[0]


def run_and_record(level: Level, out_dir: Path, duration: float | None = None, *,
                   seed: int | None = None, progress: bool = True,
                   error_bars: dict | None = None, snapshot: bool = True,
                   half_step: bool | str = False) -> tuple[Path, Recorder | SceneRun]:
    """:func:`run_level`, also returning the run's recorder (its time series in memory;
    a scene level's :class:`~chainfountain.headless.scene.SceneRun`);
    ``snapshot=False`` leaves out ``snapshot.png`` (drawing it is most of a short run's
    cost: 0.3 s of 0.42 s for 0.5 s of ``wide_low``) and a scene's ``scene.png``."""
    duration = default_duration(level) if duration is None else float(duration)
    out_dir = prepare_out_dir(out_dir)
    if not kind_of(level.sim).fountain:
        return run_scene(level, out_dir, duration, seed=seed, progress=progress,
                         snapshot=snapshot, refine=half_step)
    sim, rec, wall, ended = simulate(level, duration, seed=seed, progress=progress)
    half = None
    if half_step and kind_of(level.sim).half_step_bars:
        if isinstance(half_step, str):
            half = half_step
        elif ended is not None:
            half = f"the run ended early ({ended.reason})"
        else:
            fine = apparatus_refine.halved(level)
            half = (fine, *simulate(fine, duration, seed=seed, progress=progress,
                                    label=f"{level.meta.name} at dt/2"))
    received: list[int] = []
    with _signals_deferred(received):
        path = _write_outputs(level, out_dir, duration, sim, rec, wall, ended, error_bars,
                              snapshot, half)
    return path, rec


def write_outputs(run: Stepper, out_dir: Path, duration: float | None = None, *,
                  error_bars: dict | None = None, snapshot: bool = True) -> Path:
    """Write a :class:`~chainfountain.headless.stepper.Stepper`'s run into ``out_dir`` as
    ``chainfountain run`` does (the folder is made and checked first); returns
    ``summary.json``. ``duration``: the seconds asked for (default: the time run). A
    signal while writing is noted, not obeyed."""
    asked = run.time if duration is None else float(duration)
    out_dir = prepare_out_dir(Path(out_dir))
    with _signals_deferred([]):
        if not run.fountain:
            return _write(run.level, out_dir, asked, run.scene_run(), snapshot)
        return _write_outputs(run.level, out_dir, asked, run.sim, run.recorder, run.wall,
                              run.ended, error_bars, snapshot)


def _write_outputs(level: Level, out_dir: Path, duration: float, sim: Simulation,
                   rec: Recorder, wall: float, ended: Ending | None,
                   error_bars: dict | None = None, snapshot: bool = True,
                   half: tuple | str | None = None) -> Path:
    """Every output of a finished (or stopped) run, raw data first; see :func:`run_level`
    (``half``: the run at half the step, its level and :func:`simulate`'s tuple, or why
    there is none)."""
    lam = level.sim.chain.linear_density
    app = sim.apparatus
    written: list[str] = []
    write_failed: dict[str, str] = {}
    analysis_failed: dict[str, str] = {}

    def put(name: str, writer: Callable[..., None], *args: Any) -> None:
        try:
            writer(out_dir / name, *args)
            written.append(name)
        except OSError as exc:
            write_failed[name] = exc.strerror or str(exc)
        except Exception as exc:  # noqa: BLE001 - an analysis behind the file failed
            analysis_failed[name] = f"{type(exc).__name__}: {exc}"

    put("speed.csv", files.write_samples, _attempt(analysis_failed, "samples",
                                              lambda: rec.samples, default=[]))
    if app is not None:
        put("apparatus.csv", files.write_samples, _attempt(
            analysis_failed, "apparatus samples", lambda: rec.apparatus_samples, default=[]))
    put("tensions.csv", files.write_tensions, rec, lam)
    summary = summarize(level, sim, rec, duration, wall)
    if error_bars is not None and "error_bars" in summary.sections:
        summary.sections["error_bars"] = json_safe(error_bars)
    if half is not None and "apparatus" in summary.sections:
        summary.sections["apparatus"]["flight"]["step"] = _attempt(
            analysis_failed, "the step's refinement", _apparatus_step, level, duration,
            summary.sections["apparatus"], half)
    half_end = half[4] if isinstance(half, tuple) else None
    if ended is not None:
        summary.ended_early = Ended(
            t_s=_f(sim.time), cause=ended.cause, reason=ended.reason,
            signal_number=int(ended.signum) if ended.signum is not None else None)
        if ended.cause == "machine" and app is not None and app.fold_guided:
            # when the fountain last landed in the end guide's mouth (a lost catch comes
            # about 1 s before the fold's collapse)
            summary.ended_early.last_mouth_entry_s = _f(app.last_mouth_entry)
    elif half_end is not None and half_end.cause == "interrupted":  # the command stopped
        summary.ended_early = Ended(
            t_s=_f(sim.time), cause=half_end.cause, signal_number=int(half_end.signum or 2),
            reason=f"{half_end.reason} while running again at half the step: the run's own "
            "figures are complete, their step's error is not given")
    beaker = summary.sections.get("beaker") or {}
    v = beaker.get("speed") or summary.fountain.v or 0
    title = (f"{level.meta.name}: t = {sim.time:.2f} s, v = {v:.3f} m/s"
             + ("" if summary.steady else " (not steady)")
             + ("" if ended is None else " - ended early"))
    if snapshot and summary.fountain.samples is not None:
        put("snapshot.png", files.write_snapshot, sim, summary, title)
    if (app is not None and app.variant == "open" and "apparatus" in summary.sections) or \
            summary.sections.get("open"):
        put("reaction.png", files.write_reaction_figure, rec, summary, lam, level.sim.gravity,
            title)
    summary.analysis_failed.update(analysis_failed)
    order = ["summary.json", *DEFAULT_OUTPUTS[1:], "apparatus.csv", "reaction.png"]
    summary.outputs = sorted(["summary.json", *written], key=order.index)
    summary.write_failed = write_failed
    return files.write_summary(out_dir, summary, written)


def _apparatus_step(level: Level, duration: float, coarse: dict[str, Any],
                    half: tuple | str) -> dict[str, Any]:
    """``apparatus.flight.step`` from the run at half the step, or why there is none."""
    if isinstance(half, str):
        return apparatus_refine.skipped(half)
    halved, sim, rec, wall, ended = half
    if ended is not None:
        return apparatus_refine.skipped(f"the run at half the step ended early "
                                        f"({ended.reason})")
    fine = summarize(halved, sim, rec, duration, wall)
    return apparatus_refine.step_section(coarse, fine.sections["apparatus"],
                                         level.sim.solver.dt)


def describe_outputs(summary_path: Path, summary: RunSummary | None = None) -> str:
    """A few lines for the terminal: what was written and how the run compares with theory,
    formatted from ``summary`` (read from ``summary_path`` when not given)."""
    summary_path = Path(summary_path)
    out = summary_path.parent
    s = RunSummary.load(summary_path) if summary is None else summary
    if s.scene is not None:
        return describe_scene(s, out)
    f = s.fountain
    steady = steadiness(s, f"steady since {f.steady_since_s:.2f} s" if s.steady
                        else "never steady (compare with care)")
    lines = [
        f"wrote {out}/" + ", ".join(s.outputs or DEFAULT_OUTPUTS),
        f"  {s.links} links, {s.steps} steps, real-time factor "
        f"{s.realtime_factor or 0:.2f}, {steady}",
    ]
    for name, why in s.write_failed.items():
        lines.append(f"  NOT WRITTEN: {name} ({why})")
    for name, why in s.analysis_failed.items():
        lines.append(f"  analysis failed: {name} ({why}); its figures are null")
    if s.ended_early is not None:
        # the reason runs to several sentences (a fold's collapse: about 900 characters):
        # wrapped to the terminal, continuation lines indented under it
        width = max(60, min(100, shutil.get_terminal_size((100, 24)).columns - 1))
        lines.append(textwrap.fill(
            f"ENDED EARLY (of {s.requested_duration_s:g} s asked for): "
            f"{s.ended_early.reason}", width=width, initial_indent="  ",
            subsequent_indent="    ", break_on_hyphens=False))
    return "\n".join(lines + section_lines(s))
