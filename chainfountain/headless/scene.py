"""A headless run of a scene level (``kind = "scene"``): step it, sample its probes, write
``probe_<name>.csv`` per probe, ``summary.json`` (each column's statistics and the closed
form's comparison) and ``scene.png`` (the chain at a few moments and the probes against
time)."""

from __future__ import annotations

import io as _io
import signal
from pathlib import Path
from typing import Any

import numpy as np

from chainfountain import atomic
from chainfountain.headless import files, scene_compare, scene_refine
from chainfountain.headless.report import Ended, RunSummary, SceneFigures
from chainfountain.headless.section_text import pct
from chainfountain.headless.stepper import SceneRun, Stepper
from chainfountain.headless.stepping import (
    Ending,
    Interrupted,
    _progress,
    _signals_deferred,
    _signals_raise,
)
from chainfountain.headless.summary import _attempt, _f
from chainfountain.level.model import Level

SHAPES = 6
"""Chain shapes kept for the picture, evenly over the run."""


def simulate_scene(level: Level, duration: float, *, seed: int | None = None,
                   progress: bool = True, label: str | None = None) -> SceneRun:
    """Build the scene and step it for ``duration`` simulated seconds, sampling every
    ``recording.sample_interval``, or less often to keep at most
    :data:`~chainfountain.headless.stepping.MAX_SAMPLES` per probe (``summary.json``
    gives the interval used), keeping the chain's shape at :data:`SHAPES` moments
    (:class:`~chainfountain.headless.stepper.Stepper`)."""
    run = Stepper(level, seed=seed, duration=duration)
    n_steps = int(round(duration / run.dt))
    run.shape_at = set(np.linspace(0, n_steps, SHAPES).round().astype(int).tolist())
    with _progress(duration, progress, label or level.meta.name) as bar, _signals_raise():
        run.advance(duration, bar)
    return run.scene_run()


def run_scene(level: Level, out_dir: Path, duration: float, *, seed: int | None = None,
              progress: bool = True, snapshot: bool = True,
              refine: bool | str = False) -> tuple[Path, SceneRun]:
    """Run a scene level into ``out_dir`` (which exists and is writable); returns the path
    of ``summary.json`` and the run. Probe files first, then the summary, the picture
    last; a signal while writing is noted, not obeyed. ``refine``: also run it at half
    the step and give the closed form's figures their step's error
    (:mod:`~chainfountain.headless.scene_refine`, ``summary.json``'s
    ``closed_form_step``), where the scene has a closed form and no jitter; a sentence:
    not, for that reason (``closed_form_step`` gives it)."""
    run = simulate_scene(level, duration, seed=seed, progress=progress)
    half = refine if isinstance(refine, str) else (
        _refined(level, run, duration, seed, progress) if refine else None)
    with _signals_deferred([]):
        path = _write(level, out_dir, duration, run, snapshot, half)
    return path, run


def _refined(level: Level, run: SceneRun, duration: float, seed: int | None,
             progress: bool) -> SceneRun | Ending | str:
    """The scene run again at half its step, why it is not (a sentence), or how a signal
    ended it (its :class:`~chainfountain.headless.stepping.Ending`)."""
    why = scene_refine.refusal(level)
    if why is not None:
        return why
    if run.ended is not None:
        return f"the run ended early ({run.ended.reason})"
    if not scene_refine.has_figures(scene_compare.compare(level.sim, run.log, run.start)):
        return "the run reached none of the closed form's marks"
    try:
        with _signals_raise():
            half = simulate_scene(scene_refine.halved(level), duration, seed=seed,
                                  progress=progress, label=f"{level.meta.name} at dt/2")
    except (Interrupted, KeyboardInterrupt) as exc:
        signum = exc.signum if isinstance(exc, Interrupted) else signal.SIGINT
        return Ending("interrupted", f"interrupted by {signal.Signals(signum).name}", signum)
    if half.ended is not None and half.ended.cause == "interrupted":
        return half.ended
    return half


def _probe_csv(path: Path, columns: dict[str, np.ndarray]) -> None:
    buf = _io.StringIO()
    buf.write(",".join(columns) + "\n")
    np.savetxt(buf, np.column_stack(list(columns.values())), fmt="%.9g", delimiter=",")
    atomic.write_text(path, buf.getvalue())


def _stats(values: np.ndarray) -> dict[str, Any]:
    if not len(values):
        return {"mean": None, "min": None, "max": None, "final": None}
    return {"mean": _f(values.mean()), "min": _f(values.min()), "max": _f(values.max()),
            "final": _f(values[-1])}


def _step_section(level: Level, form: dict[str, Any] | None,
                  half: SceneRun | Ending | str) -> dict[str, Any]:
    """``closed_form_step``: the refinement of ``form`` by the run at half the step, or
    why there is none."""
    if isinstance(half, str):
        return scene_refine.skipped(half)
    if isinstance(half, Ending):
        return scene_refine.skipped(f"{half.reason} while running again at half the step")
    if half.ended is not None:
        return scene_refine.skipped(f"the run at half the step ended early "
                                    f"({half.ended.reason})")
    fine = scene_compare.compare(half.sim.config, half.log, half.start)
    if form is None or fine is None:
        return scene_refine.skipped("no closed-form figures to refine")
    return scene_refine.step_error(form, fine, level.sim.solver.dt)


