"""Pick-up and put-down forces of a roller rolling on a resting chain, against the paper.

Runs :class:`research.rigs.pickup.RollerRig` (paper section "Pick-Up and
Pull-Down Forces") at alpha = 0, 45, 90 deg, with and without a cart force,
prints a Markdown table and writes ``docs/img/pickup.png``::

    .venv/bin/python -m research.pickup_study            # ~1 min
    .venv/bin/python -m research.pickup_study --no-figure
    .venv/bin/python -m research.pickup_study --putdown-2cm   # ~25 s, no figure
    .venv/bin/python -m research.pickup_study --pickup-2cm --iterations 20
    .venv/bin/python -m research.pickup_study --pickup-2cm-law   # ~4 min, no figure

``--pickup-2cm``: pick-up at alpha = 0 with the same chain, 3 m/s, dt 0.5 ms, for cart
forces 0-0.3, and the line ``Tbar = p + G*Fbar_c`` (carriage mass ``0.02 + F/(g sin 30
deg)``, the rope-tied cart). ``--iterations`` sets the solver iterations of both studies
(default 10; the fold preset runs at 20).

``--pickup-2cm-law``: the rig law for the presets' chain, ``PICKUP_RIG_2CM`` and
``CART_GAIN_2CM`` (``chainfountain.sim.apparatus``): 19 pick-up runs of 6 s at 2.6-5.1
m/s and ``Fbar_c`` 0-0.5 (2 cm links, dt 0.5 ms, 10 iterations), the tension read
through the contacts, and the weighted fit ``Tbar = p_inf + R/(lambda v^2) +
G*Fbar_c`` (errors from six 1-s blocks per run, scaled by the fit's chi2/dof).

``--putdown-2cm``: put-down at alpha = 0 with the apparatus presets' chain (2 cm rod
links, friction 0.6) at 3 m/s, dt 0.5 ms, 10 iterations, for several cart forces, and
the line ``Tbar = d + G_d*Fbar_c`` through the steady runs (``PUTDOWN_RIG_2CM``).
"""

from __future__ import annotations

import argparse
import math
import sys
import time

import numpy as np

from chainfountain.sim.config import ChainConfig
from research.rigs.pickup import RigConfig, RigResult, lossless_bar, run_rig

LAM, V = 0.05, 5.0


def one(mode: str, alpha_deg: float, f_bar: float = 0.0, L: float = 0.01) -> RigResult:
    ch = ChainConfig(link_length=L, linear_density=LAM, friction=1.0, link_radius=0.002)
    cfg = RigConfig(mode=mode, angle=math.radians(alpha_deg), speed=V,
                    cart_force=f_bar * LAM * V * V, chain=ch)
    return run_rig(cfg, duration=0.6, settle=0.25)


def config_2cm(mode: str, v: float, f: float, iterations: int = 10,
               rest_length: float | None = None) -> RigConfig:
    """Rig at the apparatus presets' scale: 2 cm rod links, friction 0.6, dt 0.5 ms, cart
    force ``f*lambda*v**2`` (pick-up: the rope-tied cart's mass ``F/(g sin 30 deg)`` on the
    20 g carriage)."""
    from chainfountain.sim.config import SolverConfig

    ch = ChainConfig(link_length=0.02, linear_density=LAM, friction=0.6, link_radius=0.002)
    sol = SolverConfig(dt=0.0005, iterations=iterations, joint_error_bias=1e-10,
                       collision_slop=1e-4)
    F = f * LAM * v * v
    extra: dict = {"carriage_mass": 0.02 + F / (9.81 * 0.5)} if mode == "pickup" else {}
    if rest_length is not None:
        extra["rest_length"] = rest_length
    return RigConfig(mode=mode, speed=v, cart_force=F, chain=ch, solver=sol, **extra)


