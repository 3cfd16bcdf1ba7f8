"""The ``summary.json`` object of a headless run (:class:`~chainfountain.headless.report.
RunSummary`): figures over the steady window, and the sections the level's kind adds,
each built by one function of :data:`SECTIONS`."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from chainfountain.headless.report import (
    AbsErrors,
    FountainFigures,
    RelErrors,
    Remeasured,
    RunSummary,
    Theory,
    finite,
    json_safe,
)
from chainfountain.level.io import Level
from chainfountain.sim.kinds import kind_of
from chainfountain.sim.machine_rules import keeps_any_speed
from chainfountain.sim.measure import Summary
from chainfountain.sim.recorder import Recorder
from chainfountain.sim.reference import LaunchReference
from chainfountain.sim.stiff_reference import Prediction, Reference, StiffReference
from chainfountain.sim.world import Simulation

_f = finite
"""JSON-safe float (NaN/inf become null); the name other modules import."""

SectionBuilder = Callable[[Level, Simulation, Recorder, "Summary | None"], Any]
"""A section of ``summary.json``: ``(level, sim, recorder, window)`` to the section's
object (a typed part, a JSON-ready dict or text, a
:class:`~chainfountain.headless.report.Remeasured`), or ``None`` when the run has none.
``window`` is the recorder's :class:`~chainfountain.sim.measure.Summary` over the
averaging window (``None`` when it could not be computed)."""


def _attempt(failed: dict[str, str], name: str, fn: Callable[..., Any], *args: Any,
             default: Any = None) -> Any:
    """``fn(*args)``, or ``default`` with the failure noted under ``name``: an analysis
    after the simulation must never lose the run."""
    try:
        return fn(*args)
    except Exception as exc:  # noqa: BLE001 - reported by name in summary.json
        failed[name] = f"{type(exc).__name__}: {exc}"
        return default


def _prediction(level: Level, sim: Simulation, s: Summary) -> Prediction:
    """The theory the window is compared with: the level's, or for a machine that keeps
    any speed the one at the window's own speed."""
    if keeps_any_speed(level.sim):
        return sim.predict_at(s.speed_mean)
    return Prediction(sim.reference, sim.catenary, sim.reference_note)


def _reference(level: Level, sim: Simulation, s: Summary) -> Reference | None:
    """The theory's fountain the window is compared with (:func:`_prediction`)."""
    return _prediction(level, sim, s).reference


def _tension_end(s: Summary) -> float:
    """The window's scaled end tension: the last joint of its mean ``Tbar`` profile."""
    tb = s.extras.get("tension_bar")
    return float(tb[-1]) if tb is not None and len(tb) else float("nan")


def _joints(level: Level, v: float, cat: LaunchReference) -> dict[str, Any]:
    """A stiff chain's joints, physical and scaled at speed ``v``
    (:func:`~chainfountain.theory.stiff.scaled_stiffness`, :func:`~chainfountain.theory.
    stiff.scaled_damping`), with the damper's decay over the catenary's flight and whether
    it settles (:func:`~chainfountain.theory.stiff.damper_decay`, ``docs/stiff_stability.md``;
    ``damper_decay`` ``None``: no standing waves to decay)."""
    from chainfountain.theory.stiff import (
        SETTLES_AT,
        damper_decay,
        scaled_damping,
        scaled_stiffness,
    )

    ch = level.sim.chain
    c, d, L, lam = ch.bending_stiffness, ch.bending_damping, ch.link_length, ch.linear_density
    e, delta = scaled_stiffness(c, L, lam, v), scaled_damping(d, L, lam, v)
    decay = damper_decay(e, delta, cat.arc_length, 0.5 * (cat.T0_bar + cat.TE_bar))
    return {"c": finite(c), "d": finite(d), "e": finite(e), "delta": finite(delta),
            "damper_decay": finite(decay) if math.isfinite(decay) else None,
            "settles": bool(decay >= SETTLES_AT)}


def _beside(cat: LaunchReference, s: Summary) -> dict[str, Any]:
    """The catenary's figures and the window's errors against them, beside a stiff
    chain's theory."""
    errs = s.errors(cat)
    return {"h": finite(cat.h), "vertex_x": finite(cat.x_rise), "l": finite(cat.landing_x),
            "q": finite(cat.q), "T0_bar": finite(cat.T0_bar),
            "rel_error": {k: finite(errs[k]) for k in ("h", "vertex_x", "l")}}