def _write(level: Level, out_dir: Path, duration: float, run: SceneRun,
           snapshot: bool, half: SceneRun | Ending | str | None = None) -> Path:
    cfg = level.sim
    sim, log = run.sim, run.log
    written: list[str] = []
    write_failed: dict[str, str] = {}
    failed: dict[str, str] = {}
    probes: dict[str, Any] = {}
    for i, probe in enumerate(cfg.scene.probes):
        cols = log.columns(i)
        name = f"probe_{probe.name}.csv"
        try:
            _probe_csv(out_dir / name, cols)
            written.append(name)
        except OSError as exc:
            write_failed[name] = exc.strerror or str(exc)
        probes[probe.name] = {"kind": probe.kind, "point": probe.point, "file": name,
                              "columns": {c: _stats(v) for c, v in cols.items() if c != "t"}}
    summary = RunSummary(
        level=level.meta.name, kind="scene", duration_s=_f(sim.time),
        requested_duration_s=_f(duration), steps=int(round(sim.time / sim.dt)),
        links=sim.n, link_length=cfg.chain.link_length, dt=sim.dt, wall_s=_f(run.wall),
        realtime_factor=_f(sim.time / run.wall) if run.wall > 0 else None,
        scene=SceneFigures(pymunk_step=sim.scene.h, sample_interval_s=run.interval,
                           samples=log.n, seed=sim.config.scene.seed,
                           jitter=cfg.scene.jitter, probes=probes),
        sections={"closed_form": _attempt(failed, "closed form", scene_compare.compare, cfg,
                                          log, run.start)})
    if half is not None:
        summary.sections["closed_form_step"] = _attempt(
            failed, "closed form's step refinement", _step_section, level,
            summary.sections["closed_form"], half)
    if run.ended is not None:
        summary.ended_early = Ended(
            t_s=_f(sim.time), cause=run.ended.cause, reason=run.ended.reason,
            signal_number=int(run.ended.signum) if run.ended.signum is not None else None)
    elif isinstance(half, Ending):  # the command was stopped: it says so and exits so
        summary.ended_early = Ended(
            t_s=_f(sim.time), cause=half.cause, signal_number=int(half.signum or 2),
            reason=f"{half.reason} while running again at half the step: the run's own "
            "figures are complete, their step's error is not given")
    if snapshot:
        try:
            _figure(out_dir / "scene.png", level, run, summary)
            written.append("scene.png")
        except OSError as exc:
            write_failed["scene.png"] = exc.strerror or str(exc)
        except Exception as exc:  # noqa: BLE001 - a failed picture never loses the run
            failed["scene.png"] = f"{type(exc).__name__}: {exc}"
    summary.analysis_failed = failed
    summary.outputs = ["summary.json", *written]
    summary.write_failed = write_failed
    return files.write_summary(out_dir, summary, written)


