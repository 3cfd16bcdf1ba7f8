"""A scene's closed-form errors with the step's error bar, by refinement: the scene is run
again at half its step (``solver.dt / 2``, the same sub-steps and iterations, the same
links) and each figure ``f`` (its relative error against the closed form) is taken to be
first order in the step, as the shipped scenes measure (``docs/accuracy.md``, 'Scenes':
the free end's speed at 75 % of the fall -1.50 / -0.87 / -0.54 % at 250 / 125 / 62.5 us,
the fixed end's force +1.83 / +3.97 / +5.04 %; each halving moves them by about half the
last), so that

    f(0) = 2 f(dt/2) - f(dt)                        (Richardson, order 1)
    the step's error of f(dt) = 3 |f(dt) - f(dt/2)|  (Roache's grid convergence index)

The bar is Roache's two-grid index, ``3 |f(dt) - f(dt/2)| / (2**p - 1)`` at order
``p = 1``: 1.5 times Richardson's ``|f(dt) - f(0)| = 2 |f(dt) - f(dt/2)|``, because not
every figure is cleanly first order. ``falling_chain``'s fixed-end force at 75 % of the
fall reads +1.84 / +3.97 / +5.04 / +5.83 % at 250 / 125 / 62.5 / 31.25 us: the halvings
move it by 2.14, 1.06 and 0.79 points, so its value at zero step lies above the finest
pair's +6.6 %, more than 4.8 points from the figure at 250 us, beyond Richardson's 4.3
and inside the index's 6.4. The link length is the scene's own and is not refined: the
closed forms are a continuous chain's, so a figure at zero step still carries the links'
size.

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
"""Roache's safety factor for an error estimate from two steps."""
METHOD = ("refinement: the scene again at half its step (same links, sub-steps and "
          "iterations); first order: f(0) = 2 f(dt/2) - f(dt), the step's error of f(dt) = "
          "3 |f(dt) - f(dt/2)| (Roache's grid convergence index, two steps)")


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
    (at ``dt/2``): for each of :data:`FIGURES`, its value at half the step, at zero step
    and its step's error (see the module docstring; ``None`` where either run has none)."""
    out: dict[str, Any] = {"method": METHOD, "dt": dt, "half_dt": dt / 2}
    for key in FIGURES:
        a, b = coarse.get(key), fine.get(key)
        if isinstance(a, list):
            pairs = [_pair(x, y) for x, y in zip(a, b or [None] * len(a), strict=True)]
            out[key] = {"half_step": list(b or [None] * len(a)),
                        "zero_step": [p[0] for p in pairs],
                        "step_error": [p[1] for p in pairs]}
        else:
            zero, err = _pair(a, b)
            out[key] = {"half_step": b, "zero_step": zero, "step_error": err}
    return out


def skipped(why: str) -> dict[str, Any]:
    """The section of a scene whose step is not refined."""
    return {"method": METHOD, "skipped": why}
