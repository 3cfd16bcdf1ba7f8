"""The joint-gripped folding roller as a one-freedom linkage: gripped links welded to it.

A redesign of ``research/joint_putdown.py`` (the first rig, which locks within 0.2 s;
deleted, in git history: ``git show c48f91db91fb:research/joint_putdown.py``).
Same scene: no gravity, ``alpha = 0``, the strand arrives horizontally over the roller's
top at ``v``, pushed in by a row of kinematic port links that travel with the roller; a
cart force ``F_c`` pushes the roller along its motion; the loss-free balance is
``Tbar = T/(lambda v^2) = 1/4 + Fbar_c/2`` and the roller runs at ``v/2`` (the chain is
laid at rest, so the laying rate is the roller's speed and the chain's conservation gives
``v/2`` on average whatever the roller's radius).

What is different, and why it cannot over-determine the chain:

* **Weld, not groove.** A gripped link is welded to the roller (a pivot at its front
  joint and a gear of ratio 1 holding its angle: exactly its three freedoms), both at its
  own current place, so a weld starts with zero error. The chain joint between two welded
  links is removed (it would be a redundant loop through the roller). Gripped links keep
  their own bodies, so the momentum the chain carries round is the chain's own.
* **No rolling constraint.** The axle runs in a horizontal groove at height ``R``; the
  roller (with its welded links) has two freedoms left, and the landing link (its front
  pinned to the table, its back jointed to the lowest welded link) takes one: the roller
  is a one-freedom linkage, driven by the strand and the cart only. With the axle at fixed
  height, a welded joint at the bottom of its circle has no vertical velocity, and the
  landing link (nearly horizontal) forbids a horizontal one: it comes down at rest, and
  the landing link's hand-over to the next link is continuous in velocity (both roll
  about the landed joint). Nothing is imposed that the linkage does not already obey.
* **Grip** (``--grip``): the strand's last link is welded when its back joint
  ``top``: passes over the roller's centre, at its own place wherever that is (the first
  rig's rule); ``rim``: as ``top``, or sooner if it comes within ``--grip-tol`` of the
  rim; ``rimonly``: only when it comes within ``--grip-tol`` of the rim; ``chord``: when
  the rim point at chord ``L`` from the last gripped joint passes over the centre, the
  link first turned about its front joint to put its back joint on that point (the
  strand's next joint is left where it was, and its joint closes the gap); ``catch``
  (default): as ``rim``, welded with its gear set to the chord onto the rim (the point at
  chord ``L`` from the last gripped joint), the difference closed by the gear's error
  correction in ``--catch-time`` (no teleport, no jump in position); ``soft``: as
  ``catch``, but the link's angle is drawn to the chord by a critically damped rotary
  spring (time ``--catch-time``) and welded where it is ``3 --catch-time`` later.
* **Land**: the lowest welded joint is pinned to the table where it is as it passes
  under the roller's centre; the landing link (both ends now down) leaves the space and
  the lowest welded link is un-welded and becomes the landing link.

The strand has ``--strand-links`` free links between the top grip and the port (the port
releases its front link when it is within that many links of the roller's centre). Its
tension is read at the middle joint (impulse over the step) and averaged per 0.05 s; the
rig prints the mean and spread (standard deviation of the 0.05-s means) over the last
second, whether the roller stalled (a window below ``v/4`` after 0.2 s), how far outside
the rim the gripped joints were when gripped and how low the laid joints lie.

Measured (3 m/s, 2 s, 0.5/0.25/0.125 ms; ``research/notes/apparatus_notebook.md``,
"Thirty-ninth session"): nothing locks. On the rig's 30-mm roller (ten links a turn)
``top`` runs but the welded polygon grows up to 27 mm outside the rim; ``rimonly``
stalls without a cart (at ``Tbar = 1/4`` the strand has no pull onto the rim) and with
``--cart 0.05`` reads ``Tbar`` 0.302/0.307/0.316 (loss-free 0.306); ``catch`` reads
0.246/0.254/0.273 (0.250): each grip's jolt (the link turns ~10 rad/s slower than the
roller) is not resolved in the step. On a roller of radius 5 links (``--radius 0.1``)
``catch`` is converged: ``Tbar`` 0.2490/0.2496/0.2498 (0.2500) and with ``--cart 0.05``
0.3045/0.3049/0.3052 (0.3056), spread <= 0.004, roller 1.5017/1.5007/1.5002 m/s (the
excess over ``v/2`` is the joints' O(dt) stretch under ``error_bias`` 1e-10); 10 s hold.

Usage::

    python -m research.joint_putdown_weld --radius 0.1              # catch, no cart: converged
    python -m research.joint_putdown_weld --radius 0.1 --cart 0.05 --seconds 10
    python -m research.joint_putdown_weld --grip rimonly --cart 0.05   # the rig's 30-mm roller
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
        grip: str = "catch", grip_tol: float = 5e-4, window: float = 0.05,
        bias: float = 1e-10, catch_time: float = 5e-3, wave_damping: float = 0.0,
        snap_every: float = 0.0) -> dict:
    """One put-down run; the roller speed and the strand tension per ``window`` s, and
    diagnostics of the grips (``grip_r``: the joint's distance outside the rim when
    gripped; ``grip_dw``: the link's angular velocity less the roller's) and landings
    (``land_v``: the joint's speed, ``land_y``: its height when pinned to the table)."""
    space = pymunk.Space()
    space.iterations = iterations
    static = space.static_body
    m_link = lam * L
    I_link = m_link * L * L / 12.0
    h = 0.5 * L
    R = r + rho  # the chain's centre line on the roller
    d_ang = 2.0 * math.asin(L / (2.0 * R))  # chord angle of one link
    vR = 0.5 * v
    om = vR / R  # counter-clockwise: the roller rolls towards -x, rolling about the bottom
    # the path: one laid link ending at the bottom contact (0, 0), round the roller's -x side
    # to its top, then the strand along +x at the top's height
    pts = [(L, 0.0), (0.0, 0.0)]
    th = -0.5 * math.pi
    while th - d_ang >= -1.5 * math.pi - 1e-9:
        th -= d_ang
        pts.append((R * math.cos(th), R + R * math.sin(th)))
    i_top = len(pts) - 1
    xw, yw = pts[-1]
    y0 = 2.0 * R
    x0 = xw + math.sqrt(L * L - (y0 - yw) ** 2)
    for i in range(strand_links):
        pts.append((x0 + i * L, y0))
    P = np.array(pts)

    def vel_on_roller(p: np.ndarray) -> tuple[float, float]:
        # rolling about the bottom contact (0, 0)
        return (-om * p[1], om * p[0])

    bodies: list[pymunk.Body] = []
    for k in range(len(P) - 1):  # link k spans P[k] (front) -> P[k+1] (back)
        b = pymunk.Body(m_link, I_link)
        c = 0.5 * (P[k] + P[k + 1])
        b.position = tuple(c)
        b.angle = math.atan2(P[k][1] - P[k + 1][1], P[k][0] - P[k + 1][0])
        if k == 0:  # the landing link: rolls about its front (on the table)
            b.velocity = vel_on_roller(c)
            b.angular_velocity = om
        elif k + 1 <= i_top:  # welded
            b.velocity = vel_on_roller(c)
            b.angular_velocity = om
        else:
            b.velocity = (-v, 0.0)
        space.add(b)
        bodies.append(b)

    roller = pymunk.Body(roller_mass, 0.5 * roller_mass * r * r)
    roller.position = (0.0, R)
    roller.velocity = (-vR, 0.0)
    roller.angular_velocity = om
    axle = pymunk.GrooveJoint(static, roller, (-1e3, R), (1e3, R), (0.0, 0.0))
    axle.error_bias = bias
    space.add(roller, axle)

    def front(k: int) -> pymunk.Vec2d:
        return bodies[k].local_to_world((h, 0.0))

    def back(k: int) -> pymunk.Vec2d:
        return bodies[k].local_to_world((-h, 0.0))

    dampers: dict[int, pymunk.DampedRotarySpring] = {}  # the wave damper on joint k
    up: dict[int, pymunk.PivotJoint] = {}  # the chain joint from link k's back to k+1's front

    def join(k: int) -> None:
        """Chain joint between link k's back and link k+1's front (anchored where they are
        now on link k+1, so it starts without error)."""
        p = back(k)
        j = pymunk.PivotJoint(bodies[k], bodies[k + 1], (-h, 0.0),
                              bodies[k + 1].world_to_local(p))
        j.error_bias = bias
        j.collide_bodies = False
        space.add(j)
        up[k] = j
        if wave_damping > 0.0 and k not in dampers:
            dmp = pymunk.DampedRotarySpring(bodies[k], bodies[k + 1], 0.0, 0.0,
                                            wave_damping * lam * v * L * L)
            dmp.collide_bodies = False
            space.add(dmp)
            dampers[k] = dmp

    def unjoin(k: int) -> None:
        space.remove(up.pop(k))
        if k in dampers:
            space.remove(dampers.pop(k))

    welds: dict[int, tuple] = {}

    def weld(k: int, angle: float | None = None) -> None:
        """Weld link k to the roller: a pivot at its front joint, a gear holding its angle
        (its own, or ``angle``: then the gear closes the difference in ``catch_time``)."""
        p = front(k)
        pj = pymunk.PivotJoint(roller, bodies[k], roller.world_to_local(p), (h, 0.0))
        own = bodies[k].angle
        if angle is None:
            target = own
        else:  # the nearest turn to its own angle
            target = own + math.remainder(angle - own, 2.0 * math.pi)
        gj = pymunk.GearJoint(roller, bodies[k], target - roller.angle, 1.0)
        for j in (pj, gj):
            j.error_bias = bias
            j.collide_bodies = False
        if angle is not None:
            gj.error_bias = math.exp(-1.0 / catch_time)
        space.add(pj, gj)
        welds[k] = (pj, gj)
        if k - 1 in welds and k - 1 in up:
            unjoin(k - 1)  # redundant: both links on the roller

    def unweld(k: int) -> None:
        space.remove(*welds.pop(k))

    softs: dict[int, tuple] = {}  # link -> (spring, step made)

    def soft_weld(k: int, angle: float, step: int) -> None:
        """A compliant grip: the link's front is pinned to the roller at once, its angle
        is drawn to ``angle`` by a critically damped rotary spring (time ``catch_time``,
        the link's inertia about its front) and welded where it is ``3 catch_time`` later."""
        p = front(k)
        pj = pymunk.PivotJoint(roller, bodies[k], roller.world_to_local(p), (h, 0.0))
        pj.error_bias = bias
        pj.collide_bodies = False
        own = bodies[k].angle
        target = own + math.remainder(angle - own, 2.0 * math.pi)
        I_f = m_link * L * L / 3.0
        sp = pymunk.DampedRotarySpring(bodies[k], roller, target - roller.angle,
                                       I_f / catch_time ** 2, 2.0 * I_f / catch_time)
        # (DampedRotarySpring's rest angle: angle of a minus angle of b)
        sp.collide_bodies = False
        space.add(pj, sp)
        welds[k] = (pj,)
        softs[k] = (sp, step)
        if k - 1 in welds and k - 1 in up:
            unjoin(k - 1)

    def harden(k: int) -> None:
        sp, _ = softs.pop(k)
        space.remove(sp)
        (pj,) = welds[k]
        gj = pymunk.GearJoint(roller, bodies[k], bodies[k].angle - roller.angle, 1.0)
        gj.error_bias = bias
        gj.collide_bodies = False
        space.add(gj)
        welds[k] = (pj, gj)

    table_pin: dict[int, pymunk.PivotJoint] = {}

    def pin_table(k: int) -> None:
        j = pymunk.PivotJoint(static, bodies[k], front(k))
        j.error_bias = bias
        space.add(j)
        table_pin[k] = j

    # initial constraints
    for k in range(len(bodies) - 1):
        join(k)
    pin_table(0)
    for k in range(1, i_top):  # links 1..i_top-1 lie on the roller (vertices 1..i_top)
        weld(k)
    a = 1          # the lowest welded link (its front: the next joint to land)
    b = i_top      # the strand's last link (its front is on the roller)

    # the port: kinematic links behind the strand, pushing in at v
    port: list[pymunk.Body] = []

    def port_link() -> None:
        last = bodies[-1]
        p = last.local_to_world((-h, 0.0))
        kb = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        kb.position = (p.x + h, y0)
        kb.angle = math.pi
        kb.velocity = (-v, 0.0)
        space.add(kb)
        bodies.append(kb)
        port.append(kb)

    for _ in range(4):
        port_link()
    join(len(bodies) - 5)  # the strand's last link to the first port link
    n_port = 4

    steps = int(round(seconds / dt))
    T: list[float] = []
    TA: list[float] = []  # the mean over the strand's joints
    VR: list[float] = []
    OM: list[float] = []
    errs: list[float] = []
    land_v: list[float] = []
    land_y: list[float] = []
    grip_r: list[float] = []
    grip_step: list[int] = []
    grip_dw: list[float] = []
    err_where: list[int] = []
    snaps: list = []
    moved_max = 0.0
    t0 = time.perf_counter()
    for step in range(steps):
        roller.apply_force_at_world_point((-cart, 0.0), roller.position)
        space.step(dt)
        c = roller.position
        for k in [k for k, (_, s0) in softs.items() if step - s0 >= 3.0 * catch_time / dt]:
            harden(k)
        # land: the lowest welded joint passes under the centre
        while a < b - 1 and front(a).x >= c.x:
            # the landing link a-1 leaves; link a becomes the landing link
            land_v.append(bodies[a].velocity_at_world_point(front(a)).length)
            land_y.append(front(a).y)
            unjoin(a - 1)
            space.remove(table_pin.pop(a - 1), bodies[a - 1])
            unweld(a)
            pin_table(a)
            if a + 1 in welds:
                join(a)  # link a's back to link a+1's front (welded)
            a += 1
        # grip: the strand's last link b is welded
        while b + 1 < len(bodies) - n_port:
            pb = back(b)
            go = False
            if grip == "top":
                go = pb.x <= c.x
            elif grip == "rim":
                go = pb.x <= c.x or (pb - c).length <= R + grip_tol
            elif grip == "rimonly":
                go = (pb - c).length <= R + grip_tol
            elif grip == "chord":
                pf = front(b)
                u = (pf - c)
                ang = math.atan2(u.y, u.x) - d_ang  # the rim point L ahead (towards +x)
                q = c + R * pymunk.Vec2d(math.cos(ang), math.sin(ang))
                go = q.x <= c.x
                if go:
                    # turn link b about its front so its back lies on q
                    bb = bodies[b]
                    new_ang = math.atan2(pf.y - q.y, pf.x - q.x)
                    moved_max = max(moved_max, (q - pb).length)
                    bb.angle = new_ang
                    bb.position = pf - pymunk.Vec2d(h, 0).rotated(new_ang)
                    # velocity: the roller's at those points
                    bb.velocity = roller.velocity_at_world_point(bb.position)
                    bb.angular_velocity = roller.angular_velocity
                    space.reindex_shapes_for_body(bb)
            elif grip in ("catch", "soft"):
                go = pb.x <= c.x or (pb - c).length <= R + grip_tol
            else:
                raise ValueError(grip)
            if not go:
                break
            grip_r.append((back(b) - c).length - R)
            grip_step.append(step)
            grip_dw.append(bodies[b].angular_velocity - roller.angular_velocity)
            if grip in ("catch", "soft"):
                pf = front(b)
                u = pf - c
                ang = math.atan2(u.y, u.x) - d_ang
                q = c + R * pymunk.Vec2d(math.cos(ang), math.sin(ang))
                moved_max = max(moved_max, (q - pb).length)
                target = math.atan2(pf.y - q.y, pf.x - q.x)
                if grip == "catch":
                    weld(b, target)
                else:
                    soft_weld(b, target, step)
            else:
                weld(b)
            b += 1
        # the port: release its front link into the strand once within the strand's length
        kf = port[0]
        if kf.position.x < c.x + (strand_links + 0.5) * L:
            kf.body_type = pymunk.Body.DYNAMIC
            kf.mass = m_link
            kf.moment = I_link
            kf.velocity = (-v, 0.0)
            port.pop(0)
            join(len(bodies) - n_port)  # the released link to the next port link
            port_link()
        mid = b + strand_links // 2
        j = up.get(mid)
        T.append(j.impulse / dt if j is not None else math.nan)
        js = [up[k].impulse for k in range(b, len(bodies) - n_port) if k in up]
        TA.append(sum(js) / (len(js) * dt) if js else math.nan)
        VR.append(-roller.velocity.x)
        OM.append(roller.angular_velocity)
        if step % 20 == 0:
            e, ke = 0.0, -1
            for k, jj in up.items():
                ek = (back(k) - bodies[k + 1].local_to_world(jj.anchor_b)).length
                if ek > e:
                    e, ke = ek, k
            errs.append(e)
            err_where.append(ke - b)
        if snap_every > 0 and step % max(1, int(round(snap_every / dt))) == 0:
            pts_now = [tuple(front(k) - c) for k in range(a - 1, len(bodies) - n_port + 1)]
            snaps.append(((step + 1) * dt, a - 1, b, np.array(pts_now)))
        if not math.isfinite(roller.position.x) or abs(roller.velocity.x) > 10 * v:
            break
    wall = time.perf_counter() - t0
    n = max(1, int(round(window / dt)))
    out = []
    for i0 in range(0, len(VR) - n + 1, n):
        out.append({"t": (i0 + n) * dt, "vR": float(np.mean(VR[i0:i0 + n])),
                    "T_bar": float(np.nanmean(T[i0:i0 + n])) / (lam * v * v),
                    "TA_bar": float(np.nanmean(TA[i0:i0 + n])) / (lam * v * v)})
    return {"dt": dt, "windows": out, "pred": 0.25 + 0.5 * cart / (lam * v * v),
            "ran": len(VR) * dt, "laid": a, "gripped": b, "max_err": max(errs or [0.0]),
            "moved_max": moved_max, "wall": wall, "VR": np.array(VR),
            "T": np.array(T) / (lam * v * v), "OM": np.array(OM),
            "land_v": np.array(land_v), "land_y": np.array(land_y),
            "grip_r": np.array(grip_r), "grip_step": np.array(grip_step),
            "grip_dw": np.array(grip_dw), "err_where": err_where, "errs": np.array(errs),
            "snaps": snaps}


def summary(o: dict, last: float = 1.0, window: float = 0.05) -> dict:
    """Mean roller speed and Tbar over the last ``last`` s; spread = std of window means."""
    w = [x for x in o["windows"] if x["t"] > o["ran"] - last + 1e-9]
    vr = np.array([x["vR"] for x in w])
    tb = np.array([x["T_bar"] for x in w])
    ta = np.array([x["TA_bar"] for x in w])
    return {"vR": float(vr.mean()), "vR_sd": float(vr.std()), "T": float(np.nanmean(tb)),
            "T_sd": float(np.nanstd(tb)), "vR_min": float(vr.min()),
            "TA": float(np.nanmean(ta)), "TA_sd": float(np.nanstd(ta))}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speed", type=float, default=3.0)
    ap.add_argument("--cart", type=float, default=0.0, help="cart force F_c (N)")
    ap.add_argument("--seconds", type=float, default=2.0)
    ap.add_argument("--dts", type=float, nargs="+", default=[5e-4, 2.5e-4, 1.25e-4])
    ap.add_argument("--grip", choices=["top", "rim", "rimonly", "chord", "catch", "soft"],
                    default="catch", help="when and how the strand's last link is gripped")
    ap.add_argument("--grip-tol", type=float, default=5e-4,
                    help="a joint this near the rim (m) is gripped (rim, rimonly, catch, soft)")
    ap.add_argument("--catch-time", type=float, default=5e-3,
                    help="catch: time constant of the gear's error correction (s); soft: "
                    "of the critically damped spring (s)")
    ap.add_argument("--radius", type=float, default=0.03, help="roller radius r (m)")
    ap.add_argument("--roller-mass", type=float, default=0.04)
    ap.add_argument("--strand-links", type=int, default=6)
    ap.add_argument("--iterations", type=int, default=20)
    ap.add_argument("--bias", type=float, default=1e-10,
                    help="error_bias of every joint (the apparatus's 1e-10)")
    ap.add_argument("--wave-damping", type=float, default=0.0,
                    help="D of a rotary damper D lambda v L^2 on every chain joint")
    ap.add_argument("--windows", action="store_true", help="print every window")
    a = ap.parse_args(argv)
    for dt in a.dts:
        o = run(a.speed, a.cart, dt, a.seconds, r=a.radius, roller_mass=a.roller_mass,
                strand_links=a.strand_links, iterations=a.iterations, grip=a.grip,
                grip_tol=a.grip_tol, catch_time=a.catch_time, bias=a.bias,
                wave_damping=a.wave_damping)
        s = summary(o)
        late = [w["vR"] for w in o["windows"] if w["t"] > 0.2]
        locked = bool(late) and min(late) < 0.25 * a.speed
        g = o["grip_r"] * 1e3
        print(f"dt {dt * 1e3:.4g} ms: ran {o['ran']:.2f} s, laid {o['laid']} links, "
              f"{'LOCKED/STALLED (a window below v/4)' if locked else 'no lock'}; last 1 s: "
              f"vR {s['vR']:.4f} +- {s['vR_sd']:.4f} m/s (v/2 = {0.5 * a.speed:g}), "
              f"Tbar {s['T']:.4f} +- {s['T_sd']:.4f} (loss-free {o['pred']:.4f}); "
              f"gripped joint outside the rim by {np.median(g):.2f} mm (median), "
              f"{g.max():.2f} mm (max); lowest laid joint at y = {o['land_y'].min() * 1e3:.2f} mm; "
              f"max joint gap {o['max_err'] * 1e3:.3f} mm "
              f"({o['wall']:.1f} s wall)", flush=True)
        if a.windows:
            print("   t vR Tbar: " + ", ".join(f"{w['t']:.2f} {w['vR']:.3f} {w['T_bar']:.3f}"
                                              for w in o["windows"]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
