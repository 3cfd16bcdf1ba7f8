"""A step in the upper cart's force against the energy balance (issue 4, step 2).

Runs :func:`research.rigs.cart_step.cart_step` on ``apparatus_floor`` (long strand,
``plate_links = 0``, unless ``--plate-links``) for each cart mass and prints, per window,
the measured deceleration over the predicted one for the energy balance (gain 1/2, with
and without the pick-up's speed dependence), ``CART_GAIN_2CM`` (the rig law's steady
gain for these links, 0.526; 0.68 when read through biased contacts:
``docs/apparatus.md``, "Contact impulses") and the paper's momentum
law (gain 1), beside the pair's tension readings. ``docs/apparatus.md``,
"Unbalanced carts", quotes it::

    .venv/bin/python -m research.cart_step_study                  # 60 g, about 10 s
    .venv/bin/python -m research.cart_step_study --masses 0.025 0.04 0.06
    .venv/bin/python -m research.cart_step_study --plate-links 20   # the treadmill
    .venv/bin/python -m research.cart_step_study --figure docs/img/cart_step.png
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

from chainfountain.level import io
from chainfountain.level.io import LevelError
from chainfountain.level.library import shipped_dir
from chainfountain.sim.apparatus import CART_GAIN_2CM, RunEnded
from chainfountain.study.changes import laid_on_path
from research.rigs.cart_step import CartStep, cart_step

LEVELS = shipped_dir()


def _positive(text: str) -> float:
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not x > 0.0:
        raise argparse.ArgumentTypeError(f"{text!r}: must be > 0")
    return x


def table(steps: dict[float, CartStep], windows: list[float]) -> None:
    print("| cart g | window s | measured m/s^2 | energy 1/2 | 1/2, no drag | "
          f"rig gain {CART_GAIN_2CM:g} | paper gain 1 | M_up kg | closure kg | "
          "pick-up gain | dT_exit N | dT_launch N |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for mass, s in steps.items():
        for w in windows:
            c = s.until(w)
            print(f"| {mass * 1e3:g} | {w:g} | {c.deceleration:+.4f} | {c.ratio(0.5):.3f} | "
                  f"{c.ratio(0.5, drag=False):.3f} | {c.ratio(CART_GAIN_2CM):.3f} | "
                  f"{c.ratio(1.0):.3f} | {c.m_up:.3f} | {c.closure_mass:.3f} | "
                  f"{c.pickup_gain:.3f} | {c.dT_exit:+.4f} | {c.dT_launch:+.4f} |")


def figure(steps: dict[float, CartStep], out: Path, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from chainfountain.atomic import atomic_path

    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    for i, (mass, s) in enumerate(steps.items()):
        col = f"C{i}"
        ax.plot(s.t, s.dv, color=col, lw=1.0, label=f"{mass * 1e3:g} g: measured")
        ax.plot(s.t, s.predicted(0.5), color=col, ls="--", lw=1.0,
                label="energy balance (gain 1/2)" if i == 0 else None)
        ax.plot(s.t, s.predicted(CART_GAIN_2CM), color=col, ls=":", lw=1.0,
                label=f"CART_GAIN_2CM {CART_GAIN_2CM:g}" if i == 0 else None)
    ax.set_xlabel("time after the cart was made heavier (s)")
    ax.set_ylabel("chain speed change (m/s)")
    ax.set_title(title, fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    with atomic_path(out) as tmp:
        fig.savefig(tmp, dpi=90)
    plt.close(fig)
    print(f"wrote {out}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="apparatus_floor",
                    help="a floor-variant apparatus level in levels/ (default apparatus_floor)")
    ap.add_argument("--masses", type=_positive, nargs="+", default=[0.06],
                    help="upper cart masses after the switch, kg (default 0.06)")
    ap.add_argument("--plate-links", type=int, default=0,
                    help="apparatus.plate_links (0: the long strand, as the test)")
    ap.add_argument("--switch", type=_positive, default=1.0, help="switch time, s")
    ap.add_argument("--windows", type=_positive, nargs="+", default=[0.3, 0.6, 1.0],
                    help="comparison windows after the switch, s")
    ap.add_argument("--figure", type=Path, default=None, help="write a PNG of the runs")
    args = ap.parse_args(argv)
    if args.plate_links < 0:
        ap.error(f"--plate-links {args.plate_links}: must be >= 0")
    try:
        cfg = laid_on_path(io.load(LEVELS / f"{args.level}.toml")).sim
    except LevelError as e:
        ap.error(f"--level {args.level!r}: {e}")
    cfg = dataclasses.replace(cfg, apparatus=dataclasses.replace(
        cfg.apparatus, plate_links=args.plate_links))
    window = max(args.windows)
    steps: dict[float, CartStep] = {}
    t0 = time.perf_counter()
    for m in args.masses:
        print(f"cart {m * 1e3:g} g: running ...", file=sys.stderr, flush=True)
        try:
            steps[m] = cart_step(cfg, m, args.switch, window)
        except ValueError as e:
            ap.error(f"--level {args.level!r}: {e}")
        except RunEnded as e:
            print(f"cart {m * 1e3:g} g: the run ended: {e}", file=sys.stderr)
            return 1
    table(steps, sorted(args.windows))
    print(f"\n{args.level}, plate_links {args.plate_links}, switch at {args.switch:g} s from "
          f"{cfg.carts[0].mass * 1e3:g} g; wall {time.perf_counter() - t0:.0f} s")
    if args.figure is not None:
        figure(steps, args.figure, f"{args.level} (plate_links {args.plate_links}): upper cart "
               f"{cfg.carts[0].mass * 1e3:g} g -> heavier at {args.switch:g} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
