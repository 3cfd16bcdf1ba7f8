"""The ``summary.json`` object of a headless run: figures over the steady window and the
paper's prediction with relative errors."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from chainfountain.level.io import Level
from chainfountain.sim.machine_rules import keeps_any_speed
from chainfountain.sim.measure import Summary
from chainfountain.sim.recorder import Recorder
from chainfountain.sim.reference import LaunchReference
from chainfountain.sim.world import Simulation


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
    # steady: the run's last averaging window (``recording.window``) is the reference, so a
    # fountain that formed from its stub is steady from when it formed
    steady = _attempt(failed, "steady-state detection", rec.steady_from)
    window_start = steady if steady is not None else max(0.0, sim.time - rec.cfg.window)
    s = _attempt(failed, "window averages", rec.summary, sim.time - window_start)
    if s is None:
        return {"level": level.meta.name, "kind": level.sim.kind, "duration_s": _f(sim.time),
                "requested_duration_s": _f(duration), "steps": sim.steps,
                "links": sim.n_links, "dt": sim.dt, "wall_s": _f(wall), "steady": False,
                "theory": None, "analysis_failed": failed}
    failed.update(s.failed)
    ref = sim.reference
    neutral = keeps_any_speed(level.sim)
    if neutral:
        ref = sim.reference_at(s.speed_mean)  # it keeps any speed: the paper's at its own
    tb = s.extras.get("tension_bar")
    TE_bar = float(tb[-1]) if tb is not None and len(tb) else float("nan")
    speed_cv = s.speed_uniformity
    app = sim.apparatus
    H = sim.drop
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
    out["theory"] = _theory(ref, s, TE_bar) if ref is not None else None
    if level.sim.kind == "feed" and level.sim.feed.drive != "motor":
        # what sets the speed: the machine's laws select it, or (loss-free) keep any
        out["machine"] = "keeps any speed" if neutral else "selects"
    if sim.slide_away is not None:
        # the paper's non-stationary arrangement: its measurement is the reaction's rate
        from chainfountain.sim.slide_away_report import report as open_report

        rep = _attempt(failed, "open report", open_report, rec.samples,
                       sim.piston.hand_over, level.sim.chain.linear_density, sim.g,
                       ref.v if ref is not None else math.nan)
        if rep is not None:
            out["open"] = json_safe(rep)
    if sim.beaker is not None:
        from chainfountain.sim.beaker_report import report as beaker_report

        rep = _attempt(failed, "beaker report", beaker_report, sim.beaker,
                       (s.vertex_x, s.vertex_y), s.landing_x, s.t0, s.t1, sim.g)
        if rep is not None:
            out["beaker"] = json_safe(rep)
    if app is not None:
        from chainfountain.sim.apparatus_report import report

        rep = _attempt(failed, "apparatus report", report, sim, rec, s.t0, s.t1)
        if rep is not None:
            out["TE_bar"] = _f(rep["measured"]["TE_bar"])
            out["apparatus"] = json_safe(rep)
    out["analysis_failed"] = failed
    return out


def _theory(ref: LaunchReference, s: Summary, TE_bar: float) -> dict[str, Any]:
    """``summary.json``'s ``theory``: the paper's fountain for this feed and the window's
    errors against it (:class:`~chainfountain.sim.reference.LaunchReference`)."""
    errs = s.errors(ref)
    return {
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


def json_safe(obj: Any) -> Any:
    """Nested dict/list with NaN/inf as null (for the apparatus report and converge.json)."""
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [json_safe(v) for v in obj]
    if isinstance(obj, bool) or obj is None or isinstance(obj, str):
        return obj
    return _f(obj)


def model_error(level: Level) -> dict[str, Any]:
    """``summary.json``'s ``error_model``: what the error model
    (:mod:`chainfountain.sim.accuracy`) says about a fed level's settings, or why it says
    nothing."""
    from chainfountain.sim import accuracy

    sim = level.sim
    out: dict[str, Any] = {"source": "error model (chainfountain.sim.accuracy, fitted by "
                           "research/error_model.py)", "bounds": None}
    f = sim.feed
    if f.floor != "absorbing" or sim.rollers or sim.carts:
        out["why_none"] = ("the model covers fed fountains on an absorbing floor only; "
                           "use chainfountain converge LEVEL")
        return out
    if f.drive != "motor":
        out["note"] = ("the flying chain's error at the machine's speed; a machine's speed "
                       "moves besides (research/ideal_machine_holds.py)")
    try:
        ref = LaunchReference.of_level(sim)
    except ValueError as exc:
        out["why_none"] = f"no fountain: {exc}"
        return out
    why = accuracy.in_domain(ref)
    if why is not None:
        out["why_none"] = why
        return out
    sv = sim.solver
    est = accuracy.estimate(ref, accuracy.Settings(sim.chain.link_length, sv.dt / sv.substeps,
                                                   sv.iterations))
    out["links_in_flight"] = est.links
    out["solver_converged"] = est.converged
    out["iterations_needed"] = accuracy.iterations_needed(est.links, sv.dt / sv.substeps)
    if not est.converged:
        out["why_none"] = (f"the solver does not converge on {est.links} links at "
                           f"{sv.iterations} iterations (needs {out['iterations_needed']}): the "
                           "fountain may sit up to a few per cent low; raise solver.iterations "
                           "or set solver.accuracy")
        return out
    names = {"vertex_y": "h", "vertex_x": "vertex_x", "landing_x": "l"}
    out["predicted"] = {names[k]: _f(v) for k, v in est.errors.items()}
    out["bounds"] = {names[k]: _f(v) for k, v in est.bounds.items()}
    return out
