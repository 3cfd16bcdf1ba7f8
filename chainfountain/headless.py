"""Headless runs: step a level without a window, record, compare with theory, write files.

Outputs (all written atomically into the output folder):

- ``summary.json``: headline measurements over the steady window and the
  paper's prediction with relative errors;
- ``tensions.csv``: time, joint index, arc length, x, y, signed tension (N),
  scaled tension, decimated to at most ``MAX_TENSION_SAMPLES`` time samples;
- ``speed.csv``: one row per recorded sample (speed, vertex, stretch, ...);
- ``snapshot.png``: the chain at the end with the predicted catenary (metres);
- apparatus levels: ``apparatus.csv``, one row per recorded apparatus sample (roller
  speeds, end tensions, cart forces, the lower plate's reaction, ...);
- the 'open' arrangement: ``reaction.png``, the lower plate's reaction against time
  with the paper's rate.

``summary.json`` lists the files written under ``outputs``.
"""

from __future__ import annotations

import contextlib
import csv
import dataclasses
import io as _io
import json
import math
import shutil
import signal
import sys
import textwrap
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from chainfountain import atomic
from chainfountain.errors import OutputError, RunEnded, UserError
from chainfountain.level.io import Level
from chainfountain.sim.recorder import Recorder
from chainfountain.sim.world import Simulation
from chainfountain.theory.apparatus import plate_reaction

MAX_TENSION_SAMPLES = 200
MAX_PROFILES = 2000
"""Per-link profiles kept in memory by a headless run (thinned evenly beyond; 40 s at 50 Hz)."""
MAX_SAMPLES = 100_000
"""Scalar samples kept by a headless run (thinned evenly beyond: 1000 s at 100 Hz)."""
DEFAULT_DURATION = 8.0
"""Simulated seconds of a headless run when none is given."""
FORMING_DURATION = 20.0
"""... of a fed level that starts from its stub: the shipped ones are steady after 4-12 s."""
DEFAULT_OUTPUTS = ("summary.json", "tensions.csv", "speed.csv", "snapshot.png")
"""What every run writes (``summary.json`` lists its own files under ``outputs``)."""
LOG_PROGRESS_EVERY = 30.0
"""Wall seconds between progress lines when stderr is not a terminal (a log file)."""


def default_duration(level: Level) -> float:
    """Simulated seconds of a headless run of ``level`` when none is given:
    :data:`DEFAULT_DURATION`; :data:`FORMING_DURATION` for a fed level that starts from its
    stub, so that it forms and is then averaged; an apparatus level's own
    ``apparatus.duration`` when its upper table is sized by it (no treadmill), so the run
    ends before the table does."""
    sim = level.sim
    if sim.kind == "apparatus" and sim.apparatus.plate_links == 0:
        return float(sim.apparatus.duration)
    if sim.kind == "feed" and sim.initial.mode == "stub":
        return FORMING_DURATION
    return DEFAULT_DURATION


def default_out_dir(level: Level) -> Path:
    """Where a headless run of ``level`` writes by default: ``./runs/<name>``."""
    from chainfountain.level.library import safe_name

    return Path("runs") / safe_name(level.meta.name)


class _LogProgress:
    """Progress for a log file (stderr not a terminal): one line at most every
    :data:`LOG_PROGRESS_EVERY` wall seconds, so a long run in a batch job is not silent."""

    def __init__(self, total: float, label: str) -> None:
        self.total, self.label = total, label
        self.n = 0.0
        self.t0 = self.last = time.perf_counter()

    def update(self, dn: float) -> None:
        self.n += dn
        now = time.perf_counter()
        if now - self.last < LOG_PROGRESS_EVERY:
            return
        self.last = now
        el = now - self.t0
        left = el * (self.total - self.n) / self.n if self.n > 0 else math.nan
        print(f"  {self.label}: {self.n:.2f}/{self.total:.2f} sim s "
              f"({100 * self.n / self.total:.0f} %), {el:.0f} s elapsed, about {left:.0f} s left",
              file=sys.stderr, flush=True)

    def __enter__(self) -> _LogProgress:
        return self

    def __exit__(self, *exc: object) -> None:
        return None


