"""Starting the gripped fold from rest with the chain hanging between the machine's guides.

A prototype (monkeypatched, not in the package). The chain lies at rest along its whole
path: on the upper table, round the pick-up roller, up the upper guide, then *hanging*
under its weight from the fountain start to the end guide's mouth (a catenary through the
two points, ``--slack`` longer than the chord), through the lower guide and round the
folding roller onto the lower table. A starter motor runs both rollers up from rest to
``apparatus.speed`` over 0.5 s (the upper guide's links, as the floor presets' starter,
and the folding roller's carriage at half the speed) and lets go at ``--hand-over`` s;
then only the carts, the brake and the fall drive the chain.

Prints the chain speed's and the landing's (``dr``, the entering link's offset from the
first turn's radius) 0.5-s means, and how the run ended.

Usage::

    python research/hanging_start.py --seconds 12 --hand-over 1.2 --keep-capture --close 20 \
        --drive-lower carriage --set apparatus.end_follow=0     # formed and held 12 s
    python research/hanging_start.py ... --dt-factor 0.5           # did not rise
"""

from __future__ import annotations

import argparse
import math

import numpy as np
from scipy.optimize import brentq

from chainfountain.errors import RunEnded
from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim import Simulation
from chainfountain.sim.apparatus import Apparatus, starter
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


def patch(slack: float, hand_over: float, capture: tuple[float, float], keep: bool,
          shape: str, lag_factor: float,
          fade: tuple[float, float], boost: float, drive_lower: str,
          steer: float) -> None:
    read0, path0 = Apparatus._read_config, Apparatus._fountain_path
    starter0, drive0 = Apparatus._init_starter_state, Apparatus._drive_starter

    def read(self, space, chain, cfg) -> None:
        read0(self, space, chain, cfg)
        self.v_lay = 0.0

    def fountain_path(self) -> np.ndarray:
        laid = path0(self)
        if shape == "fountain":
            self._lag = 0.0
            return laid
        hang = hanging_path(self.end[0], self.end[1], slack)

        def arc(p: np.ndarray) -> float:
            p = np.vstack(([0.0, 0.0], p))
            return float(np.sum(np.hypot(*np.diff(p, axis=0).T)))

        # the lower roller starts later, so that the loop gets the fountain's length
        self._lag = lag_factor * (arc(laid) - arc(hang)) / float(self.cfg.speed)
        return hang

    def init_starter(self) -> None:
        starter0(self)
        self.starting = True
        self._shipped_capture = self.fold_capture
        self.fold_capture = (capture[0], math.radians(capture[1]))

    def drive(self) -> None:
        drive0(self)
        v = boost * float(self.cfg.speed) * min(1.0, max(0.0, self._t - self._lag) / starter.RAMP)
        if drive_lower == "none":
            return
        if drive_lower == "hand":  # hold back the lower cart's push until the chain runs
            lo = self.lower
            f = -lo.direction * lo.force * (1.0 - v / (boost * float(self.cfg.speed)))
            lo.carriage.apply_force_at_world_point((f, 0.0), lo.carriage.position)
            if lo.carriage.velocity.x < 0.0:  # a pawl: it does not roll back
                lo.carriage.velocity = (0.0, 0.0)
            return
        if drive_lower == "carriage":
            self.lower.carriage.velocity = (0.5 * v, 0.0)
            return
        if drive_lower == "steer":  # store chain while the fountain lands short
            dr = self._mouth_dr if self._mouth_dr is not None else 0.0
            f = min(1.2, max(0.5, 1.0 - steer * dr))
            self.lower.carriage.velocity = (0.5 * v * f, 0.0)
            return
        starter.run_along(self.guide, self._gq, v)  # the chain in the lower guide

    def check(self) -> None:
        if self._t >= hand_over:
            self.starting = False
            if not keep:
                self.fold_capture = self._shipped_capture

    before0 = Apparatus.before_step

    def before(self) -> None:
        before0(self)
        t = self._t - hand_over
        if self.starting or t >= fade[1] or fade[0] <= 0.0:
            return
        c = fade[0] * (1.0 - t / fade[1])
        u_s = 0.5 * float(self.cfg.speed)
        for unit in (self.upper, self.lower):
            body = unit.carriage
            body.apply_force_at_world_point((-c * (body.velocity.x - u_s), 0.0),
                                            body.position)

    Apparatus.before_step = before
    Apparatus.starter_speed = property(
        lambda self: boost * float(self.cfg.speed) * min(1.0, self._t / starter.RAMP))
    Apparatus._read_config = read
    Apparatus._fountain_path = fountain_path
    Apparatus._init_starter_state = init_starter
    Apparatus._drive_starter = drive
    Apparatus._check_starter = check


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
                    help="Apparatus.fold_close_rate (m/s): how fast a link captured off "
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
    starter.RAMP = a.ramp
    if a.close is not None:
        Apparatus.fold_close_rate = a.close
    patch(a.slack, a.hand_over, tuple(a.capture), a.keep_capture, a.shape,
          a.lag_factor, tuple(a.fade), a.boost, a.drive_lower, a.steer)
    lvl = laid_on_path(io.load(LEVELS / f"{a.level}.toml"))
    ch = {k: float(v) for k, v in (x.split("=", 1) for x in a.set)}
    if a.dt_factor != 1.0:
        ch["solver.dt"] = lvl.sim.solver.dt * a.dt_factor
    lvl = with_changes(lvl, ch) if ch else lvl
    sim = Simulation(lvl.sim)
    app = sim.apparatus
    print(f"lower roller starts {app._lag:.3f} s after the upper")
    print(f"{a.level}: hanging start, slack {a.slack:g}, hand-over {a.hand_over:g} s, "
          f"h {sim.h * 1e3:g} ms; ramp {starter.RAMP} s")
    note = f"held {a.seconds:g} s"
    try:
        while sim.time < a.seconds - 1e-9:
            v, dr, vout = [], [], []
            for _ in range(50):
                sim.advance(0.01)
                v.append(app.speed)
                vout.append(2.0 * app.lower.speed)
                if app._mouth_dr is not None:
                    dr.append(app._mouth_dr)
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
