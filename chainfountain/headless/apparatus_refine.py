"""A contact machine's figures refined in the step: the run again at half its step.

The contact machines have no error model; what the step does to their figures is
measured by refinement. ``chainfountain run LEVEL --error-bars`` runs an apparatus level
a second time at half its step (the same links, sub-steps, iterations, start and
duration) and gives, in ``summary.json``'s ``apparatus.flight.step``, how far each of the
flight's figures moved (the speed, ``Tbar_0``, ``Tbar_E``, the paper's relation across
the flight and the vertex against the catenary through the ends) beside their values at
half the step and the statistical errors of both window means. One run at each step: a
move holds both means' statistical error besides the step's part, so it bounds the
step's error of the coarse figure from above rather than measures it, and the machine's
chaos makes the two runs different trajectories (compare the moves with the ``_se``).
"""

from __future__ import annotations

import math
from typing import Any

from chainfountain.headless.scene_refine import halved  # noqa: F401 - the level at dt/2

FIGURES = ("T0_bar", "TE_bar", "relation_miss", "vertex_y_rel_error")
"""The flight's figures whose move is given (``apparatus.flight``), besides the speed."""

METHOD = ("refinement: the level again at half its step (same links, sub-steps, iterations, "
          "start and duration, the same window); moves = |f(dt) - f(dt/2)| (the speed's "
          "relative), which hold both window means' statistical errors (_se) besides the "
          "step's")
"""How the moves are made, in words (``apparatus.flight.step.how``)."""


def _finite(x: Any) -> bool:
    return isinstance(x, int | float) and math.isfinite(x)


def step_section(coarse: dict[str, Any], fine: dict[str, Any], dt: float) -> dict[str, Any]:
    """``apparatus.flight.step`` from the run's ``apparatus`` section (``coarse``, at step
    ``dt``) and the run at half the step's (``fine``)."""
    cf, ff = coarse.get("flight") or {}, fine.get("flight") or {}
    moves: dict[str, float | None] = {}
    for key in FIGURES:
        a, b = cf.get(key), ff.get(key)
        moves[key] = abs(a - b) if _finite(a) and _finite(b) else None
    v0 = (coarse.get("measured") or {}).get("v")
    v1 = (fine.get("measured") or {}).get("v")
    moves["v_rel"] = abs(v0 / v1 - 1.0) if _finite(v0) and _finite(v1) and v1 > 0 else None
    half = {key: ff.get(key) for key in FIGURES} | {"v": v1}
    half_se = {key: ff.get(f"{key}_se") for key in ("T0_bar", "TE_bar", "relation_miss", "v")}
    return {"moves": moves, "how": METHOD, "dt": dt, "half_dt": dt / 2.0,
            "half_step": half, "half_step_se": half_se, "window": fine.get("window")}


def skipped(why: str) -> dict[str, Any]:
    """``apparatus.flight.step`` when the run at half the step gives no moves."""
    return {"moves": None, "how": f"not refined: {why}"}