def _progress(total: float, enabled: bool, label: str = "run"):
    """A tqdm bar on a terminal, :class:`_LogProgress` lines otherwise, nothing if disabled."""
    from tqdm import tqdm

    if enabled and not sys.stderr.isatty():
        return _LogProgress(total, label)
    return tqdm(total=round(total, 3), unit="sim s", disable=not enabled,
                bar_format="{l_bar}{bar}| {n:.2f}/{total:.2f} sim s [{elapsed}<{remaining}]",
                file=sys.stderr, leave=False)


class Interrupted(Exception):
    """SIGINT (Ctrl-C) or SIGTERM arrived while a headless run was simulating."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


@dataclass
class Ending:
    """Why a run stopped before its duration."""

    cause: str
    """``"machine"`` (the apparatus cannot go on), ``"diverged"`` (the watchdog) or
    ``"interrupted"`` (a signal)."""
    reason: str
    signum: int | None = None


@contextlib.contextmanager
def _signals_raise() -> Iterator[None]:
    """While simulating, SIGINT and SIGTERM raise :class:`Interrupted` (main thread only)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum: int, frame: object) -> None:
        raise Interrupted(signum)

    old = {sig: signal.signal(sig, handler) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for sig, h in old.items():
            signal.signal(sig, h)


@contextlib.contextmanager
def _signals_deferred(received: list[int]) -> Iterator[None]:
    """While the outputs are written, a signal is noted in ``received`` (and said), not
    obeyed, so no output is left half-written; the caller exits afterwards."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum: int, frame: object) -> None:
        received.append(signum)
        print(f"chainfountain: {signal.Signals(signum).name}: finishing the outputs first",
              file=sys.stderr, flush=True)

    old = {sig: signal.signal(sig, handler) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for sig, h in old.items():
            signal.signal(sig, h)


def simulate(level: Level, duration: float, *, seed: int | None = None,
             progress: bool = True) -> tuple[Simulation, Recorder, float, Ending | None]:
    """Build and run a level for ``duration`` simulated seconds.

    Returns sim, recorder, wall seconds and why the run ended early (a
    :class:`~chainfountain.errors.RunEnded`: a table used up, the fold collapsed, the
    watchdog; or SIGINT/SIGTERM), or None if it ran for the whole ``duration``."""
    from chainfountain.sim.watchdog import Diverged

    sim_cfg = level.sim
    if seed is not None:
        sim_cfg = dataclasses.replace(
            sim_cfg, initial=dataclasses.replace(sim_cfg.initial, seed=int(seed)))
    sim = Simulation(sim_cfg)
    rec = Recorder(sim, max_profiles=MAX_PROFILES, max_samples=MAX_SAMPLES)
    n_steps = int(round(duration / sim.dt))
    chunk = max(1, int(round(0.05 / sim.dt)))
    t0 = time.perf_counter()
    ended: Ending | None = None
    with _progress(duration, progress, level.meta.name) as bar, _signals_raise():
        done = 0
        step = sim.step
        try:
            while done < n_steps:
                m = min(chunk, n_steps - done)
                for _ in range(m):
                    step()
                done += m
                bar.update(m * sim.dt)
                if done % (20 * chunk) < chunk:  # analyse as we go: raw states are large
                    rec.samples  # noqa: B018 - property access processes the raw samples
        except Diverged as exc:
            ended = Ending("diverged", str(exc))
        except RunEnded as exc:
            ended = Ending("machine", str(exc))
        except (Interrupted, KeyboardInterrupt) as exc:
            signum = exc.signum if isinstance(exc, Interrupted) else signal.SIGINT
            ended = Ending("interrupted", f"interrupted by {signal.Signals(signum).name} at "
                           f"t = {sim.time:.3f} s", signum)
    wall = time.perf_counter() - t0
    return sim, rec, wall, ended


def _f(x: Any) -> Any:
    """JSON-safe float (NaN/inf become null)."""
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def _attempt(failed: dict[str, str], name: str, fn: Callable[..., Any], *args: Any,
             default: Any = None) -> Any:
    """``fn(*args)``, or ``default`` with the failure noted under ``name``: an analysis
    after the simulation must never lose the run."""
    try:
        return fn(*args)
    except Exception as exc:  # noqa: BLE001 - reported by name in summary.json
        failed[name] = f"{type(exc).__name__}: {exc}"
        return default


def summarize(level: Level, sim: Simulation, rec: Recorder, duration: float,
              wall: float) -> dict[str, Any]:
    """The ``summary.json`` object. Analyses that fail are listed under
    ``analysis_failed`` (name: reason) and their figures are null."""
    failed: dict[str, str] = {}
    steady = _attempt(failed, "steady-state detection", rec.steady_from, duration)
    window_start = steady if steady is not None else max(0.0, sim.time - rec.cfg.window)
    s = _attempt(failed, "window averages", rec.summary, sim.time - window_start)
    if s is None:
        return {"level": level.meta.name, "kind": level.sim.kind, "duration_s": _f(sim.time),
                "requested_duration_s": _f(duration), "steps": sim.steps,
                "links": sim.n_links, "dt": sim.dt, "wall_s": _f(wall), "steady": False,
                "theory": None, "analysis_failed": failed}
    failed.update(s.failed)
    ref = sim.reference
    tb = s.extras.get("tension_bar")
    TE_bar = float(tb[-1]) if tb is not None and len(tb) else float("nan")
    speed_cv = s.speed_uniformity
    app = sim.apparatus
    H = level.sim.apparatus.drop if app is not None else level.sim.feed.drop
    out: dict[str, Any] = {
        "level": level.meta.name,
        "kind": level.sim.kind,
        "duration_s": _f(sim.time),
        "requested_duration_s": _f(duration),
        "steps": sim.steps,
        "links": sim.n_links,
        "links_free": sim.n_free,
        "link_length": level.sim.chain.link_length,
        "dt": sim.dt,
        "wall_s": _f(wall),
        "realtime_factor": _f(sim.time / wall) if wall > 0 else None,
        "steady": steady is not None,
        "steady_since_s": _f(steady),
        "window": [_f(s.t0), _f(s.t1)],
        "samples": s.samples,
        "speed_mean": _f(s.speed_mean),
        "speed_cv": _f(speed_cv),
        "speed_spread": _f(s.speed_spread_inst),
        "max_stretch": _f(s.stretch_max),
        "vertex": [_f(s.vertex_x), _f(s.vertex_y)],
        "start": [0.0, 0.0],
        "end": [_f(s.landing_x), _f(-H)],
        "h": _f(s.vertex_y),
        "l": _f(s.landing_x),
        "H": H,
        "q_fit": _f(s.q_fit),
        "k": _f(sim.g / s.speed_mean**2) if s.speed_mean > 0 else None,
        "T0_bar": _f(s.T0_bar),
        "TE_bar": _f(TE_bar),
        "tension_rms": _f(s.tension_rms),
    }
    if ref is not None:
        errs = s.errors(ref)
        out["theory"] = {
            "h": ref.h,
            "vertex": [ref.x_rise, ref.h],
            "l": ref.landing_x,
            "q": ref.q,
            "k": ref.k,
            "v": ref.v,
            "T0_bar": ref.T0_bar,
            "TE_bar": ref.TE_bar,
            "rel_error": {
                "h": _f(errs["vertex_y"]),
                "vertex_x": _f(errs["vertex_x"]),
                "l": _f(errs["landing_x"]),
                "q": _f(errs["q"]),
                "speed": _f(errs["speed"]),
            },
            "abs_error": {
                "T0_bar": _f(errs["T0_bar"]),
                "TE_bar": _f(TE_bar - ref.TE_bar),
                "tension_rms": _f(s.tension_rms),
            },
        }
    else:
        out["theory"] = None
    if app is not None:
        from chainfountain.sim.apparatus_report import report

        rep = _attempt(failed, "apparatus report", report, sim, rec, s.t0, s.t1)
        if rep is not None:
            out["TE_bar"] = _f(rep["measured"]["TE_bar"])
            out["apparatus"] = json_safe(rep)
    out["analysis_failed"] = failed
    return out


def json_safe(obj: Any) -> Any:
    """Nested dict/list with NaN/inf as null (for the apparatus report and converge.json)."""
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [json_safe(v) for v in obj]
    if isinstance(obj, bool) or obj is None or isinstance(obj, str):
        return obj
    return _f(obj)


def _write_tensions(path: Path, rec: Recorder, lam: float) -> None:
    profs = rec.profiles
    samples = rec.samples
    if not profs:
        atomic.write_text(path, "t,joint,s,x,y,tension_N,tension_bar\n")
        return
    idx = np.unique(np.linspace(0, len(profs) - 1, min(MAX_TENSION_SAMPLES, len(profs)))
                    .round().astype(int))
    buf = _io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["t", "joint", "s", "x", "y", "tension_N", "tension_bar"])
    t_samples = np.array([smp.t for smp in samples])
    for i in idx:
        p = profs[i]
        smp = samples[int(np.argmin(np.abs(t_samples - p.t)))]
        v = smp.speed_mean if smp.speed_mean > 0 else 1.0
        xy = np.column_stack([p.x, p.y])
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))])
        scale = lam * v * v
        for j in range(len(p.tension_bar)):
            w.writerow([f"{smp.t:.6g}", j, f"{s[j]:.6g}", f"{p.x[j]:.6g}", f"{p.y[j]:.6g}",
                        f"{p.tension_bar[j] * scale:.6g}", f"{p.tension_bar[j]:.6g}"])
    atomic.write_text(path, buf.getvalue())


def _write_samples(path: Path, samples: list) -> None:
    """One row per recorded sample (a dataclass), one column per field."""
    buf = _io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    cols = [f.name for f in dataclasses.fields(samples[0])] if samples else ["t"]
    w.writerow(cols)
    for smp in samples:
        w.writerow([f"{getattr(smp, c):.6g}" for c in cols])
    atomic.write_text(path, buf.getvalue())


def write_reaction_figure(path: Path, rec: Recorder, summary: dict[str, Any],
                          lam: float, g: float, title: str) -> None:
    """'open' arrangement: the lower plate's reaction force against time, with the
    paper's rate ``lambda g v`` integrated over the measured speed from the first sample
    (the paper: "the reaction force change is exactly known over time")."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    S = rec.apparatus_samples
    t = np.array([x.t for x in S], dtype=float)
    R = np.array([x.tail_reaction for x in S], dtype=float)
    v = np.array([x.v for x in S], dtype=float)
    ok = np.isfinite(R) & np.isfinite(v)
    t, R, v = t[ok], R[ok], v[ok]
    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=100)
    ax.plot(t, R, ".", ms=3, color="#333333", label="measured (each sample)")
    if len(t) > 1:
        ax.plot(t, plate_reaction(t, v, float(R[0]), lam, g), "--", color="#d62728", lw=1.4,
                label="lambda g v (paper), from the first sample")
    o = (summary.get("apparatus") or {}).get("open") or {}
    rate, pred = o.get("tail_reaction_rate_N_per_s"), o.get("tail_reaction_rate_predicted")
    if rate is not None and pred is not None:
        w0, w1 = summary["apparatus"]["window"]
        ax.text(0.02, 0.97, f"rate over {w0:.2g}-{w1:.2g} s: {rate:.3f} N/s measured "
                f"(Theil-Sen), {pred:.3f} N/s = lambda g v ({100 * (rate / pred - 1):+.1f} %)",
                transform=ax.transAxes, va="top", fontsize=8)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("lower plate reaction (N)")
    ax.grid(alpha=0.3)
    ax.set_ylim(bottom=0.0)
    _save_png(fig, ax, path, title, legend="lower right")