def _figure(path: Path, level: Level, run: SceneRun, summary: RunSummary) -> None:
    """The chain at a few moments (left) and each probe against time (right)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    probes = level.sim.scene.probes
    rows = max(1, len(probes))
    fig = plt.figure(figsize=(10, max(4.0, 2.0 * rows)), dpi=100)
    grid = fig.add_gridspec(rows, 2, width_ratios=(1, 1.4))
    ax = fig.add_subplot(grid[:, 0])
    colors = plt.cm.viridis(np.linspace(0, 0.9, len(run.shapes)))
    for (t, pts), c in zip(run.shapes, colors, strict=True):
        ax.plot(pts[:, 0], pts[:, 1], "-", color=c, lw=1.2, label=f"t = {t:.3f} s")
    if level.sim.scene.floor == "solid":
        ax.axhline(level.sim.scene.floor_y, color="#555555", lw=2)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(fontsize=8, loc="best")
    ax.set_title(f"{level.meta.name}: the chain", fontsize=10)
    for i, probe in enumerate(probes):
        pax = fig.add_subplot(grid[i, 1])
        cols = run.log.columns(i)
        for c, v in cols.items():
            if c != "t":
                pax.plot(cols["t"], v, lw=1, label=c)
        pax.set_ylabel(f"{probe.name}\n({probe.kind})", fontsize=9)
        pax.legend(fontsize=7, loc="best")
        if i == len(probes) - 1:
            pax.set_xlabel("t (s)")
    form = summary.sections.get("closed_form") or {}
    note = f"{summary.links} links, dt {summary.dt * 1e6:.0f} us " \
           f"({summary.scene.pymunk_step * 1e6:.1f}-us pymunk steps)"
    if form.get("name"):
        errs = form.get("speed_rel_error") or [form.get("force_rel_error")]
        shown = ", ".join("n/a" if e is None else f"{100 * e:+.1f} %" for e in errs)
        note += f"; against {form['name']}: {shown}"
        step = summary.sections.get("closed_form_step") or {}
        key = "speed_rel_error" if form.get("speed_rel_error") else "force_rel_error"
        if key in step:
            half, bar = step[key]["half_step"], step[key]["gci"]
            half, bar = (half, bar) if isinstance(half, list) else ([half], [bar])
            note += f"\nat half the step ({step['half_dt'] * 1e6:g} us): " + ", ".join(
                "n/a" if h is None or b is None else f"{100 * h:+.1f} +- {100 * b:.1f} %"
                for h, b in zip(half, bar, strict=True)) + " (Roache's index)"
    fig.suptitle(note, fontsize=9)
    fig.tight_layout()
    with atomic.atomic_path(path) as tmp:
        fig.savefig(tmp)
    plt.close(fig)


def describe_scene(s: RunSummary, out: Path) -> str:
    """A few lines for the terminal about a scene run's summary ``s``."""
    sc = s.scene
    lines = [f"wrote {out}/" + ", ".join(s.outputs),
             f"  {s.links} links, {s.steps} steps of {s.dt * 1e6:g} us "
             f"({sc.pymunk_step * 1e6:.3g}-us pymunk steps), {sc.samples} samples every "
             f"{sc.sample_interval_s * 1e3:.3g} ms, real-time factor "
             f"{s.realtime_factor or 0:.2f}"]
    for name, why in s.write_failed.items():
        lines.append(f"  NOT WRITTEN: {name} ({why})")
    for name, why in s.analysis_failed.items():
        lines.append(f"  analysis failed: {name} ({why})")
    if s.ended_early is not None:
        lines.append(f"  ENDED EARLY (of {s.requested_duration_s:g} s asked for): "
                     f"{s.ended_early.reason}")
    form = s.sections.get("closed_form") or {}
    if form.get("name") == "folded_fall":
        for share, v, vt, ev, ef in zip(form["at_share"], form["speed_m_s"],
                                        form["speed_theory_m_s"], form["speed_rel_error"],
                                        form["force_rel_error"], strict=True):
            if v is None:
                lines.append(f"  folded fall at {100 * share:.0f} % of the length: not reached")
                continue
            lines.append(f"  folded fall at {100 * share:.0f} % of the length: free end "
                         f"{v:.3f} m/s (Calkin-March {vt:.3f}, {pct(ev)}), fixed end's force "
                         f"{pct(ef)}")
    elif form.get("name") == "scale" and form.get("force_rel_error") is None:
        lines.append(f"  scale: not compared; the run ended before "
                     f"{100 * form['landed_share'][1]:.0f} % of the chain had landed")
    elif form.get("name") == "scale":
        lines.append(f"  scale while {100 * form['landed_share'][0]:.0f}-"
                     f"{100 * form['landed_share'][1]:.0f} % of the chain has landed: reads "
                     f"{pct(form['force_rel_error'])} against 3 lambda g y (Hamm-Geminard)"
                     + ("; a pile of jittered links is chaotic: compare the mean over seeds "
                        "(chainfountain sweep with seeds)"
                        if sc.jitter and "closed_form_step" not in s.sections else ""))
    lines.extend(_step_lines(s.sections.get("closed_form_step"), form, sc.pymunk_step))
    return "\n".join(lines)


def _step_lines(step: dict[str, Any] | None, form: dict[str, Any],
                pymunk_step: float) -> list[str]:
    """The closed form's figures at half the step with their bars (Roache's index) and at
    zero step, from ``closed_form_step``."""
    if not step or not form.get("name"):
        return []
    if step.get("skipped"):
        import textwrap

        return textwrap.wrap(f"the step's error: not refined: {step['skipped']}", 96,
                             initial_indent="  ", subsequent_indent="    ")

    def row(key: str) -> str | None:
        half, bar, zero = (step[key][k] for k in ("half_step", "gci", "zero_step"))
        if not isinstance(half, list):
            half, bar, zero = [half], [bar], [zero]
        if all(z is None for z in zero):
            return None
        shown = ", ".join("n/a" if h is None or b is None else f"{100 * h:+.2f} +- {100 * b:.2f}"
                          for h, b in zip(half, bar, strict=True))
        at_zero = "/".join("n/a" if z is None else f"{100 * z:+.2f}" for z in zero)
        return f"{shown} % (at zero step {at_zero} %)"

    names = {"speed_rel_error": "free end's speed", "force_rel_error": "fixed end's force"
             if form["name"] == "folded_fall" else "scale"}
    rows = [(name, row(key)) for key, name in names.items() if key in step]
    rows = [(name, r) for name, r in rows if r is not None]
    if not rows:
        return []
    return [f"  at half the step ({step['half_dt'] * 1e6:g} us, pymunk steps of "
            f"{pymunk_step / 2 * 1e6:.3g} us), each with its bar (Roache's index):",
            *(f"    {name}: {r}" for name, r in rows)]