def rig_2cm(mode: str, forces: tuple[float, ...], v: float = 3.0, iterations: int = 10,
            duration: float = 3.0, fit_from: float = 0.0) -> int:
    """Pick-up (alpha = 0) or put-down rig at the apparatus presets' scale (2 cm links,
    dt 0.5 ms); prints a table and the fit ``Tbar = intercept + G*Fbar_c`` over
    ``Fbar_c >= fit_from``."""
    word = "exit" if mode == "pickup" else "entry"
    print(f"| Fbar_c | chain speed m/s | v_R/v | Tbar {word} (pivots) | halves | "
          "from contacts |")
    print("|---|---|---|---|---|---|")
    fit = []
    for f in forces:
        cfg = config_2cm(mode, v, f, iterations)
        r = run_rig(cfg, duration=duration, settle=0.25 if mode == "pickup" else 0.5)
        h = len(r.t) // 2
        halves = [float(np.mean(r.pivot_force[s])) / (LAM * float(np.mean(np.abs(r.v[s]))) ** 2)
                  for s in (slice(0, h), slice(h, None))]
        print(f"| {f:.2f} | {r.speed:.3f} | {r.roller_ratio:.3f} | {r.pivot_bar:.3f} | "
              f"{halves[0]:.3f} / {halves[1]:.3f} | {r.force_bar:.3f} |")
        sys.stdout.flush()
        if f >= fit_from - 1e-9:
            fit.append((f, r.pivot_bar))
    if len(fit) >= 2:
        G, c = np.polyfit([x for x, _ in fit], [y for _, y in fit], 1)
        print(f"\nTbar = {c:.3f} + {G:.3f}*Fbar_c (Fbar_c >= {fit_from:g})")
    return 0


LAW_RUNS = ([(2.6, f) for f in (0.0, 0.1, 0.2, 0.3)] + [(2.75, f) for f in (0.0, 0.1, 0.2, 0.3)]
            + [(2.9, f) for f in (0.0, 0.1, 0.2, 0.3)] + [(3.2, f) for f in (0.0, 0.1, 0.2, 0.3)]
            + [(5.1, f) for f in (0.0, 0.2, 0.5)])
"""(chain speed m/s, cart force over ``lambda v^2``) of ``--pickup-2cm-law``."""


