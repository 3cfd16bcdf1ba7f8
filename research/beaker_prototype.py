"""Beaker prototype: does the free pymunk chain show the Mould effect (a chain fountain)?

A pot (three static segments: floor and two walls) holds a chain laid as a pile; the
chain's end runs up out of the pot, over the right rim and hangs a short way down the
outside. Everything starts at rest (after a short settle with the end held); the end is
let go, the hanging weight pulls the chain out of the pile, it falls a drop ``H`` below
the rim to an *absorbing floor* that deletes every link reaching it (the chain's front
end is then free again, the floor pulls nothing: B&W's beta = 0).

The chain is built here directly with pymunk (the same model as
``chainfountain/sim/chain.py``: rod links of length ``L`` with capsule shapes of radius
``r``, joined by pivot joints, optional damped rotary springs ``c``, ``d`` between
neighbours), but with **self-collision** between links (joined neighbours excepted) and
friction ``mu`` against each other and the pot.

Pile layouts (``--layout``):

* ``rows``:    zig-zag of horizontal rows stacked from the pot floor (links lie flat and
  must rotate to be picked up; the last row ends next to the exit wall);
* ``columns``: zig-zag of vertical columns packed side by side (links stand up and are
  pulled out along their own direction);
* ``heap``:    the ``rows`` pile shaken (every pile link gets a random 0.3 m/s velocity and
  30 rad/s spin) and settled for ``--settle`` s with the end held (a rougher heap).

Measured and printed every ``--every`` s (simulated time):

* ``v_fall``: mean speed *along the chain* (link velocity projected on the link) of the
  falling strand outside the pot (sway does not count);
* ``v_flux``: L * (links absorbed per s) over the last interval: the chain speed at the
  floor, the steadier reading (+-1 link per interval, i.e. +-0.1 m/s at 0.1 s);
* ``top_h``: the fountain's rise h, the highest point of the chain's centre line above
  where it would lie on the rim (rim top surface + r): 0 = draped on the rim;
* ``h_pk``, ``pick``: the same highest point above the pick-up point, taken as the
  highest slow link (< 0.15 v_fall) in the pot, and that point's height above the pot floor;
* ``v2/gH``, ``v2/gHp``: v_fall^2 over g*H (H: rim top -> floor) and over g*Hp (Hp:
  pick-up -> floor); B&W with an absorbing floor (beta = 0): v^2 = g*Hp/(1 - alpha),
  h_pk/Hp = alpha/(1 - alpha); ``a_v`` = 1 - g*Hp/v_flux^2 and ``a_h`` = h_pk/(Hp + h_pk)
  are alpha read off the speed and off the rise;
* ``n_pot`` links in the pot, ``rem`` links absorbed, ``rtf`` real-time factor so far.

``SUMMARY`` averages the rows from half a drop's worth of chain after the end reached the
floor until the pile runs low (``--avg-from``); ``top_max_after_arrival`` is the largest
rise sampled. ``--snap FILE.png`` also draws the chain near the pot every 3rd print.

Bending: ``--bend-limit DEG`` (default 30) puts a RotaryLimitJoint (+-DEG) on each joint
as soon as it is bent less than 0.9*DEG (so the pile's tight U-turns start free and get
limited once pulled straight); ``--c``/``--d`` add a damped rotary spring (rest angle 0).

Run from the repository root::

    .venv/bin/python research/beaker_prototype.py                     # default (~30 s)
    .venv/bin/python research/beaker_prototype.py --snap /tmp/beaker.png
    .venv/bin/python research/beaker_prototype.py --bend-limit 0      # free pivots
    .venv/bin/python research/beaker_prototype.py --L 0.02 --r 0.003 --pot-w 0.3 --H 2
    .venv/bin/python research/beaker_prototype.py --bend-limit 0 --c 2e-4 --d 2e-5
    .venv/bin/python research/beaker_prototype.py --study             # all study runs
    .venv/bin/python research/beaker_prototype.py --study --only 3,4  # some of them
    .venv/bin/python research/beaker_prototype.py --bench             # cost per step

Each run prints its parameters, a time series and one ``SUMMARY`` line; ``--study`` ends
with a table of the summaries. Keep runs to ~2-3 min of wall time: the cost is about
linear in the number of links and in 1/h.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import time
from dataclasses import dataclass

import numpy as np
import pymunk

from chainfountain.sim.scene_layout import along_polyline

G = 9.81
CHAIN_CAT = 0b10
WALL_CAT = 0b100


@dataclass
class Params:
    name: str = "default"
    L: float = 0.01            # link length (m)
    r: float = 0.002           # link capsule radius (m)
    lam: float = 0.05          # linear density (kg/m)
    mu: float = 0.4            # friction link-link and link-pot
    c: float = 0.0             # bending stiffness of the joints (N m/rad)
    d: float = 0.0             # bending damping of the joints (N m s/rad)
    bend_limit: float = 30.0   # max bend angle per joint (deg), 0 = none (free pivots)
    layout: str = "rows"       # rows | columns | heap
    pot_w: float = 0.2         # inner width (m)
    pot_h: float = 0.3         # wall height above the pot floor (m)
    wall_r: float = 0.003      # radius of the pot's segments (m)
    fill: float = 0.9          # pile height / pot height
    gap: float = 0.0005        # extra gap between rows/columns at the start (m)
    H: float = 1.0             # drop rim -> absorbing floor (m)
    hang: float = 0.35         # length hanging over the rim at the start (m)
    dt: float = 1 / 4000       # time step between checks (s)
    substeps: int = 2          # pymunk steps per dt
    iterations: int = 6        # solver iterations per pymunk step
    settle: float = 0.05       # settle time with the end held (s)
    t_end: float = 2.5         # simulated time after release (s)
    every: float = 0.1         # print interval (s)
    avg_from: float = 0.5      # average from when this many H of chain passed after arrival
    max_wall: float = 170.0    # stop a run after this many wall seconds
    snap: str = ""             # PNG file: snapshots of the chain near the pot (optional)


# ----------------------------------------------------------------------------- layout
def zigzag(n_lines: int, m: int, s: float, L: float) -> np.ndarray:
    """Points (u, w) of a zig-zag of ``n_lines`` lines of ``m`` links each, lines ``s``
    apart in w, joined by one slanted link each; line 0 runs +u from (0, 0)."""
    du = math.sqrt(L * L - s * s)
    pts = [(0.0, 0.0)]
    u, w, sgn = 0.0, 0.0, 1.0
    for k in range(n_lines):
        for _ in range(m):
            u += sgn * L
            pts.append((u, w))
        if k < n_lines - 1:
            u -= sgn * du
            w += s
            pts.append((u, w))
            sgn = -sgn
    return np.array(pts)


def layout_points(p: Params) -> tuple[np.ndarray, dict]:
    """Chain points from the upstream end (bottom of the pile) to the free hanging end.
    Pot: inner floor at y = 0 (surface), inner walls at x = 0 and x = pot_w (surfaces)."""
    L, r, s = p.L, p.r, 2 * p.r + p.gap
    du = math.sqrt(L * L - s * s)
    pile_h = p.fill * p.pot_h
    if p.layout in ("rows", "heap"):
        m = int((p.pot_w - 2 * r - du - 0.002) / L)
        n_lines = max(1, int((pile_h - 2 * r) / s) + 1)
        if n_lines % 2 == 0:
            n_lines -= 1        # odd: the top row runs +x and ends near the exit wall
        uw = zigzag(n_lines, m, s, L)
        x = uw[:, 0] + r + du + 0.001
        y = uw[:, 1] + r + p.gap
        pile = np.column_stack((x, y))
    elif p.layout == "columns":
        m = int((pile_h - 2 * r - du - p.gap) / L)
        n_lines = int((p.pot_w - 2 * r - 0.002) / s) + 1
        if n_lines % 2 == 0:
            n_lines -= 1        # odd: the last column runs up, next to the exit wall
        uw = zigzag(n_lines, m, s, L)
        x = uw[:, 1] + r + 0.001
        y = uw[:, 0] + r + du + p.gap
        pile = np.column_stack((x, y))
    else:
        raise ValueError(f"layout {p.layout!r}")
    y_rim = p.pot_h + p.wall_r      # the rim's top surface
    top = pile[-1]
    clear = p.wall_r + r + 0.001
    xo = p.pot_w + 2 * p.wall_r + clear          # centre line outside the exit wall
    verts = np.array([
        top,
        (p.pot_w - 0.02, y_rim + r + 0.001),
        (p.pot_w + p.wall_r, y_rim + r + 0.0015),
        (xo, p.pot_h - 0.01),
        (xo, y_rim - p.hang),
    ])
    exit_pts = along_polyline(verts, L)
    pts = np.vstack((pile, exit_pts[1:]))
    info = dict(n_pile=len(pile) - 1, n_lines=n_lines, per_line=m, y_rim=y_rim,
                pile_top=float(pile[:, 1].max()), x_rim=p.pot_w + p.wall_r)
    return pts, info


# ----------------------------------------------------------------------------- model
class Beaker:
    def __init__(self, p: Params) -> None:
        self.p = p
        pts, self.info = layout_points(p)
        pts = pts[::-1]                 # index 0: the free hanging end
        self.space = sp = pymunk.Space()
        sp.gravity = (0.0, -G)
        sp.iterations = p.iterations
        sp.collision_slop = 1e-4
        sp.use_spatial_hash(4 * p.r + p.L, 4 * len(pts))
        self.h = p.dt / p.substeps
        # pot: floor and walls (surfaces at y=0, x=0, x=pot_w)
        wr = p.wall_r
        self.walls = []
        for a, b in (((-wr, -wr), (p.pot_w + wr, -wr)),
                     ((-wr, -wr), (-wr, p.pot_h)),
                     ((p.pot_w + wr, -wr), (p.pot_w + wr, p.pot_h))):
            seg = pymunk.Segment(sp.static_body, a, b, wr)
            seg.friction = p.mu
            seg.filter = pymunk.ShapeFilter(categories=WALL_CAT)
            sp.add(seg)
            self.walls.append(seg)
        m = p.lam * p.L
        mom = m * p.L ** 2 / 12
        filt = pymunk.ShapeFilter(categories=CHAIN_CAT)
        self.bodies: list[pymunk.Body] = []
        self.cons: list[list] = []      # constraints to the upstream neighbour
        hl = 0.5 * p.L
        rng = np.random.default_rng(1)
        for i in range(len(pts) - 1):
            a, b = pts[i], pts[i + 1]   # a downstream (front), b upstream (back)
            body = pymunk.Body(m, mom)
            body.position = tuple(0.5 * (a + b))
            body.angle = math.atan2(a[1] - b[1], a[0] - b[0])
            shp = pymunk.Segment(body, (-hl, 0), (hl, 0), p.r)
            shp.friction = p.mu
            shp.filter = filt
            sp.add(body, shp)
            self.bodies.append(body)
            self.cons.append([])
        for i in range(len(self.bodies) - 1):
            self._join(i)
        self.pin = pymunk.PivotJoint(sp.static_body, self.bodies[0], tuple(pts[0]), (hl, 0))
        sp.add(self.pin)
        self.removed = 0
        self.y_floor = self.info["y_rim"] - p.H        # H: rim top surface -> floor
        self.rng = rng

    def _join(self, i: int) -> None:
        p, hl = self.p, 0.5 * self.p.L
        a, b = self.bodies[i], self.bodies[i + 1]
        j = pymunk.PivotJoint(a, b, (-hl, 0), (hl, 0))
        j.collide_bodies = False
        j.error_bias = 1e-10             # as chainfountain's SolverConfig
        cs = [j]
        if p.c > 0 or p.d > 0:
            # rest angle 0 (straight); the pile's bends push against it
            s = pymunk.DampedRotarySpring(a, b, 0.0, p.c, p.d)
            s.collide_bodies = False
            cs.append(s)
        self.space.add(*cs)
        self.cons[i] = cs

    def add_bend_limits(self) -> None:
        """Give every joint bent less than ``bend_limit`` now a RotaryLimitJoint
        (+-bend_limit). Joints bent more (the pile's U-turns, a heap's kinks) stay free
        until they straighten: this is called again every few ms during the run."""
        lim = math.radians(self.p.bend_limit)
        bs, cons = self.bodies, self.cons
        for i in range(len(bs) - 1):
            if len(cons[i]) and isinstance(cons[i][-1], pymunk.RotaryLimitJoint):
                continue
            a, b = bs[i], bs[i + 1]
            rel = (a.angle - b.angle + math.pi) % (2 * math.pi) - math.pi
            if abs(rel) < 0.9 * lim:
                rl = pymunk.RotaryLimitJoint(a, b, -lim, lim)
                rl.collide_bodies = False
                self.space.add(rl)
                cons[i].append(rl)

    def release(self) -> None:
        self.space.remove(self.pin)
        self.pin = None

    def absorb(self) -> None:
        bs = self.bodies
        while len(bs) > 2 and bs[0].position.y < self.y_floor:
            body = bs.pop(0)
            objs = [body, *body.shapes, *self.cons.pop(0)]
            self.space.remove(*objs)
            self.removed += 1

    def step(self) -> None:
        for _ in range(self.p.substeps):
            self.space.step(self.h)
        if self.pin is None:
            self.absorb()

    def state(self) -> tuple[np.ndarray, np.ndarray]:
        pos = np.array([tuple(b.position) for b in self.bodies])
        vel = np.array([tuple(b.velocity) for b in self.bodies])
        return pos, vel

    def measure(self) -> dict:
        p, info = self.p, self.info
        pos, vel = self.state()
        ang = np.array([b.angle for b in self.bodies])
        hl = 0.5 * p.L
        ends_y = np.concatenate((pos[:, 1] + hl * np.sin(ang), pos[:, 1] - hl * np.sin(ang)))
        speed = np.hypot(vel[:, 0], vel[:, 1])
        # chain speed: velocity along the link (downstream +x of the body), which the
        # shape's sway does not add to; mean over the links of the falling strand
        vt = vel[:, 0] * np.cos(ang) + vel[:, 1] * np.sin(ang)
        fall = (pos[:, 0] > info["x_rim"] + p.wall_r) & (pos[:, 1] < info["y_rim"])
        v_rim = float(vt[fall].mean()) if fall.any() else float("nan")
        inpot = (pos[:, 0] > 0) & (pos[:, 0] < p.pot_w) & (pos[:, 1] < info["y_rim"])
        slow = inpot & (speed < max(0.1, 0.15 * (v_rim if v_rim == v_rim else 0)))
        pk = float(pos[slow, 1].max()) if slow.any() else 0.0
        top = float(ends_y.max())
        itop = int(np.argmax(pos[:, 1]))
        # rise: the chain's highest centre-line point above where it lies on the rim
        return dict(v_rim=v_rim, top=top - info["y_rim"] - p.r, pick=pk, h_pk=top - pk,
                    x_top=float(pos[itop, 0]), n_pot=int(inpot.sum()),
                    vmax=float(speed.max()))


# ----------------------------------------------------------------------------- run
def run(p: Params, quiet: bool = False) -> dict:
    t0 = time.perf_counter()
    sim = Beaker(p)
    info = sim.info
    n0 = len(sim.bodies)
    out = print if not quiet else (lambda *a, **k: None)
    out(f"\n=== {p.name}: layout {p.layout}, L {p.L*100:.1f} cm, r {p.r*1000:.1f} mm, "
        f"{n0} links ({info['n_pile']} in {info['n_lines']} lines of {info['per_line']}), "
        f"mu {p.mu}, c {p.c:g}, d {p.d:g}, bend_limit {p.bend_limit:g} deg")
    out(f"    pot {p.pot_w} x {p.pot_h} m, pile top {info['pile_top']:.3f} m (rim "
        f"{info['y_rim']:.3f}), H {p.H} m, hang {p.hang} m, dt {p.dt*1e6:.0f} us x "
        f"{p.substeps} substeps x {p.iterations} it")
    if p.layout == "heap":
        # shake the pile's links so the ordered rows tumble into a heap while settling
        for b in sim.bodies:
            if b.position.y < info["pile_top"] + 0.01:
                b.velocity = tuple(sim.rng.normal(0, 0.3, 2))
                b.angular_velocity = float(sim.rng.normal(0, 30))
    n_settle = int(round(p.settle / p.dt))
    for _ in range(n_settle):
        sim.step()
    if p.bend_limit > 0:
        sim.add_bend_limits()
    sim.release()
    out("      t    v_fall v_flux  top_h  h_pk    pick   v2/gH  v2/gHp  a_v    a_h    "
        "n_pot  rem   rtf")
    n_every = max(1, int(round(p.every / p.dt)))
    n_total = int(round(p.t_end / p.dt))
    rows = []
    snaps = []
    last_rem, t_arrive = 0, None
    tw0 = time.perf_counter()
    for k in range(1, n_total + 1):
        sim.step()
        if p.bend_limit > 0 and k % 40 == 0:
            sim.add_bend_limits()
        if t_arrive is None and sim.removed > 0:
            t_arrive = k * p.dt
        if k % n_every == 0:
            t = k * p.dt
            m = sim.measure()
            v_flux = (sim.removed - last_rem) * p.L / (n_every * p.dt)
            last_rem = sim.removed
            Hp = m["pick"] - sim.y_floor
            v = m["v_rim"]
            v2gH = v * v / (G * p.H)
            v2gHp = v * v / (G * Hp)
            vf2 = v_flux * v_flux / (G * Hp)   # the flux speed is the steadier reading
            a_v = 1 - 1 / vf2 if vf2 > 0 else float("nan")
            a_h = m["h_pk"] / (Hp + m["h_pk"])
            rtf = t / (time.perf_counter() - tw0)
            row = dict(t=t, v_rim=v, v_flux=v_flux, top=m["top"], vf2=vf2, h_pk=m["h_pk"],
                       pick=m["pick"], v2gH=v2gH, v2gHp=v2gHp, a_v=a_v, a_h=a_h,
                       n_pot=m["n_pot"], rem=sim.removed, rtf=rtf, x_top=m["x_top"],
                       Hp=Hp)
            rows.append(row)
            if p.snap and (k // n_every) % 3 == 0:
                snaps.append((t, sim.state()[0], np.array([b.angle for b in sim.bodies])))
            out(f"  {t:5.2f}  {v:6.3f}  {v_flux:6.3f}  {m['top']*100:5.1f}  "
                f"{m['h_pk']*100:5.1f}  {m['pick']*100:5.1f}  {v2gH:6.3f}  {v2gHp:6.3f}  "
                f"{a_v:+.3f} {a_h:+.3f}  {m['n_pot']:5d} {sim.removed:5d}  {rtf:5.3f}"
                + ("" if m["vmax"] < 30 else f"  !vmax {m['vmax']:.0f}"))
            if m["n_pot"] < 0.08 * info["n_pile"] or len(sim.bodies) < 20:
                out("  (pile nearly used up: stop)")
                break
            if time.perf_counter() - t0 > p.max_wall:
                out("  (wall-time limit: stop)")
                break
    wall = time.perf_counter() - t0
    if p.snap:
        save_snaps(p, sim, snaps)
    # steady part: after the end arrived and a further avg_from*H of chain passed
    steady = []
    if t_arrive is not None and rows:
        v_arr = max(r["v_rim"] for r in rows if r["t"] <= t_arrive + p.every) or 1.0
        t_s = t_arrive + p.avg_from * p.H / max(v_arr, 0.5)
        steady = [r for r in rows if r["t"] >= t_s and r["n_pot"] > 0.15 * info["n_pile"]]
    def mean(key):
        return float(np.mean([r[key] for r in steady])) if steady else float("nan")
    summ = dict(name=p.name, layout=p.layout, L=p.L, H=p.H, c=p.c, d=p.d, mu=p.mu,
                bend=p.bend_limit, links=n0, t_arr=t_arrive if t_arrive else float("nan"),
                n_steady=len(steady), v=mean("v_rim"), v_flux=mean("v_flux"),
                top=mean("top"), top_max=max((r["top"] for r in rows), default=float("nan")),
                top_max_after=max((r["top"] for r in rows if t_arrive and r["t"] >= t_arrive),
                                  default=float("nan")),
                h_pk=mean("h_pk"), v2gH=mean("v2gH"), v2gHp=mean("v2gHp"), vf2=mean("vf2"),
                vf2H=mean("v_flux") ** 2 / (G * p.H),
                a_v=1 - 1 / mean("vf2") if steady else float("nan"),
                a_h=mean("a_h"), Hp=mean("Hp"),
                rtf=rows[-1]["t"] / (wall - (tw0 - t0)) if rows else float("nan"),
                wall=wall)
    out("SUMMARY " + fmt_summary(summ))
    return summ


def save_snaps(p: Params, sim: Beaker, snaps: list) -> None:
    """Chain near the pot at every third print time, one panel each."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = len(snaps)
    cols = min(n, 6)
    nr = (n + cols - 1) // cols
    fig, axs = plt.subplots(nr, cols, figsize=(3 * cols, 3.2 * nr), squeeze=False)
    for ax, (t, pos, ang) in zip(axs.flat, snaps, strict=False):
        hl = 0.5 * p.L
        dx, dy = hl * np.cos(ang), hl * np.sin(ang)
        segs = np.stack([np.column_stack((pos[:, 0] - dx, pos[:, 1] - dy)),
                         np.column_stack((pos[:, 0] + dx, pos[:, 1] + dy))], axis=1)
        for a, b in segs:
            ax.plot([a[0], b[0]], [a[1], b[1]], "b-", lw=0.8)
        for w in sim.walls:
            ax.plot([w.a[0], w.b[0]], [w.a[1], w.b[1]], "k-", lw=2)
        ax.set_xlim(-0.05, p.pot_w + 0.15)
        ax.set_ylim(-0.02, p.pot_h + 0.18)
        ax.set_aspect("equal")
        ax.set_title(f"t = {t:.2f} s", fontsize=9)
    for ax in list(axs.flat)[n:]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(p.snap, dpi=80)
    print(f"snapshots: {p.snap}")


