"""The beaker's discretisation error: a first-order model in the time step, measured by
refinement.

A beaker's figures converge in the step at first order, and slowly
(``python -m research.beaker_refinement``; docs/beaker.md, "Against Biggins and Warner,
with error bars"): the shipped beaker (2-cm links, 6 iterations, one pymunk step a step;
30 s from rest, the last 10 s averaged, three nudged starts) at 250, 125 and 62.5 us:

==========================  =====  =====  =====  ==========  =====================
figure                      250    125    62.5   zero step   ``SLOPE`` (per 250 us)
==========================  =====  =====  =====  ==========  =====================
speed (m/s)                 4.388  4.523  4.588  4.653       0.057
top above the rim (m)       0.278  0.313  0.328  0.343       0.19
``alpha`` from the speed    0.507  0.536  0.549  0.562       0.098
==========================  =====  =====  =====  ==========  =====================

Each halving moves a figure half as far as the one before (0.135 then 0.065 m/s, 0.035
then 0.015 m), so the zero-step value is the last one plus the last move (Richardson at
first order), and a run at step ``dt`` lies below it by ``SLOPE * dt / 250 us`` of it.
Twice the iterations recover about a third of the speed's shortfall at 250 us; the model
holds for the refined chain and solver only (:func:`applies`), and says so elsewhere.
"""

from __future__ import annotations

import copy
import math

from chainfountain.sim.config import BeakerConfig, ChainConfig, SimConfig, SolverConfig

DT_REF = 2.5e-4
"""Step (s) at which :data:`SLOPE` is the shortfall."""
DT_MIN = 6.25e-5
"""The smallest step refined (s): ``solver.accuracy`` chooses no step below it."""
SLOPE = {"speed": 0.057, "rise_above_rim": 0.19, "alpha_from_speed": 0.098}
"""Shortfall at :data:`DT_REF` of each figure below its zero-step value, as a fraction of
that value (the module's table)."""
REFINED = {"chain.link_length": 0.02, "solver.iterations": 6, "solver.substeps": 1}
"""The settings the refinement measured, besides the step (the shipped beaker's)."""
REFINED_BEAKER = {"beaker.drop": 1.0, "beaker.pot_width": 0.3, "beaker.pot_depth": 0.3,
                  "beaker.pile_rows": 4, "beaker.pile_depth": 0.04,
                  "chain.bend_limit": 0.5235987755982988, "chain.friction": 0.4}
"""The beaker and chain the refinement measured (the shipped beaker's). Elsewhere the
shortfall differs: at a 1.5-m drop (seeds 0 and 1, 20 s from rest, the last 8 s) the top
reads 0.421 / 0.469 / 0.506 m at 250 / 125 / 62.5 us, halvings moving it 0.048 then
0.037 m, not half as far each time, so its zero-step value lies above 0.54 m and the
shortfall at 250 us above 29 %, where :data:`SLOPE` gives 23 %."""
SOURCE = ("error model: first order in the step, measured by refining the shipped beaker "
          "(python -m research.beaker_refinement; docs/beaker.md)")
"""Where the bars come from."""


def _have(chain: ChainConfig, solver: SolverConfig, beaker: BeakerConfig) -> dict[str, float]:
    return {"chain.link_length": chain.link_length, "solver.iterations": solver.iterations,
            "solver.substeps": solver.substeps, "beaker.drop": beaker.drop,
            "beaker.pot_width": beaker.pot_width, "beaker.pot_depth": beaker.pot_depth,
            "beaker.pile_rows": beaker.pile_rows, "beaker.pile_depth": beaker.pile_depth,
            "chain.bend_limit": chain.bend_limit, "chain.friction": chain.friction}


def _off(have: dict[str, float], refined: dict[str, float]) -> list[str]:
    return [f"{k} = {have[k]:g} (refined at {v:g})" for k, v in refined.items()
            if abs(have[k] - v) > 1e-9 * max(1.0, abs(v))]