def law_2cm(duration: float = 6.0) -> int:
    """The pick-up rig law for the presets' chain: table of runs and weighted fit."""
    print("| v m/s | Fbar_c | chain speed m/s | v_R/v | Tbar exit | s.e. | pivots |")
    print("|---|---|---|---|---|---|---|")
    rows = []
    t0 = time.perf_counter()
    for v, f in LAW_RUNS:
        cfg = config_2cm("pickup", v, f, rest_length=2.0 * duration)
        r = run_rig(cfg, duration=duration + 0.25, settle=0.25)
        lv2 = LAM * r.speed**2
        blocks = [float(np.mean(b)) / lv2 for b in np.array_split(r.force, 6)]
        se = float(np.std(blocks, ddof=1) / math.sqrt(len(blocks)))
        rows.append((r.speed, cfg.cart_force / lv2, r.force_bar, se))
        print(f"| {v:g} | {f:g} | {r.speed:.3f} | {r.roller_ratio:.3f} | {r.force_bar:.4f} | "
              f"{se:.4f} | {r.pivot_bar:.4f} |", flush=True)
    v, f, T, se = (np.array(c) for c in zip(*rows, strict=True))
    X = np.column_stack([np.ones_like(v), 1.0 / (LAM * v * v), f])
    A = X / se[:, None]
    c = np.linalg.lstsq(A, T / se, rcond=None)[0]
    res = (T - X @ c) / se
    chi2 = float(res @ res) / (len(T) - 3)
    err = np.sqrt(np.diag(np.linalg.inv(A.T @ A)) * max(chi2, 1.0))
    print(f"\nTbar = {c[0]:.4f} (+-{err[0]:.4f}) + {c[1]:.4f} (+-{err[1]:.4f}) N/(lambda v^2) "
          f"+ {c[2]:.4f} (+-{err[2]:.4f}) Fbar_c; chi2/dof {chi2:.2f}, rms residual "
          f"{float(np.sqrt(np.mean((T - X @ c) ** 2))):.4f}; wall "
          f"{time.perf_counter() - t0:.0f} s")
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-figure", action="store_true")
    ap.add_argument("--putdown-2cm", action="store_true",
                    help="put-down at the apparatus presets' scale (2 cm links, 3 m/s)")
    ap.add_argument("--pickup-2cm", action="store_true",
                    help="pick-up at the apparatus presets' scale (2 cm links, 3 m/s)")
    ap.add_argument("--pickup-2cm-law", action="store_true",
                    help="the pick-up rig law for the presets' chain (19 runs, ~4 min)")
    ap.add_argument("--iterations", type=int, default=10,
                    help="solver iterations for --putdown-2cm / --pickup-2cm")
    ap.add_argument("--duration", type=float, default=None,
                    help="averaging time (s) for --putdown-2cm / --pickup-2cm")
    ap.add_argument("--out", default="docs/img/pickup.png")
    args = ap.parse_args(argv)
    if args.putdown_2cm:
        return rig_2cm("putdown", (0.1, 0.2, 0.3, 0.4, 0.5), iterations=args.iterations,
                       duration=args.duration or 3.0, fit_from=0.3)
    if args.pickup_2cm_law:
        return law_2cm()
    if args.pickup_2cm:
        return rig_2cm("pickup", (0.0, 0.1, 0.2, 0.3), iterations=args.iterations,
                       duration=args.duration or 2.0)
    t0 = time.perf_counter()
    rows = []
    print("| mode | alpha deg | cart F/(lambda v^2) | L mm | v_R/v | paper v_R/v | "
          "F/(lambda v^2) (pivots) | from contacts | paper | lossless |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    runs = [("pickup", a, 0.0, 0.01) for a in (0, 45, 90)]
    runs += [("pickup", a, 0.0, 0.005) for a in (0, 90)]
    runs += [("pickup", 0, f, 0.01) for f in (0.2, 0.5)]
    runs += [("putdown", a, f, 0.01) for a in (0, 45, 90) for f in (0.1, 0.3, 0.5)]
    for mode, a, f, L in runs:
        r = one(mode, a, f, L)
        ca = math.cos(math.radians(a))
        paper = 1.0 / (1.0 + ca) if mode == "pickup" else 0.5
        rows.append((mode, a, f, L, r.roller_ratio, r.pivot_bar, paper))
        print(f"| {mode} | {a} | {f:.1f} | {L * 1e3:.0f} | {r.roller_ratio:.3f} | "
              f"{1 / (1 + ca):.3f} | {r.pivot_bar:.3f} | {r.force_bar:.3f} | {paper:.3f} | "
              f"{lossless_bar(mode, math.radians(a), f):.3f} |")
        sys.stdout.flush()
    print(f"\nwall {time.perf_counter() - t0:.0f} s")
    if args.no_figure:
        return 0
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(1, 2, figsize=(9, 3.6), dpi=90)
    al = np.linspace(0, 90, 50)
    ax = axs[0]
    ax.plot(al, 1 / (1 + np.cos(np.radians(al))), "--", color="#d62728",
            label="paper: 1/(1+cos alpha)")
    ax.plot(al, [lossless_bar("pickup", math.radians(x), 0.0) for x in al], ":", color="k",
            label="energy balance, no loss")
    for mode, a, f, L, _, fb, _ in rows:
        if mode == "pickup" and f == 0.0:
            ax.plot(a, fb, "o" if L == 0.01 else "s", mfc="none" if L < 0.01 else None,
                    color="#1f77b4", label=f"sim, L = {L * 1e3:.0f} mm")
    h, lab = ax.get_legend_handles_labels()
    keep = dict(zip(lab, h, strict=True))
    ax.legend(keep.values(), keep.keys(), fontsize=7)
    ax.set_xlabel("alpha (deg)")
    ax.set_ylabel("F / (lambda v^2)")
    ax.set_title("pick-up, no cart", fontsize=9)
    ax.grid(alpha=0.3)
    ax = axs[1]
    fs = np.linspace(0, 0.5, 10)
    ax.plot(fs, 0.5 + fs, "--", color="#d62728", label="paper: 1/2 + F_c (put-down)")
    ax.plot(fs, [lossless_bar("pickup", 0.0, f) for f in fs], ":", color="k",
            label="energy balance, no loss, 0 deg: 1/4 + F_c/2")
    for mode, marker, col in (("pickup", "o", "#1f77b4"), ("putdown", "^", "#2ca02c")):
        for a in (0, 45, 90):
            pts = [(f, fb) for m, aa, f, L, _, fb, _ in rows if m == mode and aa == a
                   and L == 0.01 and (mode == "putdown" or a == 0)]
            if pts:
                x, y = np.array(pts).T
                ax.plot(x, y, marker + "-", color=col, alpha=0.4 + a / 180,
                        label=f"sim {mode} {a} deg")
    ax.set_xlabel("cart force F_c / (lambda v^2)")
    ax.set_ylabel("strand tension / (lambda v^2), pivots")
    ax.set_title("with a cart force on the roller", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    from chainfountain.atomic import atomic_path

    with atomic_path(args.out) as tmp:
        fig.savefig(tmp)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
