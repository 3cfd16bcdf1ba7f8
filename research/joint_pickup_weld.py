"""The joint-gripped pick-up roller as a one-freedom linkage: the put-down rig time-reversed.

The twin of ``research/joint_putdown_weld.py`` (read its docstring first). Same scene: no
gravity, ``alpha = 0``, 2-cm links of ``lambda = 0.05`` kg/m, the axle in a horizontal
groove at the height ``R`` of the chain's centre line (``R = r + rho``), no rolling
constraint. The chain lies at rest on the table ahead of the roller (``x > 0``); the roller
moves towards it (``+x``, clockwise), lifts it at the bottom, carries it round its back
(``-x`` side) and lets it go at the top into a horizontal strand that leaves along ``+x``
over the resting chain; a cart force ``F_c`` holds the roller back (``-x``).

* **Table.** Resting links are not bodies: the chain's joints on the table are the fixed
  points ``(m L, 0)``. Only the *lifting link* is in the space: its tail (table side) is
  pinned to the table, its lead joined to the lowest welded link's tail.
* **Lift.** When the lifting link's tail passes under the roller's centre it is un-pinned
  from the table and the link is welded to the roller where it is (a pivot at its tail and a
  gear of ratio 1, both at their current place: zero error at creation); the chain joint to
  the welded link above becomes redundant and is removed. The next link is made at rest on
  the table (tail pinned, lead joined to the new weld's pivot at its current place). In the
  limit of exact detection the roller rolls about the lifted joint at that instant (the old
  lifting link, pinned there, allows nothing else), so the hand-over is continuous in
  velocity; the detection's lag gives an O(dt) jolt.
* **Release** (``--release``): the top welded link is un-welded when its lead joint (strand
  side) passes over the roller's centre (``--release-angle`` later, in rad), and its tail
  re-joined by a chain joint to the next welded link at its current place. ``hard``
  (default): the weld is dropped at once (this removes constraints, so no velocity jumps);
  ``soft``: the gear is replaced by a rotary spring holding the link's angle on the roller,
  critically damped for the link's inertia about its tail with time ``--release-time``,
  whose stiffness and damping are ramped linearly to zero over ``3 --release-time``
  (the time-reverse of the put-down's catch, which closes a gap; here there is none).
* **Drive** (``--drive``): ``port`` (default): a row of kinematic links at ``y = 2R``
  moving at ``+v``; the strand's leading link is taken into it (made kinematic at
  ``(v, 0)``) once its centre is ``--strand-links`` + 1/2 links ahead of the roller's
  centre, so the strand's speed is imposed and its tension measured (impulse of the
  middle strand joint per step, averaged per 0.05 s). ``pull``: no port; a constant force
  ``--pull`` (in ``lambda v^2``) pulls the strand's leading joint along ``+x``, the strand
  grows (``--strand-max`` caps it: the leading link is dropped and the pull moves to the
  next), and the speed is measured: the rig then reports ``Tbar = F / (lambda u^2)`` with
  ``u`` the strand's mean speed (of its middle third), against the loss-free law.

**Loss-free law.** The chain is picked up at the roller's speed, so chain conservation
gives ``v_R = v/2`` on average whatever the polygon (the roller advances ``L`` per link
lifted, and the lifted chain grows at ``v - v_R``). Power: ``T v = (1/2) lambda v_R v^2 +
F_c v_R`` so ``Tbar = T/(lambda v^2) = 1/4 + Fbar_c/2``; the paper's ``1/2 + Fbar_c``
(``p = 1/2``, ``G = 1``) is the horizontal momentum balance ``T - F_c = lambda v (v - v_R)``
*without* the table's reaction; in the linkage the table pin pushes the chain forward
with ``H = lambda v^2/4 + F_c/2`` on average (momentum then balances too). The welded
linkage has no impulsive event in the limit of exact detection: the lift is continuous in
velocity and the release only removes constraints, so it should read ``1/4 + Fbar_c/2``
less nothing, except the kinetic energy of the transverse waves the released links carry
into the strand (absorbed at the port), which depends on ``L/R``, not on the step.

Measured (3 m/s, 2 s, last second, 0.5/0.25/0.125 ms; ``research/notes/apparatus_notebook.md``,
"Thirty-ninth session: a welded pick-up rig"): nothing locks; the lift reaches the roller
at 0.006/0.003/0.001 m/s (100 mm), the released link turns within ~1 rad/s of the roller
1 ms on. ``--drive pull`` is the well-posed drive: on the 100-mm roller ``F/(lambda u^2)``
0.2505/0.2503/0.2502 (loss-free 0.2500; 10 s: 0.2506 at 0.5 ms, 0.2502 at 0.125 ms), with
``--cart 0.05 --pull 0.3056`` 0.3061/0.3059/0.3058 (0.3056), ``--cart 0.2 --pull 0.4722``
0.4731/0.4729/0.4727 (0.4725); on the 30-mm roller 0.2533/0.2523/0.2520 (0.2500) and
0.3093/0.3084/0.3080 (0.3061): converged, about 1 % above loss-free (the polygon's transverse
kick into the strand). The port drive reads the same law on the 100-mm roller with a cart
(0.3059/0.3054/0.3053, 10 s alike) but not on the 30-mm roller (0.259/0.270/0.274, spread
growing as the step shrinks: a link-frequency ringing of the short strand between the
polygon and the kinematic port), and without a cart its strand drifts off the port's line
(~4 mm/s: at ``T = lambda (v - v_R)^2`` the strand's shape is neutral in the roller's frame).
``--release soft`` and ``--release-frac 0.5`` do not help.

Usage::

    python -m research.joint_pickup_weld --radius 0.1 --drive pull --pull 0.25
    python -m research.joint_pickup_weld --radius 0.1 --drive pull --pull 0.3056 --cart 0.05
    python -m research.joint_pickup_weld --drive pull --pull 0.25            # 30-mm roller
    python -m research.joint_pickup_weld --radius 0.1 --cart 0.05            # port drive
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
import pymunk


def run(v: float = 3.0, cart: float = 0.0, dt: float = 5e-4, seconds: float = 2.0,
        L: float = 0.02, lam: float = 0.05, r: float = 0.03, rho: float = 0.002,
        roller_mass: float = 0.04, iterations: int = 20, strand_links: int = 6,
        release: str = "hard", release_angle: float = 0.0, release_frac: float = 0.0,
        release_time: float = 2e-3,
        window: float = 0.05, bias: float = 1e-10, drive: str = "port",
        pull: float = 0.25, strand_max: int = 400) -> dict:
    """One pick-up run; the roller speed and the strand tension per ``window`` s, and
    diagnostics of the lifts (``lift_v``: the roller's speed at the lifted joint when it is
    welded, ``lift_dx``: how far past the centre it was) and of the releases
    (``rel_dw``: the released link's angular velocity less the roller's 1 ms later)."""
    space = pymunk.Space()
    space.iterations = iterations
    static = space.static_body
    m_link = lam * L
    I_link = m_link * L * L / 12.0
    h = 0.5 * L
    R = r + rho
    d_ang = 2.0 * math.asin(L / (2.0 * R))
    vR = 0.5 * v
    om = -vR / R  # clockwise: the roller rolls towards +x about its bottom contact
    # joints from the bottom contact (0, 0) round the -x side to the top
    ring = [(0.0, 0.0)]
    th = -0.5 * math.pi
    while th - d_ang >= -1.5 * math.pi - 1e-9:
        th -= d_ang
        ring.append((R * math.cos(th), R + R * math.sin(th)))
    xw, yw = ring[-1]
    y0 = 2.0 * R
    x0 = xw + math.sqrt(L * L - (y0 - yw) ** 2)
    strand = [(x0 + i * L, y0) for i in range(strand_links)]
    # chain order from the strand's leading end to the table: J[i] is link i's lead,
    # J[i+1] its tail
    J = list(reversed(strand)) + list(reversed(ring)) + [(L, 0.0)]
    P = np.array(J)
    n_strand = strand_links
    # link i spans J[i] -> J[i+1]: links 0..n_strand-1 are the strand (the last one ends
    # at the top joint), then the welded links on the roller, and last the lifting link
    # (0, 0) -> (L, 0)

    def vel_on_roller(p) -> tuple[float, float]:
        return (-om * p[1], om * p[0])  # rolling about (0, 0)

    bodies: dict[int, pymunk.Body] = {}

    def new_link(i: int, lead, tail, vel=(0.0, 0.0), w: float = 0.0) -> pymunk.Body:
        b = pymunk.Body(m_link, I_link)
        lead = np.asarray(lead, float)
        tail = np.asarray(tail, float)
        b.position = tuple(0.5 * (lead + tail))
        b.angle = math.atan2(lead[1] - tail[1], lead[0] - tail[0])
        b.velocity = vel
        b.angular_velocity = w
        space.add(b)
        bodies[i] = b
        return b

    n_links = len(P) - 1
    i_lift = n_links - 1
    for i in range(n_links):
        c = 0.5 * (P[i] + P[i + 1])
        if i < n_strand:
            new_link(i, P[i], P[i + 1], (v, 0.0))
        elif i < i_lift:
            new_link(i, P[i], P[i + 1], vel_on_roller(c), om)
        else:
            new_link(i, P[i], P[i + 1])  # the lifting link: at rest (rolling about (0,0))

    roller = pymunk.Body(roller_mass, 0.5 * roller_mass * r * r)
    roller.position = (0.0, R)
    roller.velocity = (vR, 0.0)
    roller.angular_velocity = om
    axle = pymunk.GrooveJoint(static, roller, (-1e3, R), (1e3, R), (0.0, 0.0))
    axle.error_bias = bias
    space.add(roller, axle)

    def lead(i: int) -> pymunk.Vec2d:
        return bodies[i].local_to_world((h, 0.0))

    def tail(i: int) -> pymunk.Vec2d:
        return bodies[i].local_to_world((-h, 0.0))

    up: dict[int, pymunk.PivotJoint] = {}  # chain joint from link i's tail to i+1's lead

    def join(i: int) -> None:
        p = tail(i)
        j = pymunk.PivotJoint(bodies[i], bodies[i + 1], (-h, 0.0),
                              bodies[i + 1].world_to_local(p))
        j.error_bias = bias
        j.collide_bodies = False
        space.add(j)
        up[i] = j

    def unjoin(i: int) -> None:
        space.remove(up.pop(i))

    welds: dict[int, tuple] = {}

    def weld(i: int) -> None:
        """Weld link i to the roller where it is: a pivot at its tail, a gear at its angle."""
        p = tail(i)
        pj = pymunk.PivotJoint(roller, bodies[i], roller.world_to_local(p), (-h, 0.0))
        gj = pymunk.GearJoint(roller, bodies[i], bodies[i].angle - roller.angle, 1.0)
        for j in (pj, gj):
            j.error_bias = bias
            j.collide_bodies = False
        space.add(pj, gj)
        welds[i] = (pj, gj)
        if i - 1 in welds and i - 1 in up:
            unjoin(i - 1)  # redundant: both links on the roller

    softs: dict[int, tuple] = {}  # link -> (spring, step made, k0, c0)

    def unweld(i: int, step: int) -> None:
        pj, gj = welds.pop(i)
        if release == "soft":
            I_t = m_link * L * L / 3.0
            k0, c0 = I_t / release_time ** 2, 2.0 * I_t / release_time
            sp = pymunk.DampedRotarySpring(bodies[i], roller,
                                           bodies[i].angle - roller.angle, k0, c0)
            sp.collide_bodies = False
            space.add(sp)
            softs[i] = (sp, step, k0, c0)
        space.remove(pj, gj)
        join(i)  # its tail to the next welded link's lead, where they are

    table_pin: dict[int, pymunk.PivotJoint] = {}

    def pin_table(i: int) -> None:
        j = pymunk.PivotJoint(static, bodies[i], tail(i))
        j.error_bias = bias
        space.add(j)
        table_pin[i] = j

    for i in range(n_links - 1):
        join(i)
    for i in range(n_strand, i_lift):
        weld(i)
    pin_table(i_lift)
    n = i_lift        # the lifting link
    b = n_strand      # the top welded link
    m_next = 2        # the next table joint is (m_next L, 0)

    # the drive
    port: list[int] = []  # kinematic link indices, oldest first
    lo = 0                # the strand's leading dynamic link

    def port_link() -> None:
        """A kinematic link ahead of the strand's leading body."""
        first = min(bodies)
        p = bodies[first].local_to_world((h, 0.0))
        k = first - 1
        kb = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        kb.position = (p.x + h, y0)
        kb.angle = 0.0
        kb.velocity = (v, 0.0)
        space.add(kb)
        bodies[k] = kb
        port.insert(0, k)

    if drive == "port":
        for _ in range(4):
            port_link()
        # the kinematic links are not joined to each other; the first to the strand
        join(port[-1])
    F_pull = pull * lam * v * v

    steps = int(round(seconds / dt))
    T: list[float] = []
    VR: list[float] = []
    US: list[float] = []
    H: list[float] = []
    TA: list[float] = []  # the mean over the strand's joints
    SAG: list[float] = []  # the strand joints' largest distance from the port's line
    lift_v: list[float] = []
    lift_dx: list[float] = []
    rel_pending: list[tuple[int, int]] = []
    rel_dw: list[float] = []
    errs: list[float] = []
    t0 = time.perf_counter()
    for step in range(steps):
        roller.apply_force_at_world_point((-cart, 0.0), roller.position)
        if drive == "pull":
            bodies[lo].apply_force_at_world_point((F_pull, 0.0), lead(lo))
        space.step(dt)
        c = roller.position
        # soft releases: ramp the spring down, then drop it
        for i in list(softs):
            sp, s0, k0, c0 = softs[i]
            f = 1.0 - (step - s0) * dt / (3.0 * release_time)
            if f <= 0.0:
                space.remove(sp)
                del softs[i]
            else:
                sp.stiffness = k0 * f
                sp.damping = c0 * f
        # lift: the lifting link's tail passes under the centre
        while tail(n).x <= c.x:
            p = tail(n)
            lift_v.append(roller.velocity_at_world_point(p).length)
            lift_dx.append(c.x - p.x)
            space.remove(table_pin.pop(n))
            weld(n)
            # the next link, at rest on the table
            q = (m_next * L, 0.0)
            new_link(n + 1, (p.x, p.y), q)
            join(n)
            pin_table(n + 1)
            m_next += 1
            n += 1
        # release: the top welded link's lead passes over the centre
        while b < n - 2:
            pl = lead(b)
            ang = math.atan2(pl.x - c.x, pl.y - c.y)  # clockwise from the top
            if ang < release_angle + release_frac * d_ang:
                break
            unweld(b, step)
            rel_pending.append((b, step))
            b += 1
        while rel_pending and (step - rel_pending[0][1]) * dt >= 1e-3:
            i, _ = rel_pending.pop(0)
            if i in bodies:
                rel_dw.append(bodies[i].angular_velocity - roller.angular_velocity)
        # the drive's end of the strand
        if drive == "port":
            kf = bodies[lo]
            if kf.position.x > c.x + (strand_links + 0.5) * L:
                kf.body_type = pymunk.Body.KINEMATIC
                kf.velocity = (v, 0.0)
                kf.angular_velocity = 0.0
                unjoin(lo - 1)  # kinematic to kinematic: not needed
                port.append(lo)
                lo += 1
                while len(port) > 4:
                    k = port.pop(0)
                    if k in up:
                        unjoin(k)
                    space.remove(bodies.pop(k))
        else:
            if b - lo > strand_max:
                unjoin(lo)
                space.remove(bodies.pop(lo))
                lo += 1
        mid = (lo + b) // 2
        j = up.get(mid)
        T.append(j.impulse / dt if j is not None else math.nan)
        VR.append(roller.velocity.x)
        third = range(lo + (b - lo) // 3, lo + 2 * (b - lo) // 3 + 1)
        US.append(float(np.mean([bodies[i].velocity.x for i in third])))
        H.append(table_pin[n].impulse / dt)
        js = [up[i].impulse for i in range(lo, b - 1) if i in up]
        TA.append(sum(js) / (len(js) * dt) if js else math.nan)
        SAG.append(max(abs(tail(i).y - y0) for i in range(lo, b)))
        if step % 20 == 0:
            e = 0.0
            for i, jj in up.items():
                if bodies[i].body_type != pymunk.Body.DYNAMIC and \
                        bodies[i + 1].body_type != pymunk.Body.DYNAMIC:
                    continue
                e = max(e, (tail(i) - bodies[i + 1].local_to_world(jj.anchor_b)).length)
            errs.append(e)
        if not math.isfinite(roller.position.x) or abs(roller.velocity.x) > 10 * v:
            break
    wall = time.perf_counter() - t0
    nw = max(1, int(round(window / dt)))
    out = []
    for i0 in range(0, len(VR) - nw + 1, nw):
        u = float(np.mean(US[i0:i0 + nw]))
        if drive == "port":
            tb = float(np.nanmean(T[i0:i0 + nw])) / (lam * v * v)
            pred = 0.25 + 0.5 * cart / (lam * v * v)
        else:
            tb = F_pull / (lam * u * u) if u > 0 else math.nan
            pred = 0.25 + 0.5 * cart / (lam * u * u) if u > 0 else math.nan
        out.append({"t": (i0 + nw) * dt, "vR": float(np.mean(VR[i0:i0 + nw])), "u": u,
                    "T_bar": tb, "Tmid_bar": float(np.nanmean(T[i0:i0 + nw])) / (lam * u * u),
                    "pred": pred, "TA_bar": float(np.nanmean(TA[i0:i0 + nw])) / (lam * v * v),
                    "sag": float(np.max(SAG[i0:i0 + nw])),
                    "H_bar": float(np.mean(H[i0:i0 + nw])) / (lam * v * v)})
    return {"dt": dt, "windows": out, "ran": len(VR) * dt, "lifted": n - i_lift,
            "released": b - n_strand,
            "max_err": max(errs or [0.0]), "wall": wall, "VR": np.array(VR),
            "T": np.array(T) / (lam * v * v), "lift_v": np.array(lift_v),
            "lift_dx": np.array(lift_dx), "rel_dw": np.array(rel_dw),
            "pred_port": 0.25 + 0.5 * cart / (lam * v * v)}


def summary(o: dict, last: float = 1.0) -> dict:
    """Means over the last ``last`` s; spread = std of the window means."""
    w = [x for x in o["windows"] if x["t"] > o["ran"] - last + 1e-9]
    f = {k: np.array([x[k] for x in w]) for k in ("vR", "u", "T_bar", "pred", "H_bar",
                                                  "Tmid_bar", "TA_bar", "sag")}
    return {"vR": float(f["vR"].mean()), "vR_sd": float(f["vR"].std()),
            "u": float(f["u"].mean()), "T": float(np.nanmean(f["T_bar"])),
            "T_sd": float(np.nanstd(f["T_bar"])), "pred": float(np.nanmean(f["pred"])),
            "H": float(f["H_bar"].mean()), "Tmid": float(np.nanmean(f["Tmid_bar"])),
            "TA": float(np.nanmean(f["TA_bar"])), "TA_sd": float(np.nanstd(f["TA_bar"])),
            "sag": float(f["sag"].max())}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speed", type=float, default=3.0, help="port speed v (m/s)")
    ap.add_argument("--cart", type=float, default=0.0, help="cart force F_c (N), holding back")
    ap.add_argument("--seconds", type=float, default=2.0)
    ap.add_argument("--dts", type=float, nargs="+", default=[5e-4, 2.5e-4, 1.25e-4])
    ap.add_argument("--radius", type=float, default=0.03, help="roller radius r (m)")
    ap.add_argument("--roller-mass", type=float, default=0.04)
    ap.add_argument("--strand-links", type=int, default=6)
    ap.add_argument("--iterations", type=int, default=20)
    ap.add_argument("--bias", type=float, default=1e-10, help="error_bias of every joint")
    ap.add_argument("--release", choices=["hard", "soft"], default="hard")
    ap.add_argument("--release-angle", type=float, default=0.0,
                    help="release when the lead joint is this far (rad, clockwise) past the top")
    ap.add_argument("--release-frac", type=float, default=0.0,
                    help="release this many chord angles later (added to --release-angle); "
                    "0.5: the strand leaves from the highest joint on the roller")
    ap.add_argument("--release-time", type=float, default=2e-3,
                    help="soft: the spring's time; it is ramped out over 3 times this (s)")
    ap.add_argument("--drive", choices=["port", "pull"], default="port")
    ap.add_argument("--pull", type=float, default=0.25,
                    help="pull: the constant force on the strand's end, in lambda v^2")
    ap.add_argument("--strand-max", type=int, default=400,
                    help="pull: the longest strand (links); the leading link is dropped")
    ap.add_argument("--windows", action="store_true", help="print every window")
    a = ap.parse_args(argv)
    for dt in a.dts:
        o = run(a.speed, a.cart, dt, a.seconds, r=a.radius, roller_mass=a.roller_mass,
                strand_links=a.strand_links, iterations=a.iterations, bias=a.bias,
                release=a.release, release_angle=a.release_angle,
                release_frac=a.release_frac,
                release_time=a.release_time, drive=a.drive, pull=a.pull,
                strand_max=a.strand_max)
        s = summary(o)
        late = [w["vR"] for w in o["windows"] if w["t"] > 0.2]
        locked = (not late) or min(late) < 0.25 * a.speed or o["ran"] < a.seconds - 1e-9
        tag = "LOCKED/STALLED" if locked else "no lock"
        if a.drive == "port":
            reading = (f"Tbar {s['T']:.4f} +- {s['T_sd']:.4f} (loss-free {s['pred']:.4f}), "
                       f"table pin {s['H']:.3f} lambda v^2")
        else:
            reading = (f"strand u {s['u']:.4f} m/s, F/(lambda u^2) {s['T']:.4f} +- "
                       f"{s['T_sd']:.4f} (loss-free {s['pred']:.4f}), mid-joint "
                       f"{s['Tmid']:.4f}")
        print(f"dt {dt * 1e3:.4g} ms: ran {o['ran']:.2f} s, lifted {o['lifted']} links, {tag}; "
              f"last 1 s: vR {s['vR']:.4f} +- {s['vR_sd']:.4f} m/s, {reading}; "
              f"lift: roller at the joint {np.median(o['lift_v']):.3f} m/s (median), "
              f"{o['lift_v'].max():.3f} (max); released link 1 ms on turns "
              f"{np.median(o['rel_dw']):+.1f} rad/s vs roller; max joint gap "
              f"{o['max_err'] * 1e3:.3f} mm ({o['wall']:.1f} s wall)", flush=True)
        if a.windows:
            print("   t vR Tbar sag(mm): " + ", ".join(
                f"{w['t']:.2f} {w['vR']:.3f} {w['T_bar']:.3f} {w['sag'] * 1e3:.1f}"
                for w in o["windows"]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
