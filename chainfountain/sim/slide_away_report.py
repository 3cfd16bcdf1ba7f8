"""An open arrangement with ideal rollers against the paper: ``summary.json``'s ``open``.

The paper's non-stationary arrangement (Fig. "pulley_experiment_equiv_ground", right) is
one "in which the reaction force change is exactly known over time": the lower plate
carries the chain that has slid onto it, so its reaction grows at ``lambda g v``
(:func:`~chainfountain.theory.apparatus.plate_reaction`). The run's rate is compared with
it over the whole run after the hand-over and in each :data:`CHUNK` of it ("all along"),
beside the speed the machine's laws select
(:func:`~chainfountain.theory.apparatus.ideal_open_speed`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from chainfountain.sim.measure import Sample

CHUNK = 2.0
"""Length (s) of the consecutive windows in which the reaction's rate is compared."""


def _rate(t: np.ndarray, y: np.ndarray) -> float:
    """Least-squares slope of ``y`` over ``t`` (the reaction is counted, not measured
    through contacts, so it has no impulse spikes a robust fit would need to ignore)."""
    return float(np.polyfit(t, y, 1)[0]) if len(t) > 2 else math.nan


def report(samples: list[Sample], since: float, lam: float, g: float,
           v_law: float) -> dict[str, Any] | None:
    """The ``open`` object for the samples from ``since`` (s; the machine's hand-over) on:
    the plate reaction's rate against ``lambda g v`` over the run and per :data:`CHUNK`,
    the moving mass, and the largest offset ``M_tail a/(lambda v^2)`` by which the
    fountain's tensions differ from a tail pulling at the end (the tail's inertia is
    carried by the machine: :mod:`chainfountain.sim.slide_away`). ``None`` with fewer than
    three samples after ``since``."""
    S = [s for s in samples if s.t >= since - 1e-9 and math.isfinite(s.plate_reaction)]
    if len(S) < 3:
        return None
    t = np.array([s.t for s in S])
    R = np.array([s.plate_reaction for s in S])
    v = np.array([s.speed_mean for s in S])
    chunks, centres, means, masses = [], [], [], []
    edges = np.arange(t[0], t[-1] + 1e-9, CHUNK)
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        sel = (t >= a - 1e-9) & (t <= b + 1e-9)
        if sel.sum() < 3:
            continue
        rate, pred = _rate(t[sel], R[sel]), lam * g * float(v[sel].mean())
        chunks.append({"t_s": [float(a), float(b)], "rate_N_per_s": rate,
                       "predicted_N_per_s": pred, "rel": rate / pred - 1.0})
        centres.append(0.5 * (a + b))
        means.append(float(v[sel].mean()))
        masses.append(float(R[sel][-1]) / g)
    offset = math.nan
    if len(means) > 1:
        # the machine's acceleration from the windows' mean speeds (a slope inside one
        # window follows the fountain's own sway of a few mm/s, not the machine)
        accel = np.gradient(np.array(means), np.array(centres))
        offset = float(np.max(np.abs(np.array(masses) * accel)
                              / (lam * np.array(means) ** 2)))
    rate, pred = _rate(t, R), lam * g * float(v.mean())
    return {
        "window": [float(t[0]), float(t[-1])],
        "speed_law_m_per_s": v_law,
        "speed_m_per_s": [float(v[: max(1, len(v) // 20)].mean()),
                          float(v[-max(1, len(v) // 20):].mean())],
        "tail_reaction_N": [float(R[0]), float(R[-1])],
        "tail_reaction_rate_N_per_s": rate,
        "tail_reaction_rate_predicted": pred,
        "chunks": chunks,
        "worst_chunk_rel": max((abs(c["rel"]) for c in chunks), default=math.nan),
        "moving_mass_kg": float(R[-1]) / g,
        "tail_inertia_offset_bar": offset,
    }
