"""The end guide that follows the fountain's landing (``apparatus.end_follow``,
:mod:`chainfountain.sim.apparatus.follow`), with live cart changes.

``--gain`` sets ``apparatus.end_follow`` (1/s; 0: a fixed guide); ``--capture`` and
``--close`` vary the first turn's catch (a :class:`~chainfountain.sim.apparatus.Tuning`).

Per run: the chain speed, the landing offset and the guide's shift every ``--every`` s,
and how the run ended.

Usage::

    python -m research.end_follow --seconds 40 --change 4 carts[0].mass=0.024 [--gain 0]
        [--dt-factor 0.5] [--set apparatus.fold_brake=1.5]
"""

from __future__ import annotations

import argparse
import math
import os

import numpy as np

from chainfountain.errors import RunEnded
from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim.apparatus import Tuning
from chainfountain.study.changes import laid_on_path, with_changes
from research.gripped_fold import _value

LEVELS = shipped_dir()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="apparatus_fold_gripped")
    ap.add_argument("--seconds", type=float, default=60.0)
    ap.add_argument("--gain", type=float, default=2.0, help="1/s; 0: a fixed guide")
    ap.add_argument("--dt-factor", type=float, default=1.0)
    ap.add_argument("--every", type=float, default=2.0)
    ap.add_argument("--set", nargs="*", default=[], metavar="PATH=VALUE")
    ap.add_argument("--change", nargs=2, action="append", default=[],
                    metavar=("T", "PATH=VALUE"), help="a live change at T s (repeatable)")
    ap.add_argument("--capture", type=float, nargs=2, metavar=("BAND_M", "MARGIN_DEG"))
    ap.add_argument("--close", type=float)
    a = ap.parse_args()
    tuning = Tuning(fold_capture=(a.capture[0], math.radians(a.capture[1])) if a.capture
                    else None, fold_close_rate=a.close)
    lvl = io.load(LEVELS / f"{a.level}.toml")
    ch = {k: _value(v) for k, v in (x.split("=", 1) for x in a.set)}
    ch["apparatus.end_follow"] = a.gain
    if a.dt_factor != 1.0:
        ch["solver.dt"] = lvl.sim.solver.dt * a.dt_factor
    lvl = with_changes(laid_on_path(lvl), ch) if ch else laid_on_path(lvl)
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    from chainfountain.app.session import Session

    sess = Session(lvl)
    sim = sess.sim
    app = sim.apparatus
    app.retune(tuning)
    changes = sorted((float(t), kv) for t, kv in a.change)
    print(f"{a.level} {' '.join(a.set)}: gain {a.gain:g}/s, h {sim.h * 1e3:g} ms")
    note = f"held {a.seconds:g} s"
    try:
        while sim.time < a.seconds - 1e-9:
            v, dr = [], []
            n = int(round(a.every / 0.01))
            for _ in range(n):
                while changes and sim.time >= changes[0][0] - 1e-9:
                    t, kv = changes.pop(0)
                    path, value = kv.split("=", 1)
                    res = sess.set_field(path, float(value))
                    print(f"  t {t:g} s: {kv}" + ("" if res.ok else f" refused: {res.message}"))
                sess.advance(0.01)
                if sess.stopped:
                    raise RunEnded(sess.stopped)
                v.append(app.speed)
                dr.append(app.fold.mouth_dr)
            fx = app.end_shift
            print(f"  t {sim.time:5.1f} s: v {np.mean(v):.3f} m/s, landing dr "
                  f"{100 * np.mean(dr) if dr else math.nan:+.1f} cm, guide shift "
                  f"{100 * fx:+.1f} cm", flush=True)
    except RunEnded as exc:
        note = f"ended at {sim.time:.2f} s: {getattr(exc, 'plain', str(exc))}"
    print(note)


if __name__ == "__main__":
    main()
