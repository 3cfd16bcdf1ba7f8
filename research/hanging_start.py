"""Starting the gripped fold from rest with the chain hanging between the machine's guides.

A prototype (not in the package): its own starter (a
:class:`~chainfountain.sim.apparatus.Starter`), the path it lays the chain along and a
:class:`~chainfountain.sim.apparatus.Tuning`, passed to the apparatus. The chain lies at
rest along its whole path: on the upper table, round the pick-up roller, up the upper
guide, then *hanging* under its weight from the fountain start to the end guide's mouth (a
catenary through the two points, ``--slack`` longer than the chord), through the lower
guide and round the folding roller onto the lower table. A starter motor runs both rollers
up from rest to ``apparatus.speed`` over 0.5 s (the upper guide's links, as the floor
presets' starter, and the folding roller's carriage at half the speed) and lets go at
``--hand-over`` s; then only the carts, the brake and the fall drive the chain.

Prints the chain speed's and the landing's (``dr``, the entering link's offset from the
first turn's radius) 0.5-s means, and how the run ended.

Usage::

    python research/hanging_start.py --seconds 12 --hand-over 1.2 --keep-capture --close 20 \
        --drive-lower carriage --set apparatus.end_follow=0     # formed and held 12 s
    python research/hanging_start.py ... --dt-factor 0.5           # did not rise
"""

from __future__ import annotations

import argparse
import functools
import math
from typing import Any

import numpy as np
from scipy.optimize import brentq

from chainfountain.errors import RunEnded
from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim import Simulation
from chainfountain.sim.apparatus import Apparatus, Layout, Starter, Tuning, starter
from chainfountain.sim.config import SimConfig
from chainfountain.study.changes import laid_on_path, with_changes

LEVELS = shipped_dir()


def hanging_path(xe: float, ye: float, slack: float, n: int = 400) -> np.ndarray:
    """Points of a hanging catenary from (0, 0) to (xe, ye), ``slack`` times longer than
    the chord (the first point left out)."""
    chord = math.hypot(xe, ye)
    ell = chord * (1.0 + slack)
    # sqrt(ell^2 - dy^2) = 2 a sinh(xe / (2 a))
    k = math.sqrt(ell * ell - ye * ye)
    a = brentq(lambda a: 2.0 * a * math.sinh(xe / (2.0 * a)) - k, 1e-3, 1e4)
    # y = c + a cosh((x - x0)/a); y(xe) - y(0) = ye
    x0 = brentq(lambda x0: a * (math.cosh((xe - x0) / a) - math.cosh(-x0 / a)) - ye,
                -50.0, 50.0)
    c = -a * math.cosh(-x0 / a)
    xs = np.linspace(0.0, xe, n)[1:]
    return np.column_stack((xs, c + a * np.cosh((xs - x0) / a)))


class Start:
    """The hanging start's settings, and what it measured when the chain was laid."""

    def __init__(self, slack: float, hand_over: float, capture: tuple[float, float],
                 keep: bool, shape: str, lag_factor: float, fade: tuple[float, float],
                 boost: float, drive_lower: str, steer: float, ramp: float) -> None:
        self.slack, self.hand_over, self.capture, self.keep = slack, hand_over, capture, keep
        self.shape, self.lag_factor, self.fade, self.boost = shape, lag_factor, fade, boost
        self.drive_lower, self.steer, self.ramp = drive_lower, steer, ramp
        self.lag = 0.0
        """How much later (s) the lower roller starts than the upper, so that the loop
        gets the fountain's length (set when the chain is laid)."""

    def fountain_path(self, layout: Layout, laid: np.ndarray) -> np.ndarray:
        """The chain's path between the guides (``Apparatus(fountain_path=...)``): hanging,
        or the predicted fountain's."""
        if self.shape == "fountain":
            self.lag = 0.0
            return laid
        hang = hanging_path(layout.end[0], layout.end[1], self.slack)

        def arc(p: np.ndarray) -> float:
            p = np.vstack(([0.0, 0.0], p))
            return float(np.sum(np.hypot(*np.diff(p, axis=0).T)))

        # the lower roller starts later, so that the loop gets the fountain's length
        self.lag = self.lag_factor * (arc(laid) - arc(hang)) / float(layout.cfg.speed)
        return hang

    def starter(self) -> type[Starter]:
        """The starter motor of this start (``Apparatus(starter=...)``)."""
        st = self

        class HangingStarter(Starter):
            """Runs both rollers up from rest and lets go at ``hand_over``."""

            def __init__(self, *args: Any) -> None:
                super().__init__(*args)
                assert self.fold is not None, "the hanging start is for 'fold' levels"
                self.starting = True
                self.shipped_capture = self.fold.capture
                self.fold.capture = (st.capture[0], math.radians(st.capture[1]))

            @property
            def speed(self) -> float:
                return st.boost * float(self.cfg.speed) * min(1.0, self.clock.t / st.ramp)

            def drive(self) -> None:
                super().drive()
                fold, lo = self.fold, self.lower
                assert fold is not None and lo is not None
                v_full = st.boost * float(self.cfg.speed)
                v = v_full * min(1.0, max(0.0, self.clock.t - st.lag) / st.ramp)
                if st.drive_lower == "none":
                    return
                if st.drive_lower == "hand":  # hold back the lower cart's push until it runs
                    f = -lo.direction * lo.force * (1.0 - v / v_full)
                    lo.carriage.apply_force_at_world_point((f, 0.0), lo.carriage.position)
                    if lo.carriage.velocity.x < 0.0:  # a pawl: it does not roll back
                        lo.carriage.velocity = (0.0, 0.0)
                    return
                if st.drive_lower == "carriage":
                    lo.carriage.velocity = (0.5 * v, 0.0)
                    return
                if st.drive_lower == "steer":  # store chain while the fountain lands short
                    f = min(1.2, max(0.5, 1.0 - st.steer * fold.mouth_dr))
                    lo.carriage.velocity = (0.5 * v * f, 0.0)
                    return
                starter.run_along(fold.guide, fold.held, v)  # the chain in the lower guide

            def check(self, absorbed: int, chain_speed: float) -> None:
                if self.clock.t >= st.hand_over:
                    self.starting = False
                    if not st.keep and self.fold is not None:
                        self.fold.capture = self.shipped_capture

            def before_step(self) -> None:
                super().before_step()
                t = self.clock.t - st.hand_over
                c0, span = st.fade
                if self.starting or t >= span or c0 <= 0.0 or self.lower is None:
                    return
                c = c0 * (1.0 - t / span)
                u_s = 0.5 * float(self.cfg.speed)
                for unit in (self.upper, self.lower):
                    body = unit.carriage
                    body.apply_force_at_world_point((-c * (body.velocity.x - u_s), 0.0),
                                                    body.position)

        return HangingStarter