def theory_section(level: Level, sim: Simulation, rec: Recorder,
                   s: Summary | None) -> Theory | None:
    """``theory``: the theory's fountain for this run (the paper's catenary,
    :class:`~chainfountain.sim.reference.LaunchReference`, or a stiff chain's,
    :class:`~chainfountain.sim.stiff_reference.StiffReference`, with the catenary
    beside it) and the window's errors against it; a stiff chain without a steady
    fountain: why, and the catenary."""
    if s is None:
        return None
    pred = _prediction(level, sim, s)
    ref, cat = pred.reference, pred.catenary
    if ref is None and (cat is None or not pred.note):
        return None
    if ref is None:
        none = {k: None for k in ("h", "vertex_x", "l", "q", "v")}
        return Theory(h=None, vertex_x=None, l=None, q=None, k=cat.k, v=cat.v, T0_bar=None,
                      TE_bar=cat.TE_bar, rel_error=RelErrors(**none),
                      abs_error=AbsErrors(T0_bar=None, TE_bar=None, tension_rms=None),
                      theory="stiff", joints=_joints(level, cat.v, cat),
                      catenary=_beside(cat, s),
                      why_none=pred.note)
    errs = s.errors(ref)
    stiff = isinstance(ref, StiffReference)
    rel = {k: finite(errs[k]) for k in ("h", "vertex_x", "l", "q", "v")}
    if stiff:
        rel["q"] = None  # a stiff fountain has no catenary parameter
    out = Theory(
        h=ref.h, vertex_x=ref.x_rise, l=ref.landing_x, q=None if stiff else ref.q, k=ref.k,
        v=ref.v, T0_bar=ref.T0_bar, TE_bar=ref.TE_bar,
        rel_error=RelErrors(**rel),
        abs_error=AbsErrors(T0_bar=finite(errs["T0_bar"]),
                            TE_bar=finite(_tension_end(s) - ref.TE_bar),
                            tension_rms=finite(s.tension_rms)))
    if stiff:
        out.theory = "stiff"
        out.joints = _joints(level, ref.v, ref.catenary)
        out.catenary = _beside(ref.catenary, s)
    elif selects_speed(level.sim):
        out.at_speed = _at_speed(level, s)
    return out


def selects_speed(config: Any) -> bool:
    """Whether the level is a machine whose laws select its speed (an ideal machine that
    does not keep any speed)."""
    return kind_of(config).name == "ideal" and not keeps_any_speed(config)


def _at_speed(level: Level, s: Summary) -> dict[str, Any] | None:
    """The paper's fountain at the window's own speed and the window's errors against it
    (:attr:`~chainfountain.headless.report.Theory.at_speed`)."""
    try:
        ref = LaunchReference.at_speed(level.sim, s.speed_mean)
    except ValueError:
        return None
    out = _beside(ref, s)
    del out["q"], out["T0_bar"]
    return {"v": finite(ref.v), **out, "TE_bar": finite(ref.TE_bar)}


def machine_section(level: Level, sim: Simulation, rec: Recorder,
                    s: Summary | None) -> str | None:
    """``machine``: what sets an ideal machine's speed: its laws select it
    (``"selects"``), or, loss-free, it ``"keeps any speed"``."""
    if s is None:
        return None
    return "keeps any speed" if keeps_any_speed(level.sim) else "selects"


def open_section(level: Level, sim: Simulation, rec: Recorder,
                 s: Summary | None) -> dict[str, Any] | None:
    """``open``: the paper's non-stationary arrangement (``feed.drive = "ideal_open"``),
    measured by the plate reaction's rate (:mod:`chainfountain.sim.slide_away_report`)."""
    if sim.slide_away is None or s is None:
        return None
    from chainfountain.sim.slide_away_report import report

    ref = _reference(level, sim, s)
    return json_safe(report(rec.samples, sim.piston.hand_over, level.sim.chain.linear_density,
                            sim.g, ref.v if ref is not None else math.nan))


def beaker_section(level: Level, sim: Simulation, rec: Recorder,
                   s: Summary | None) -> dict[str, Any] | None:
    """``beaker``: a fountain from a pot (:mod:`chainfountain.sim.beaker_report`)."""
    if sim.beaker is None or s is None:
        return None
    from chainfountain.sim.beaker_report import report

    return json_safe(report(sim.beaker, (s.vertex_x, s.vertex_y), s.landing_x, s.t0, s.t1,
                            sim.g, level.sim.chain, level.sim.solver))


def apparatus_section(level: Level, sim: Simulation, rec: Recorder,
                      s: Summary | None) -> Remeasured | None:
    """``apparatus``: the pulley apparatus's report
    (:mod:`chainfountain.sim.apparatus_report`); its ``TE_bar``, read at the fountain's
    end height, is the summary's."""
    if sim.apparatus is None or s is None:
        return None
    from chainfountain.sim.apparatus_report import report

    rep = report(sim, rec, s.t0, s.t1)
    return Remeasured(json_safe(rep), {"TE_bar": finite(rep["measured"]["TE_bar"])})


def error_bars_section(level: Level, sim: Simulation, rec: Recorder,
                       s: Summary | None) -> dict[str, Any] | None:
    """``error_bars`` of a fed level: how to estimate them (a run with ``error_bars``
    stores :meth:`chainfountain.refine.Refinement.as_dict` here instead)."""
    return {"method": None, "how": "not estimated: chainfountain run LEVEL --error-bars, or "
            "chainfountain converge LEVEL"}


def error_model_section(level: Level, sim: Simulation, rec: Recorder,
                        s: Summary | None) -> dict[str, Any] | None:
    """``error_model`` of a fed level (:func:`model_error`)."""
    return model_error(level)