def applies(chain: ChainConfig, solver: SolverConfig, beaker: BeakerConfig) -> str | None:
    """Why the model does not apply to a beaker with ``chain``, ``solver`` and ``beaker``
    (``None`` when it does): it was measured at :data:`REFINED` and
    :data:`REFINED_BEAKER` only, at steps up to :data:`DT_REF` (a smaller step only
    brings the figures nearer their zero-step values)."""
    off = _off(_have(chain, solver, beaker), {**REFINED, **REFINED_BEAKER})
    if solver.dt / max(1, solver.substeps) > DT_REF * (1.0 + 1e-9):
        off.append(f"solver.dt = {solver.dt:g} s (refined at {DT_REF:g} s and below)")
    if off:
        return ("the step error was refined at the shipped beaker's settings only: "
                + ", ".join(off) + "; python -m research.beaker_refinement --level LEVEL "
                "refines this one")
    return None


def shortfalls(dt: float) -> dict[str, float]:
    """Each figure's shortfall below its zero-step value at step ``dt`` (s), as a fraction
    of the value measured (``measured * (1 + s)`` is the zero-step value)."""
    out = {}
    for name, slope in SLOPE.items():
        below = slope * dt / DT_REF  # of the zero-step value
        out[name] = below / (1.0 - below)
    return out


def error_bars(figures: dict[str, float], chain: ChainConfig, solver: SolverConfig,
               beaker: BeakerConfig) -> dict[str, object]:
    """``summary.json``'s ``beaker.error_bars`` for the measured ``figures`` (``speed``,
    ``rise_above_rim``, ``alpha_from_speed``): each figure's shortfall below its zero-step
    value (relative to the figure, one-sided: the step only lowers them) and that value,
    or why the model does not apply."""
    why = applies(chain, solver, beaker)
    if why is not None:
        return {"method": None, "how": why}
    if not figures:
        return {"method": None, "how": "no figures in the window: the chain has formed no "
                "fountain there"}
    dt = solver.dt / max(1, solver.substeps)
    rel = shortfalls(dt)
    return {"method": "error model", "source": SOURCE, "dt": dt, "one_sided": True,
            "accuracy": solver.accuracy or None,
            "shortfall": {k: rel[k] for k in figures},
            "zero_step": {k: figures[k] * (1.0 + rel[k]) for k in figures}}


def accuracy_refusal(cfg: SimConfig) -> str | None:
    """Why ``solver.accuracy`` cannot choose a beaker's step (``None``: it can): the step
    model holds at the refined chain, solver and beaker only (:data:`REFINED`,
    :data:`REFINED_BEAKER`)."""
    off = _off(_have(cfg.chain, cfg.solver, cfg.beaker), {**REFINED, **REFINED_BEAKER})
    if not off:
        return None
    return ", ".join(o.replace(" (refined at", " (the beaker's step error was refined at", 1)
                     for o in off[:1]) + "".join(f", {o}" for o in off[1:])


def choose_settings(cfg: SimConfig, accuracy: float) -> SimConfig:
    """A copy of the beaker ``cfg`` at the longest step, to three digits, whose every
    figure's shortfall (:func:`shortfalls`; the top's is the largest) is within
    ``accuracy``; raises :class:`~chainfountain.sim.accuracy.OutOfReach` below what the
    smallest refined step, :data:`DT_MIN`, reaches."""
    from chainfountain.sim.accuracy import OutOfReach

    below = accuracy / (1.0 + accuracy)  # the shortfall b/(1 - b) within the accuracy
    dt = min(DT_REF, DT_REF * below / max(SLOPE.values()))
    if dt < DT_MIN * (1.0 - 1e-9):
        best = max(shortfalls(DT_MIN).values())
        raise OutOfReach(f"the beaker's step model reaches {100 * best:.2f} % at its smallest "
                         f"refined step, {DT_MIN * 1e6:g} us", best)
    unit = 10.0 ** (math.floor(math.log10(dt)) - 2)
    dt = float(f"{math.floor(dt / unit) * unit:.3g}")
    if max(shortfalls(dt).values()) > accuracy:  # rounding noise
        dt = float(f"{dt - unit:.3g}")
    out = copy.deepcopy(cfg)
    out.solver.dt = dt
    return out
