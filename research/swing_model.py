"""The landing swing against the linear model of the stored-length mode.

    .venv/bin/python -m research.swing_model                  # ~10 s
    .venv/bin/python -m research.swing_model --level apparatus_fold --seconds 2

Runs a 'fold' level for ``--seconds`` (default 3) to read what the model needs: the
moving chain on either side of the fountain at 1 s (links faster than ``v/4``, left of
the fountain start / right of its end), the rollers, carriages and carts referred to
the chain speed (``(m_roller + m_carriage + m_cart)/4 + m_roller/8``), the speed and the
mean vertex height over 1 s to the end (the catenary parameter ``a = h/(1/cos(theta) -
1)``, hence the fountain's spring ``K``). Then prints
:func:`chainfountain.theory.swing.swing_mode` for the paper's rig laws (``p = d =
1/2``) and for this model's (the pick-up's ``lambda v^2``-part ``p`` = 0.27 from
``PICKUP_RIG_2CM``, its ``p_inf``: the rolling resistance does not grow with the speed;
or 0.28 from the zero-force fit over 2-5 m/s; the put-down's ``d`` = 0.172 from
``PUTDOWN_RIG_2CM`` taken to scale as ``lambda v^2``, which was measured at 3 m/s only),
with and without the launch tension's measured lag (0.039 s). What the simulation
measured for ``apparatus_special`` (docs/apparatus.md, "The landing swing"): period
2.08-2.22 s, growth +0.14 /s (walls) and +0.02 ... +0.26 /s (joint guide, starts
2.97-3.06 m/s), the pick-up strand swinging 2.6 times as far as the fold strand and
137-138 deg from it.
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from chainfountain.level import io, library
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus import PUTDOWN_RIG_2CM, pickup_rig_2cm_drag
from chainfountain.theory.swing import fountain_spring, swing_mode

MEASURED_LAG = 0.039
"""Measured lag of the launch tension behind the stored chain (s)."""
PICKUP_ZERO_FORCE_P = 0.28
"""``lambda v^2``-part of the pick-up's exit tension from the zero-force rig runs at
2.0-5.0 m/s (``0.28 + 0.0175 N/(lambda v^2)``, docs/apparatus.md, "Rig law for the
presets' links")."""


def pickup_p(v: float) -> float:
    """``(dT_exit/dv)/(2 lambda v)`` from :data:`PICKUP_RIG_2CM`: ``p(v) + v p'(v)/2``,
    which is its ``p_inf``."""
    return pickup_rig_2cm_drag(v, 1.0) / (2.0 * v)


def _moving(sim: Simulation, v: float) -> tuple[float, float]:
    """Moving chain mass (kg) left of the fountain start and right of its end."""
    app = sim.apparatus
    m = sim.chain.mass
    x_end = app.end[0]
    up = down = 0
    for lk in sim.chain.links:
        if lk.body.velocity.length < 0.25 * v:
            continue
        x = lk.body.position.x
        if x < 0.0:
            up += 1
        elif x > x_end:
            down += 1
    return up * m, down * m


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--level", default="apparatus_special", help="a 'fold' level name or path")
    ap.add_argument("--seconds", type=float, default=3.0)
    args = ap.parse_args(argv)
    try:
        level = io.load(library.resolve(args.level))
    except io.LevelError as exc:
        print(f"--level: {exc}", file=sys.stderr)
        return 2
    cfg = level.sim
    if cfg.kind == "apparatus":  # the fold's own swing: without the presets' damper
        cfg.apparatus.swing_damper = 0.0
    if cfg.kind != "apparatus" or cfg.apparatus.variant != "fold":
        print(f"--level: {args.level!r} is not a 'fold' apparatus level", file=sys.stderr)
        return 2
    if not args.seconds >= 1.5:
        print(f"--seconds: {args.seconds} is too short (allowed: 1.5 or more)", file=sys.stderr)
        return 2
    sim = Simulation(cfg)
    rec = Recorder(sim, profiles=False)
    sim.advance(1.0)
    v1s = sim.apparatus.strand_speed
    s_up, s_down = _moving(sim, v1s)
    sim.advance(args.seconds - 1.0)
    samples = [s for s in rec.samples if s.t >= 1.0]
    v = float(np.mean([s.speed_mean for s in samples]))
    h = float(np.mean([s.vertex_y for s in samples]))
    a = cfg.apparatus
    theta = a.launch_angle
    lam = cfg.chain.linear_density
    r1 = (a.roller_mass + a.carriage_mass + cfg.carts[0].mass) / 4 + a.roller_mass / 8
    r2 = (a.roller_mass + a.carriage_mass + cfg.carts[1].mass) / 4 + a.roller_mass / 8
    m1, m2 = s_up + r1, s_down + r2
    cat = h / (1.0 / math.cos(theta) - 1.0)
    K = fountain_spring(cat, theta, a.drop, lam, float(cfg.gravity))
    print(f"{level.meta.name}: v {v:.3f} m/s, vertex {h:.3f} m (a = {cat:.3f} m), "
          f"K {K:.3f} N/m; moving chain {1e3 * s_up:.0f} / {1e3 * s_down:.0f} g, "
          f"referred {1e3 * r1:.1f} / {1e3 * r2:.1f} g: m1 {1e3 * m1:.0f} g, "
          f"m2 {1e3 * m2:.0f} g\n")
    print("| rig laws | p | d | lag s | period s | growth 1/s | speed selection 1/s "
          "| abs(dv1/dv2) | phase deg |")
    print("|---|---|---|---|---|---|---|---|---|")
    p_rig, p0, d_rig = round(pickup_p(v), 2), PICKUP_ZERO_FORCE_P, PUTDOWN_RIG_2CM[0]
    rows = [("paper", 0.5, 0.5), ("this model's (pick-up slope)", p_rig, d_rig),
            ("this model's (pick-up zero-force fit)", p0, d_rig),
            (f"pick-up {p0}, paper's put-down", p0, 0.5)]
    for name, p, d in rows:
        for lag in (0.0, MEASURED_LAG):
            s = swing_mode(m1, m2, K, lam, v, p=p, d=d, delay=lag)
            print(f"| {name} | {p} | {d} | {lag} | {s.period:.2f} | {s.growth:+.3f} | "
                  f"{s.selection:+.3f} | {s.ratio:.2f} | {s.phase:+.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
