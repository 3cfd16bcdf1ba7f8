"""The paper's fountains A-C (Fig. "schematic_chain_fountain") simulated at the same scaled
stiffness, beside the steady stiff-chain theory (:mod:`chainfountain.theory.stiff`).

Each fountain is the shipped ``fountain_d`` level (the paper's example launch: 5.10 m/s at
82.0 deg onto a floor 2 m below pulling with ``Tbar_E = 0.123``; 4-mm links, 15-us steps)
with joint springs ``c = (e2 + L^2/12) lambda v^2/L`` (so that the BVP's ``e`` is the
paper's ``e2``) and, with ``--damping``, dampers ``d``. It starts on the catenary, runs
``--seconds`` and averages its last ``--window`` seconds. Prints one row per fountain and,
with ``--out``, writes the mean shapes (``.npz``) that ``--figure`` draws over the BVP's.

    python -m research.paper_stiff_fountains --seconds 6 --out /tmp/ad.npz --figure /tmp/ad.png
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

E2 = {"A": 2e-4, "B": 4e-4, "C": 8e-4, "D": 0.0}
"""The paper's ``e2`` (m^2) of fountains A-D (its ``e1`` has no bending origin; not here)."""


def simulate(name: str, seconds: float, window: float, damping: float) -> dict[str, object]:
    """Run fountain ``name`` and return its figures and mean shape (launch frame)."""
    from chainfountain.level import io, library
    from chainfountain.sim import Recorder, Simulation
    from chainfountain.study.changes import with_changes

    base = io.load(library.resolve("fountain_d"))
    L, lam, v = base.sim.chain.link_length, base.sim.chain.linear_density, base.sim.feed.speed
    e2 = E2[name]
    c = (e2 + L * L / 12.0) * lam * v * v / L if e2 > 0.0 else 0.0
    level = with_changes(base, {"chain.bending_stiffness": c,
                                "chain.bending_damping": damping}, where=name)
    sim = Simulation(level.sim)
    rec = Recorder(sim, max_profiles=4 * int(window / level.sim.recording.sample_interval))
    t = time.perf_counter()
    sim.advance(seconds)
    wall = time.perf_counter() - t
    s = rec.summary(window=window)
    early = rec.summary(window=window / 2.0) if seconds > 2 * window else s
    return {"name": name, "e2": e2, "c": c, "d": damping, "L": L, "dt": level.sim.solver.dt,
            "h": s.vertex_y, "vertex_x": s.vertex_x, "l": s.landing_x, "v": s.speed_mean,
            "window": (s.t0, s.t1), "wall": wall, "x": s.extras["x"], "y": s.extras["y"],
            "h_last_half": early.vertex_y}


def theory(name: str, damping: float, L: float) -> tuple[float, float, np.ndarray, np.ndarray]:
    """The BVP's (or, for D, the catenary's) vertex height, landing and curve."""
    from chainfountain.figures.paper import example_fountain
    from chainfountain.theory import stiff

    f = example_fountain()
    e2 = E2[name]
    if e2 == 0.0 and damping == 0.0:
        x, y = f.curve(400)
        x0, y0 = f.start
        return f.h, f.l, x - x0, y - y0
    if damping == 0.0:
        from chainfountain.figures.paper import paper_stiff
        sol = paper_stiff(e2)
    else:
        try:
            sol = stiff.stiff_fountain(f.v, f.alpha0, f.H, f.TE_bar, e2,
                                       delta=stiff.scaled_damping(damping, L, 0.05, f.v),
                                       ec=e2 + L * L / 12.0)
        except stiff.NoSteadyFountain:
            sol = None
    if sol is None:
        nan = float("nan")
        return nan, nan, np.array([]), np.array([])
    return sol.h, sol.l, sol.x, sol.y


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=6.0, help="simulated seconds a run")
    ap.add_argument("--window", type=float, default=2.0, help="averaged last seconds")
    ap.add_argument("--damping", type=float, default=0.0, help="joint damper d (N*m*s/rad)")
    ap.add_argument("--only", nargs="*", default=list(E2), choices=list(E2))
    ap.add_argument("--out", type=Path, help="write the mean shapes here (.npz)")
    ap.add_argument("--figure", type=Path, help="draw the shapes over the theory here")
    a = ap.parse_args(argv)
    rows = []
    for name in a.only:
        r = simulate(name, a.seconds, a.window, a.damping)
        print(f"{name}: measured {r['h']:.4f} {r['l']:.4f} {r['v']:.3f}", flush=True)
        th, tl, _, _ = theory(name, a.damping, float(r["L"]))
        rows.append(r)
        print(f"{name}: e2={r['e2']:.0e} c={r['c']:.4f} d={r['d']:g}  sim h={r['h']:.4f} "
              f"l={r['l']:.4f} v={r['v']:.3f} (window {r['window'][0]:.1f}-"
              f"{r['window'][1]:.1f} s; h over its last half {r['h_last_half']:.4f})  "
              f"theory h={th:.4f} l={tl:.4f}  sim/theory-1: h {r['h'] / th - 1:+.2%} "
              f"l {r['l'] / tl - 1:+.2%}  [{r['wall']:.0f} s wall]", flush=True)
    if a.out:
        np.savez(a.out, **{f"{r['name']}_{k}": np.asarray(r[k]) for r in rows
                           for k in ("x", "y", "h", "l", "c", "e2")})
    if a.figure:
        draw(rows, a.damping, a.figure)


def draw(rows: list[dict[str, object]], damping: float, path: Path) -> None:
    """The simulated mean shapes (dots) over the theory's curves (lines)."""
    from chainfountain.figures._io import plt

    fig, ax = plt.subplots(figsize=(6.4, 5.0), layout="constrained")
    for r, col in zip(rows, ("tab:green", "tab:red", "tab:purple", "tab:blue"), strict=False):
        _, _, x, y = theory(str(r["name"]), damping, float(r["L"]))
        ax.plot(x, y, color=col, lw=1.2, label=f"{r['name']}: theory (e2={r['e2']:.0e})")
        ax.plot(r["x"], r["y"], ".", color=col, ms=2, label=f"{r['name']}: simulated")
    ax.set_xlim(-0.05, 0.45)
    ax.set_ylim(-0.6, 0.5)
    ax.set_xlabel("x from launch [m]")
    ax.set_ylabel("y from launch [m]")
    ax.legend(fontsize=7)
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
