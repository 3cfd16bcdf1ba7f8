"""A beaker run against the theory: ``summary.json``'s ``beaker`` object.

The measured fountain (over a window of a :class:`~chainfountain.sim.world.Simulation` of
``kind = "beaker"``) against Biggins and Warner's relations
(:mod:`chainfountain.theory.mould`) and against this paper's inverted catenary through
the measured ends at the measured speed (:class:`~chainfountain.theory.Fountain`). Each
gives the pile's pick-up factor ``alpha``; a string model that holds gives one ``alpha``
from all of them, except the rise of B&W's zero-width fountain, which a fountain of finite
width does not reach.
"""

from __future__ import annotations

import math
from typing import Any

from chainfountain.sim import beaker_error
from chainfountain.sim.beaker import Beaker
from chainfountain.sim.config import ChainConfig, SolverConfig
from chainfountain.theory import Fountain
from chainfountain.theory.mould import alpha_from_rise, alpha_from_speed, bw_rise


def report(beaker: Beaker, vertex: tuple[float, float], landing_x: float, t0: float,
           t1: float, g: float, chain: ChainConfig, solver: SolverConfig) -> dict[str, Any]:
    """The ``beaker`` object for the window ``t0 .. t1`` (s): ``vertex`` and ``landing_x``
    are the recorder's window means (rim frame, m); ``error_bars`` the step's error
    (:func:`~chainfountain.sim.beaker_error.error_bars`, at ``chain`` and ``solver``).
    (The tension where the chain leaves the pile is no reading of ``alpha``: the links
    there are still being accelerated, and the recorder's launch tension, taken at the
    first link at rest, is about 0.)"""
    w = beaker.window(t0, t1)
    v, px, py = w["v"], w["pickup_x"], w["pickup_y"]
    H = py - beaker.floor_y  # pick-up to floor
    h = vertex[1] - py  # rise above the pick-up
    l = landing_x - px  # noqa: E741 - the paper's symbol
    out: dict[str, Any] = {
        "window_s": [t0, t1],
        "speed": v,
        "pickup": [px, py],
        "drop_from_pickup": H,
        "rise_above_pickup": h,
        "rise_above_rim": vertex[1],
        "span_from_pickup": l,
        "links_in_window": round(v * (t1 - t0) / beaker.L) if math.isfinite(v) else None,
        "alpha": {},
        "biggins_warner": {},
        "paper": None,
        "error_bars": beaker_error.error_bars({}, chain, solver, beaker.cfg),
    }
    if not (math.isfinite(v) and v > 0 and H > 0 and math.isfinite(h)):
        return out
    a_v = alpha_from_speed(v, H, 0.0, g)
    out["error_bars"] = beaker_error.error_bars(
        {"speed": v, "rise_above_rim": vertex[1], "alpha_from_speed": a_v}, chain, solver,
        beaker.cfg)
    a_h = alpha_from_rise(h, H, 0.0)
    out["alpha"] = {"from_speed": a_v, "from_rise": a_h}
    out["biggins_warner"] = {
        "beta": 0.0,
        "speed_from_alpha_rise": math.sqrt(g * H / (1.0 - a_h)) if a_h < 1 else None,
        "rise_from_alpha_speed": bw_rise(H, a_v) if 0 <= a_v < 1 else None,
    }
    try:
        f = Fountain.from_geometry(l=l, h=h, H=H, v=v, g=g)
        out["paper"] = {"q": f.q, "k": f.k, "T0_bar": f.T0_bar, "TE_bar": f.TE_bar,
                        "alpha0": f.alpha0, "alpha": 1.0 - f.T0_bar}
        out["alpha"]["from_paper_catenary"] = 1.0 - f.T0_bar
    except (ValueError, ArithmeticError, RuntimeError) as exc:
        out["paper"] = {"none": f"no inverted catenary through the measured ends ({exc})"}
    return out