def simulation(cfg: SimConfig, start: Start, tuning: Tuning) -> Simulation:
    """A simulation of ``cfg`` whose apparatus is built with ``start``'s path and starter
    and with ``tuning`` (the simulation's ``builders``)."""
    build = functools.partial(Apparatus, tuning=tuning, starter=start.starter(),
                              fountain_path=start.fountain_path)
    return Simulation(cfg, builders={"apparatus": build})


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="apparatus_fold_gripped")
    ap.add_argument("--seconds", type=float, default=20.0)
    ap.add_argument("--hand-over", type=float, default=4.0)
    ap.add_argument("--slack", type=float, default=0.05)
    ap.add_argument("--dt-factor", type=float, default=1.0)
    ap.add_argument("--capture", type=float, nargs=2, default=[0.3, 40.0],
                    metavar=("BAND_M", "MARGIN_DEG"), help="the catch while the starter runs")
    ap.add_argument("--ramp", type=float, default=starter.RAMP,
                    help="seconds the starter takes from rest to apparatus.speed")
    ap.add_argument("--shape", choices=("hanging", "fountain"), default="hanging",
                    help="the chain at rest between the guides: hanging, or in the "
                    "predicted fountain's shape (held there, let go at the start)")
    ap.add_argument("--lag-factor", type=float, default=1.0,
                    help="times the lag that gives the loop the predicted fountain's length")
    ap.add_argument("--fade", type=float, nargs=2, default=[0.0, 2.0],
                    metavar=("C", "SECONDS"), help="after the hand-over, a damper C (N s/m) "
                    "on each carriage towards half apparatus.speed, fading to 0 over SECONDS")
    ap.add_argument("--boost", type=float, default=1.0,
                    help="the starter runs at this times apparatus.speed")
    ap.add_argument("--close", type=float,
                    help="Tuning.fold_close_rate (m/s): how fast a link captured off "
                    "the first turn's radius is brought onto it")
    ap.add_argument("--drive-lower", default="chain",
                    choices=("chain", "carriage", "none", "hand", "steer"),
                    help="the starter runs the chain in the lower guide, or the folding "
                    "roller's carriage at half the speed, or leaves it to its cart")
    ap.add_argument("--steer", type=float, default=1.0,
                    help="--drive-lower steer: the folding roller runs 1 - STEER*dr of half "
                    "the starter's speed (dr in m, > 0 when the fountain lands short)")
    ap.add_argument("--set", nargs="*", default=[], metavar="PATH=NUMBER")
    ap.add_argument("--keep-capture", action="store_true",
                    help="keep that catch after the hand-over (else the level's)")
    a = ap.parse_args()
    start = Start(a.slack, a.hand_over, tuple(a.capture), a.keep_capture, a.shape,
                  a.lag_factor, tuple(a.fade), a.boost, a.drive_lower, a.steer, a.ramp)
    tuning = Tuning(fold_close_rate=a.close, lay_at_rest=True)
    lvl = laid_on_path(io.load(LEVELS / f"{a.level}.toml"))
    ch = {k: float(v) for k, v in (x.split("=", 1) for x in a.set)}
    if a.dt_factor != 1.0:
        ch["solver.dt"] = lvl.sim.solver.dt * a.dt_factor
    lvl = with_changes(lvl, ch) if ch else lvl
    sim = simulation(lvl.sim, start, tuning)
    app = sim.apparatus
    assert app is not None and app.fold is not None
    print(f"lower roller starts {start.lag:.3f} s after the upper")
    print(f"{a.level}: hanging start, slack {a.slack:g}, hand-over {a.hand_over:g} s, "
          f"h {sim.h * 1e3:g} ms; ramp {a.ramp} s")
    note = f"held {a.seconds:g} s"
    try:
        while sim.time < a.seconds - 1e-9:
            v, dr, vout = [], [], []
            for _ in range(50):
                sim.advance(0.01)
                v.append(app.speed)
                vout.append(2.0 * app.lower.speed)
                dr.append(app.fold.mouth_dr)
            mdr = 100 * np.mean(dr) if dr else math.nan
            top = max((lk.body.position.y for lk in sim.chain.links), default=math.nan)
            print(f"  t {sim.time:5.1f} s: v_in {np.mean(v):.3f} v_out {np.mean(vout):.3f} "
                  f"m/s, landing dr {mdr:+.1f} cm, top {top:.3f} m"
                  f"{'  (starter)' if app.starting else ''}", flush=True)
    except RunEnded as exc:
        note = f"ended at {sim.time:.2f} s: {getattr(exc, 'plain', str(exc))}"
    print(note)


if __name__ == "__main__":
    main()