def fmt_summary(s: dict) -> str:
    return (f"{s['name']:<14} {s['layout']:<7} L={s['L']*100:.1f}cm H={s['H']:.2f} "
            f"c={s['c']:g} d={s['d']:g} bend={s['bend']:g} mu={s['mu']} N={s['links']} "
            f"t_arr={s['t_arr']:.2f} steady_n={s['n_steady']} v={s['v']:.3f} "
            f"vflux={s['v_flux']:.3f} vf^2/gH={s['vf2H']:.3f} vf^2/gHp={s['vf2']:.3f} "
            f"a_v={s['a_v']:+.3f} top={s['top']*100:.1f}cm top_max_after_arrival="
            f"{s['top_max_after']*100:.1f}cm h_pk={s['h_pk']*100:.1f}cm a_h={s['a_h']:+.3f} "
            f"rtf={s['rtf']:.3f} wall={s['wall']:.0f}s")


# ----------------------------------------------------------------------------- study
STUDY = [
    Params(name="free-1cm-H1", bend_limit=0.0),
    Params(name="b30-1cm-H1"),
    Params(name="b30-1cm-H0.5", H=0.5, t_end=1.8),
    Params(name="b30-1cm-H2", H=2.0, t_end=2.4),
    Params(name="b30-2cm-H1", L=0.02, r=0.003, pot_w=0.3, hang=0.6),
    Params(name="b30-2cm-H2", L=0.02, r=0.003, pot_w=0.3, hang=0.6, H=2.0, t_end=2.4),
    Params(name="b30-heap-1cm-H1", layout="heap", settle=0.3),
    Params(name="stiff-1cm-H1", bend_limit=0.0, c=5e-5, d=1e-5, hang=0.6),
    Params(name="b45-1cm-H1", bend_limit=45.0),
    Params(name="b30-1cm-H1-fine", substeps=4, iterations=10),
    Params(name="b30-cols-1cm-H1", layout="columns", hang=0.5),
    Params(name="free-1cm-H2", bend_limit=0.0, H=2.0, t_end=2.4),
]


