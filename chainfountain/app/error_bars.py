"""The expert readout's line of discretisation error bars: what the running level's
figures may be off by at its link length, step and iterations, and where that comes
from. No pygame here.

- A fed fountain (motor or ideal machine): the error model's bounds
  (:func:`chainfountain.sim.accuracy.estimate`) on the vertex height and the landing,
  for an ideal machine of its flight at the speed it runs (``summary.json``'s
  ``theory.at_speed``; its speed wanders off the laws' by a few tenths of a per cent).
- The beaker: the step error model's one-sided bars
  (:mod:`chainfountain.sim.beaker_error`).
- A contact machine: how far halving the step moved the gripped presets' flight
  (:mod:`chainfountain.sim.apparatus_report.step_change`), or that its step's error is
  not refined here and how to refine it (``chainfountain run LEVEL --error-bars``).
- Elsewhere (scenes, which run headless) nothing.
"""

from __future__ import annotations

from chainfountain.sim import accuracy, beaker_error
from chainfountain.sim.apparatus_report import step_change
from chainfountain.sim.kinds import kind_of
from chainfountain.sim.reference import LaunchReference
from chainfountain.sim.world import Simulation


def error_bars_line(sim: Simulation, asked_accuracy: float = 0.0) -> str:
    """One line for the expert readout, or '' where the level has no model of its
    error (``asked_accuracy`` below the running configuration's: the level's, where the
    window runs a coarser accuracy's settings to keep real time)."""
    cfg = sim.config
    sv = cfg.solver
    dt = sv.dt / max(1, sv.substeps)
    if sim.beaker is not None:
        if beaker_error.applies(cfg.chain, sv, cfg.beaker) is not None:
            return "the step's error: not measured at these settings"
        low = beaker_error.shortfalls(dt)
        return (f"the step's error: speed -0/+{100 * low['speed']:.0f} %, top "
                f"-0/+{100 * low['rise_above_rim']:.0f} % (refined)")
    if sim.apparatus is not None:
        return _apparatus_line(cfg)
    if sim.feed is None or not kind_of(cfg).predicted:
        return ""
    ref = sim.catenary
    if not isinstance(ref, LaunchReference) or cfg.feed.floor != "absorbing":
        return ""
    why = accuracy.in_domain(ref, cfg.chain, machine=cfg.feed.drive != "motor")
    if why is not None:
        return f"no error model: {why.split(' (')[0].split(', where')[0]}"
    est = accuracy.estimate(ref, accuracy.Settings(cfg.chain.link_length, dt, sv.iterations),
                            cfg.chain, machine=cfg.feed.drive != "motor")
    if not est.converged:
        return "the solver is short of iterations: the fountain may sit a few % low"
    b = est.bounds
    what = "the flight at its speed" if cfg.feed.drive != "motor" else "model"
    if 0.0 < asked_accuracy < sv.accuracy:
        what += (f", {100 * sv.accuracy:g} % to keep real time, solver.accuracy "
                 f"{100 * asked_accuracy:g} % asked")
    elif sv.accuracy > 0:
        what += f", solver.accuracy {100 * sv.accuracy:g} %"
    return (f"error: top +-{100 * b['vertex_y']:.1f} %, landing "  # figures first: a
            f"+-{100 * b['landing_x']:.1f} % ({what})")  # narrow panel cuts the source


def _apparatus_line(cfg) -> str:
    """The step's error of a contact machine's flight: the presets' measured moves, or
    how to measure them."""
    step = step_change.step_section(cfg)
    m = step["moves"]
    if m is None:
        return "the step's error: not refined here (chainfountain run LEVEL --error-bars)"
    return (f"the step's error (refined at the presets): Tbar_0 +-{m['T0_bar']:.3f}, Tbar_E "
            f"+-{m['TE_bar']:.3f}, vertex +-{100 * m['vertex_y_rel_error']:.1f} %")
