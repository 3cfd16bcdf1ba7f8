"""A scene's closed-form errors with the step's error bar, by refinement: the scene is run
again at half its step (``solver.dt / 2``, the same sub-steps and iterations, the same
links). Each figure ``f`` (its relative error against the closed form) at the run's step
``dt`` and at ``dt/2`` gives, taking it to be first order in the step as the shipped
scenes measure (``docs/accuracy.md``, 'Scenes'):

    f(0) = 2 f(dt/2) - f(dt)                     (Richardson, order 1)
    GCI(dt/2) = 3 |f(dt) - f(dt/2)| / (2 - 1)    (Roache's grid convergence index)

The index (two grids, safety factor 3) is the error bar of the figure at half the step,
``f(dt/2)``: the refined figure and its bar. Not every figure is cleanly first order:
``falling_chain``'s fixed-end force at 75 % of the fall reads +1.83 / +3.97 / +5.04 /
+5.83 % at 250 / 125 / 62.5 / 31.25 us, the halvings moving it 2.14, 1.06 and 0.79
points, so its zero-step value lies near +8 % (the moves shrinking by a quarter each
time), 4.2 points from the figure at 125 us and inside its index, 6.4. The link length
is the scene's own and is not refined: the closed forms are a continuous chain's, so a
figure at zero step still carries the links' size.

A jittered scene is chaotic (a pile of links lands differently at every step), so two
steps give two trajectories, not a refinement: its figures are compared over seeds
(``chainfountain sweep``) and the refinement is left out, saying why.
"""

from __future__ import annotations

import copy
import math
from typing import Any

from chainfountain.level.model import Level

FIGURES = ("speed_rel_error", "force_rel_error")
"""The closed form's figures refined (a list per share of a folded fall, one for a scale)."""
SAFETY = 3.0
"""Roache's safety factor for the index from two grids."""
METHOD = ("refinement: the scene again at half its step (same links, sub-steps and "
          "iterations); first order: f(0) = 2 f(dt/2) - f(dt); the bar of f(dt/2) is "
          "Roache's grid convergence index, 3 |f(dt) - f(dt/2)|")


def refusal(level: Level) -> str | None:
    """Why the scene's step is not refined (``None``: it is)."""
    sc = level.sim.scene
    if sc.closed_form == "none":
        return "no closed form to compare with"
    if sc.jitter > 0:
        return (f"scene.jitter = {sc.jitter:g}: a pile of jittered links is chaotic, so a run "
                "at half the step is another trajectory, not a refinement; compare the mean "
                "over seeds (chainfountain sweep with seeds)")
    return None


def has_figures(form: dict[str, Any] | None) -> bool:
    """Whether the closed form's comparison ``form`` has any figure to refine."""
    if not form:
        return False
    vals = [form.get(k) for k in FIGURES]
    flat = [x for v in vals for x in (v if isinstance(v, list) else [v])]
    return any(x is not None for x in flat)


def halved(level: Level) -> Level:
    """``level`` at half its step."""
    out = copy.deepcopy(level)
    out.sim.solver.dt = level.sim.solver.dt / 2
    return out


def _pair(a: Any, b: Any) -> tuple[float | None, float | None]:
    if a is None or b is None or not (math.isfinite(a) and math.isfinite(b)):
        return None, None
    return 2 * b - a, SAFETY * abs(a - b)


def step_error(coarse: dict[str, Any], fine: dict[str, Any], dt: float) -> dict[str, Any]:
    """The refinement of the closed form's figures ``coarse`` (at step ``dt``) by ``fine``
    (at ``dt/2``): for each of :data:`FIGURES`, its value at half the step, that value's
    bar (``gci``) and the value at zero step (see the module docstring; ``None`` where
    either run has none)."""
    out: dict[str, Any] = {"method": METHOD, "dt": dt, "half_dt": dt / 2}
    for key in FIGURES:
        a, b = coarse.get(key), fine.get(key)
        if isinstance(a, list):
            b = list(b or [None] * len(a))
            pairs = [_pair(x, y) for x, y in zip(a, b, strict=True)]
            out[key] = {"half_step": b, "gci": [p[1] for p in pairs],
                        "zero_step": [p[0] for p in pairs]}
        else:
            zero, err = _pair(a, b)
            out[key] = {"half_step": b, "gci": err, "zero_step": zero}
    return out


def skipped(why: str) -> dict[str, Any]:
    """The section of a scene whose step is not refined."""
    return {"method": METHOD, "skipped": why}