def write_snapshot(path: Path, sim: Simulation, summary: dict[str, Any], title: str) -> None:
    """The chain at the end of the run over the predicted catenary, axes in metres."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pts = sim.chain_polyline()
    fig, ax = plt.subplots(figsize=(6.4, 6.4), dpi=100)
    ax.plot(pts[:, 0], pts[:, 1], "-", color="#333333", lw=1.6, label="simulated chain")
    ref = sim.reference
    if ref is not None:
        x = np.linspace(0.0, ref.landing_x, 300)
        ax.plot(x, ref.y_of_x(x), "--", color="#d62728", lw=1.2,
                label=f"inverted catenary (theory), q = {ref.q:.3g} 1/m")
        ax.plot(*ref.vertex, "x", color="#d62728", ms=9, mew=2, label="predicted vertex")
    vx, vy = summary["vertex"]
    if vx is not None and vy is not None:
        ax.plot(vx, vy, "o", mfc="none", color="#1f77b4", ms=9, mew=1.5,
                label="measured vertex (window mean)")
    fy, fx0, fx1, mode = sim.floor_geometry()
    app = sim.apparatus
    if mode != "none":
        ax.plot([fx0, fx1], [fy, fy], color="#8c564b", lw=3, label=f"{mode} floor")
    if app is not None and app.floor_depth > 0:
        ex = app.end[0]
        ax.plot([ex - 0.3, ex + 0.3], [-app.H, -app.H], ":", color="#7f7f7f", lw=1.5,
                label=f"fountain end height (Tbar_E read here; floor {app.floor_depth:.3g} m "
                "lower)")
    if app is None:
        (gx, gy), (ux, uy) = sim.guide_geometry()
        ax.plot([gx - 0.15 * ux, gx], [gy - 0.15 * uy, gy], color="#2ca02c", lw=4,
                label="feed guide")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.grid(alpha=0.3)
    if app is not None:
        # the fountain and the guides, not the metres of table on either side (a tall,
        # narrow fountain such as the paper's D ends well before 2.4 H)
        H = app.H
        ax.set_xlim(-0.6, max(1.2, min(2.4 * H, app.end[0] + 1.0)))
        ax.set_ylim(min(-H - 0.4, app.floor_y - 0.1), max(0.3, 0.6 * H))
    else:
        xs = np.concatenate([pts[:, 0], [fx0, fx1]]) if ref is None else pts[:, 0]
        ax.set_xlim(min(xs.min(), -0.2) - 0.1, max(xs.max(), 0.2) + 0.1)
    _save_png(fig, ax, path, title)


def _save_png(fig, ax, path: Path, title: str, legend: str = "best") -> None:
    """Title and legend, then the figure as PNG, atomically; closes it."""
    import matplotlib.pyplot as plt

    ax.set_title(title, fontsize=10)
    ax.legend(loc=legend, fontsize=8, framealpha=0.9)
    fig.tight_layout()
    with atomic.atomic_path(path) as tmp:
        fig.savefig(tmp, format="png")
    plt.close(fig)


EXIT_STATUS = {None: 0, "machine": 3, "diverged": 3}
"""Exit status of ``chainfountain run`` by :attr:`Ending.cause` (see :func:`exit_status`)."""


def exit_status(summary: dict[str, Any]) -> int:
    """0 for a complete run; 3 if it ended early (the machine stopped, the run diverged);
    128 + the signal's number (130 for Ctrl-C, 143 for SIGTERM) if it was interrupted;
    4 if an output could not be written. The outputs cover the part simulated."""
    if summary.get("write_failed"):
        return 4
    ended = summary.get("ended_early")
    if not ended:
        return 0
    if ended.get("cause") == "interrupted":
        return 128 + int(ended.get("signal_number") or signal.SIGINT)
    return EXIT_STATUS.get(ended.get("cause"), 3)


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
              error_bars: dict | None = None) -> Path:
    """Run ``level`` headless and write the outputs into ``out_dir``; returns summary.json.

    Raw outputs (the CSVs) are written before the analyses that could fail (figures,
    fits); a failed analysis is named in ``summary.json`` (``analysis_failed``) and the
    rest is still written. SIGINT or SIGTERM while simulating ends the run like a
    stopped machine: its part is written completely (a second signal while writing is
    noted, not obeyed). :func:`exit_status` gives the command's status. Raises
    :class:`OutputError` when ``summary.json`` itself cannot be written. ``error_bars``
    (:meth:`chainfountain.refine.Refinement.as_dict`) goes into ``summary.json`` as is."""
    duration = default_duration(level) if duration is None else float(duration)
    out_dir = prepare_out_dir(out_dir)
    sim, rec, wall, ended = simulate(level, duration, seed=seed, progress=progress)
    received: list[int] = []
    with _signals_deferred(received):
        path = _write_outputs(level, out_dir, duration, sim, rec, wall, ended, error_bars)
    return path


def _write_outputs(level: Level, out_dir: Path, duration: float, sim: Simulation,
                   rec: Recorder, wall: float, ended: Ending | None,
                   error_bars: dict | None = None) -> Path:
    """Every output of a finished (or stopped) run, raw data first; see :func:`run_level`."""
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

    put("speed.csv", _write_samples, _attempt(analysis_failed, "samples",
                                              lambda: rec.samples, default=[]))
    if app is not None:
        put("apparatus.csv", _write_samples, _attempt(
            analysis_failed, "apparatus samples", lambda: rec.apparatus_samples, default=[]))
    put("tensions.csv", _write_tensions, rec, lam)
    summary = summarize(level, sim, rec, duration, wall)
    summary["ended_early"] = None
    if level.sim.kind == "feed":
        summary["error_bars"] = json_safe(error_bars) if error_bars is not None else {
            "method": None, "how": "not estimated: chainfountain run LEVEL --error-bars, or "
            "chainfountain converge LEVEL"}
    if ended is not None:
        summary["ended_early"] = {"t_s": _f(sim.time), "cause": ended.cause,
                                  "reason": ended.reason}
        if ended.signum is not None:
            summary["ended_early"]["signal_number"] = int(ended.signum)
        if ended.cause == "machine" and app is not None and app.fold_guided:
            # when the fountain last landed in the end guide's mouth (a lost catch comes
            # about 1 s before the fold's collapse)
            summary["ended_early"]["last_mouth_entry_s"] = _f(app.last_mouth_entry)
    title = (f"{level.meta.name}: t = {sim.time:.2f} s, "
             f"v = {summary.get('speed_mean') or 0:.3f} m/s"
             + ("" if summary.get("steady") else " (not steady)")
             + ("" if ended is None else " - ended early"))
    if "vertex" in summary:
        put("snapshot.png", write_snapshot, sim, summary, title)
    if app is not None and app.variant == "open" and "apparatus" in summary:
        put("reaction.png", write_reaction_figure, rec, summary, lam, level.sim.gravity, title)
    summary["analysis_failed"].update(analysis_failed)
    order = ["summary.json", *DEFAULT_OUTPUTS[1:], "apparatus.csv", "reaction.png"]
    summary["outputs"] = sorted(["summary.json", *written], key=order.index)
    summary["write_failed"] = write_failed
    path = out_dir / "summary.json"
    try:
        atomic.write_text(path, json.dumps(summary, indent=2) + "\n")
    except OSError as exc:
        raise OutputError(f"cannot write {path} ({exc.strerror or exc}); the run's other "
                          f"outputs: {', '.join(written) or 'none'}") from None
    return path


def describe_outputs(summary_path: Path) -> str:
    """A few lines for the terminal: what was written and how the run compares with theory."""
    summary_path = Path(summary_path)
    out = summary_path.parent
    s = json.loads(summary_path.read_text())
    th = s.get("theory") or {}
    err = th.get("rel_error", {})

    def pct(x: float | None) -> str:
        return "n/a" if x is None else f"{100 * x:+.2f} %"

    steady = (f"steady since {s['steady_since_s']:.2f} s" if s.get("steady")
              else "never steady (compare with care)")
    o = (s.get("apparatus") or {}).get("open")
    if o:
        # the paper's non-stationary arrangement: its measurement is the reaction's rate
        rate, pred = o.get("tail_reaction_rate_N_per_s"), o.get("tail_reaction_rate_predicted")
        steady = "non-stationary by design"
        if rate is not None and pred:
            steady += (f"; lower plate reaction grows at {rate:.3f} N/s, lambda g v "
                       f"{pred:.3f} N/s ({pct(rate / pred - 1.0)})")
    lines = [
        f"wrote {out}/" + ", ".join(s.get("outputs") or DEFAULT_OUTPUTS),
        f"  {s['links']} links, {s['steps']} steps, real-time factor "
        f"{s.get('realtime_factor') or 0:.2f}, {steady}",
    ]
    for name, why in (s.get("write_failed") or {}).items():
        lines.append(f"  NOT WRITTEN: {name} ({why})")
    for name, why in (s.get("analysis_failed") or {}).items():
        lines.append(f"  analysis failed: {name} ({why}); its figures are null")
    ended = s.get("ended_early")
    if ended:
        # the reason runs to several sentences (a fold's collapse: about 900 characters):
        # wrapped to the terminal, continuation lines indented under it
        width = max(60, min(100, shutil.get_terminal_size((100, 24)).columns - 1))
        lines.append(textwrap.fill(
            f"ENDED EARLY (of {s['requested_duration_s']:g} s asked for): {ended['reason']}",
            width=width, initial_indent="  ", subsequent_indent="    ",
            break_on_hyphens=False))
    if th and s.get("h") is not None and s.get("l") is not None:
        lines.append(
            f"  vertex height {s['h']:.4f} m (theory {th['h']:.4f}, {pct(err.get('h'))}), "
            f"landing {s['l']:.4f} m (theory {th['l']:.4f}, {pct(err.get('l'))}), "
            f"speed {s['speed_mean']:.4f} m/s")
    d = (s.get("error_bars") or {}).get("error_bar")
    if d:
        def bar(x: float | None) -> str:
            return "n/a" if x is None else f"+-{100 * x:.2f} %"

        lines.append(
            f"  discretisation error bars at this link length and step (refinement): vertex "
            f"height {bar(d.get('h'))}, vertex x {bar(d.get('vertex_x'))}, landing "
            f"{bar(d.get('l'))}")
    return "\n".join(lines)