SECTIONS: dict[str, SectionBuilder] = {
    "theory": theory_section,
    "machine": machine_section,
    "open": open_section,
    "beaker": beaker_section,
    "apparatus": apparatus_section,
    "error_bars": error_bars_section,
    "error_model": error_model_section,
}
"""``summary.json``'s optional sections by name, in the order written: each level kind
names those it adds (:attr:`~chainfountain.sim.kinds.base.Kind.sections`); a failed
builder is named ``"<name> report"`` in ``analysis_failed``."""

ALWAYS_WRITTEN = ("theory",)
"""Sections written (``null``) even when the run has none: a fountain's ``theory``."""


def summarize(level: Level, sim: Simulation, rec: Recorder, duration: float,
              wall: float) -> RunSummary:
    """The run's :class:`~chainfountain.headless.report.RunSummary`. Analyses that fail
    are listed under ``analysis_failed`` (name: reason) and their figures are null."""
    failed: dict[str, str] = {}
    # steady: the run's last averaging window (``recording.window``) is the reference, so a
    # fountain that formed from its stub is steady from when it formed
    steady = _attempt(failed, "steady-state detection", rec.steady_from)
    window_start = steady if steady is not None else max(0.0, sim.time - rec.cfg.window)
    s = _attempt(failed, "window averages", rec.summary, sim.time - window_start)
    out = RunSummary(
        level=level.meta.name, kind=level.sim.kind, duration_s=finite(sim.time),
        requested_duration_s=finite(duration), steps=sim.steps, links=sim.n_links,
        link_length=level.sim.chain.link_length, dt=sim.dt, wall_s=finite(wall),
        realtime_factor=finite(sim.time / wall) if wall > 0 else None,
        fountain=_figures(sim, s, steady))
    if s is not None:
        failed.update(s.failed)
    own = kind_of(level.sim).sections
    for name, build in SECTIONS.items():
        if name not in own and name not in ALWAYS_WRITTEN:
            continue
        section = _attempt(failed, f"{name} report", build, level, sim, rec, s)
        if isinstance(section, Remeasured):
            for key, value in section.figures.items():
                setattr(out.fountain, key, value)
            section = section.section
        if section is not None or name in ALWAYS_WRITTEN:
            out.sections[name] = section
    out.analysis_failed = failed
    return out


def _figures(sim: Simulation, s: Summary | None, steady: float | None) -> FountainFigures:
    """The window's figures (only ``steady = False`` when its averages failed)."""
    if s is None:
        return FountainFigures(steady=False)
    return FountainFigures(
        steady=steady is not None, links_free=sim.n_free, steady_since_s=finite(steady),
        window=[finite(s.t0), finite(s.t1)], samples=s.samples, v=finite(s.speed_mean),
        speed_cv=finite(s.speed_uniformity), speed_spread=finite(s.speed_spread_inst),
        max_stretch=finite(s.stretch_max), vertex_x=finite(s.vertex_x),
        h=finite(s.vertex_y), l=finite(s.landing_x), H=sim.drop, q=finite(s.q_fit),
        k=finite(sim.g / s.speed_mean**2) if s.speed_mean > 0 else None,
        T0_bar=finite(s.T0_bar), TE_bar=finite(_tension_end(s)),
        tension_rms=finite(s.tension_rms))


def model_error(level: Level) -> dict[str, Any]:
    """``summary.json``'s ``error_model``: what the error model
    (:mod:`chainfountain.sim.accuracy`) says about a fed level's settings, or why it says
    nothing."""
    from chainfountain.sim import accuracy

    sim = level.sim
    out: dict[str, Any] = {"source": "error model (chainfountain.sim.accuracy, fitted by "
                           "research/error_model.py)", "bounds": None,
                           "accuracy": sim.solver.accuracy or None}
    f = sim.feed
    refused = kind_of(sim).accuracy_refusal(sim)
    if refused is not None:
        out["why_none"] = (f"{refused}: the model covers fed fountains on an absorbing floor"
                           ", without blocks or self-collision; chainfountain converge LEVEL "
                           "refines this one")
        return out
    if f.drive != "motor":
        out["flight_at_speed"] = True
        out["note"] = ("the flying chain's error against the paper's fountain at the speed it "
                       "runs (theory.at_speed; for a loss-free machine, theory itself); the "
                       "speed sits a few tenths of a per cent off the laws' besides "
                       "(research/ideal_machine_holds.py)")
    try:
        ref = LaunchReference.of_level(sim)
    except ValueError as exc:
        out["why_none"] = f"no fountain: {exc}"
        return out
    if accuracy.is_stiff(sim.chain):
        out["note"] = ("against the steady stiff-chain theory, for a steady run (an undamped "
                       "stiff fountain does not settle: docs/stiff_stability.md)")
    why = accuracy.in_domain(ref, sim.chain, machine=f.drive != "motor")
    if why is not None:
        out["why_none"] = why
        return out
    sv = sim.solver
    est = accuracy.estimate(ref, accuracy.Settings(sim.chain.link_length, sv.dt / sv.substeps,
                                                   sv.iterations), sim.chain,
                           machine=f.drive != "motor")
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
