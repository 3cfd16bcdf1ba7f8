"""How far halving the step moves a gripped fold's flight: its refinement, measured.

The apparatus report's standard errors (``flight``'s ``_se``) are statistical only. The
step's part was measured by running both gripped presets from rest for 40 s at their step
and at half of it and averaging 10-40 s (``python -m research.gripped_flight
apparatus_fold_gripped apparatus_special_gripped --seconds 40 --window 10 40 --dt-factor
1 0.5``; README, "What the gripped folds launch"):

==============================  ===============================  =================
figure                          ``apparatus_fold_gripped``       ``..._special_..``
==============================  ===============================  =================
``Tbar_0``                      0.724 / 0.714                    0.729 / 0.712
``Tbar_E``                      0.221 / 0.203                    0.223 / 0.238
``Tbar_0 - Tbar_E - k dy``      -0.020 / -0.003                  -0.024 / -0.049
vertex off the catenary         +1.9 / -1.5 %                    +0.5 / -1.1 %
==============================  ===============================  =================

:data:`MOVES` is the larger move of the two per figure. One run at each step: the moves
hold the statistical error of both means besides (the relation's is 0.006-0.011), so they
bound the step's part from above rather than measure it. They apply at the presets' own
step, sub-steps and links only (:func:`applies`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from chainfountain.sim.config import SimConfig

MOVES = {"T0_bar": 0.017, "TE_bar": 0.018, "relation_miss": 0.025,
         "vertex_y_rel_error": 0.034}
"""How far halving the step moved each figure of ``flight`` (the module's table)."""
REFINED = {"solver.dt": 1e-3, "solver.substeps": 2, "chain.link_length": 0.02}
"""The gripped presets' settings the refinement ran at (and at half the step)."""
SOURCE = ("refinement of the gripped presets from rest, 10-40 s at their step and half of it "
          "(python -m research.gripped_flight)")


def applies(cfg: SimConfig) -> str | None:
    """Why :data:`MOVES` do not apply to a level (``None`` when they do): only a gripped
    fold at the settings the refinement ran at."""
    a = cfg.apparatus
    if a.variant != "fold" or a.fold_roller != "gripped":
        return ("not measured for this arrangement's flight: chainfountain run LEVEL "
                "--error-bars refines it")
    have = {"solver.dt": cfg.solver.dt, "solver.substeps": cfg.solver.substeps,
            "chain.link_length": cfg.chain.link_length}
    off = [f"{k} = {have[k]:g}" for k, v in REFINED.items() if abs(have[k] - v) > 1e-9 * v]
    if off:
        return (f"refined at the gripped presets' settings only (here "
                f"{', '.join(off)}): chainfountain run LEVEL --error-bars refines this one")
    return None


def step_section(cfg: SimConfig) -> dict[str, object]:
    """``flight.step``: the refinement's moves and their source, or why there are none."""
    why = applies(cfg)
    if why is not None:
        return {"moves": None, "how": why}
    return {"moves": dict(MOVES), "how": SOURCE}