def bench(p: Params) -> None:
    sim = Beaker(p)
    n = 400
    t0 = time.perf_counter()
    for _ in range(n):
        sim.step()
    w = time.perf_counter() - t0
    print(f"{len(sim.bodies)} links: {w / n * 1e3:.2f} ms per dt ({p.substeps} substeps x "
          f"{p.iterations} it), real-time factor {p.dt * n / w:.3f}")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    for f in dataclasses.fields(Params):
        ap.add_argument("--" + f.name.replace("_", "-"), type=type(f.default),
                        default=None)
    ap.add_argument("--study", action="store_true", help="run the study list")
    ap.add_argument("--only", default="", help="comma list of study indices")
    ap.add_argument("--list", action="store_true", help="list the study runs")
    ap.add_argument("--bench", action="store_true", help="time 400 steps at rest")
    a = ap.parse_args(argv)
    over = {f.name: getattr(a, f.name) for f in dataclasses.fields(Params)
            if getattr(a, f.name) is not None}
    if a.list:
        for i, p in enumerate(STUDY):
            print(i, p)
        return
    if a.study:
        idx = [int(s) for s in a.only.split(",") if s] or range(len(STUDY))
        res = [run(dataclasses.replace(STUDY[i], **over)) for i in idx]
        print("\n=== study summary")
        for s in res:
            print(fmt_summary(s))
        return
    p = Params(**over)
    if a.bench:
        bench(p)
        return
    run(p)


if __name__ == "__main__":
    sys.exit(main())
