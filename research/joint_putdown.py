"""A folding roller that holds the chain by joints: the put-down rig of the proposed design.

The contact machine's folding roller (``chainfountain.sim.pickup.RollerRig``, mode
'putdown') grips the chain by friction; without a forward push it falls behind and the
chain piles before it, and the folds built on it are not converged in the step
(``docs/apparatus.md``, "Put-down" and "The fold depends on the time step"). This rig
tries the design proposed in ``research/notes/apparatus_notebook.md`` ("Thirty-eighth
session"): the chain's joints are pinned to the roller as they reach its top, carried
round, and pinned to the table when they come down to it; the roller pivots about the
joint it has just laid (a rolling polygon). No gravity (the paper analyses the mechanism
without it), ``alpha = 0``: the strand arrives horizontally over the top, pushed in at
``v`` by a row of kinematic links; a cart force ``F_c`` pushes the roller along its motion.

The roller's axle runs in a horizontal groove and a rolling constraint (the contact point
kept on the vertical through it) makes it roll at the radius that lays one link per chord
angle; a gripped joint may move along the roller's radius by ``play``; a laid link leaves
the space once both its ends are down.

It prints, per step size and per 0.05 s, the roller's speed (``v/2`` loss-free; the
rolling radius gives 1.487 m/s at 3 m/s) and the strand tension (a mid-strand joint's
impulse over the step) against the loss-free balance ``Tbar = 1/4 + Fbar_c/2``
(:func:`chainfountain.sim.pickup.lossless_bar` at ``alpha = 0``).

Measured (3 m/s, no cart, 0.3 s): for 0.1 s the roller runs at 1.46-1.48 m/s with the
strand at ``Tbar`` 0.29-0.40, then the constraints lock it within 0.15-0.2 s at 0.5,
0.25 and 0.125 ms (sooner at the smaller steps). Held at both ends by constraints (the
port's kinematic links and the laid chain's pin) with the roll fixed, the gripped joints'
angles, the rolling and the laid spacing over-determine the chain, and the solver's
impulses grow until the roller stops. A pivoting polygon without the rolling constraint
did not lock, but lost most of the roller's speed at each joint's landing (ten joints per
turn on the 30-mm roller). A working grip needs a compliant link somewhere: a rolling
constraint that slips beyond a force, or a roller many links round.

The rig that works is ``research/joint_putdown_weld.py`` (thirty-ninth session): gripped
links welded to the roller (pivot + gear at their own place), no rolling constraint (the
roller is a one-freedom linkage between the laid chain and the strand), the strand's last
link caught onto the rim chord; converged in the step on a roller of radius 5 links.

Usage::

    python research/joint_putdown.py                      # 3 m/s, no cart, 0.5/0.25/0.125 ms
    python research/joint_putdown.py --speed 3 --cart 0.05 --seconds 2
"""

from __future__ import annotations

import argparse
import math

import numpy as np
import pymunk


def run(v: float, cart: float, dt: float, seconds: float, L: float = 0.02,
        lam: float = 0.05, r: float = 0.03, rho: float = 0.002, roller_mass: float = 0.04,
        iterations: int = 20, strand_links: int = 6, window: float = 0.05) -> dict:
    """One put-down run; the roller speed and the strand tension per ``window`` s."""
    from chainfountain.sim.chain import Chain
    from chainfountain.sim.config import ChainConfig, SolverConfig

    space = pymunk.Space()
    space.iterations = iterations
    solver = SolverConfig(dt=dt, iterations=iterations)
    chain = Chain(space, ChainConfig(link_length=L, linear_density=lam, link_radius=rho,
                                     bending_stiffness=0.0, bending_damping=0.0),
                  solver, shapes=False)
    R = r + rho  # the chain's centre line on the roller
    vR = 0.5 * v
    om = vR / R  # counter-clockwise: the roller rolls towards -x
    rest = 2.0 * L  # laid chain at the start: two links (laid links leave the space)
    # the path: laid chain from x = rest to the bottom contact (0, 0), round the roller's
    # -x side to its top, then the strand along +x at the top's height
    pts = [(rest - k * L, 0.0) for k in range(int(round(rest / L)) + 1)]
    n_laid = len(pts) - 1  # index of the bottom contact vertex
    d_ang = 2.0 * math.asin(L / (2.0 * R))
    th = -0.5 * math.pi
    while th - d_ang >= -1.5 * math.pi - 1e-9:
        th -= d_ang
        pts.append((R * math.cos(th), R + R * math.sin(th)))
    i_top = len(pts) - 1
    xw, yw = pts[-1]  # the last vertex on the roller, short of its top: the strand starts
    y0 = 2.0 * R      # on the top's tangent, one link from it
    x0 = xw + math.sqrt(L * L - (y0 - yw) ** 2)
    for i in range(strand_links):
        pts.append((x0 + i * L, y0))
    P = np.array(pts)

    def vel(p: np.ndarray, k: int) -> tuple[float, float]:
        if k < n_laid:
            return (0.0, 0.0)
        if k < i_top:  # on the roller, rolling about the bottom contact
            return (-om * p[1], om * p[0])
        return (-v, 0.0)

    for k in range(len(P) - 1):  # link k spans P[k] -> P[k+1], pointing to index 0
        c = 0.5 * (P[k] + P[k + 1])
        ang = math.atan2(P[k][1] - P[k + 1][1], P[k][0] - P[k + 1][0])
        w = om if n_laid <= k < i_top else 0.0
        chain.append(chain.make_body(tuple(c), ang, velocity=vel(c, k), angular_velocity=w))
    roller = pymunk.Body(roller_mass, 0.5 * roller_mass * r * r)
    roller.position = (0.0, R)
    roller.velocity = (-vR, 0.0)
    roller.angular_velocity = om
    static = space.static_body
    axle = pymunk.GrooveJoint(static, roller, (-50.0, R), (50.0, R), (0.0, 0.0))
    # rolling without slip at the radius that lays the links' length per chord angle
    R_roll = L / d_ang

    def contact() -> tuple[float, float]:
        return (roller.position.x, R - R_roll)

    def set_roll(j: pymunk.GrooveJoint) -> None:
        """The contact point on the roller stays on the vertical through it: only the
        x-component (the axle's groove holds the height; a pivot would fight it)."""
        cx, cy = contact()
        j.groove_a, j.groove_b = (cx, cy - 1.0), (cx, cy + 1.0)
        j.anchor_b = roller.world_to_local((cx, cy))

    roll = pymunk.GrooveJoint(static, roller, (0.0, -1.0), (0.0, 1.0), (0.0, 0.0))
    set_roll(roll)
    for j in (axle, roll):
        j.error_bias = 1e-10
    space.add(roller, axle, roll)
    links = chain.links

    def end_of(k: int) -> pymunk.Vec2d:
        """Vertex ``k``: link ``k``'s front end (world)."""
        return links[k].body.local_to_world((0.5 * L, 0.0))

    tabled: dict[int, pymunk.PivotJoint] = {}

    def pin_table(k: int) -> None:
        """Pin vertex ``k`` to the table where it is; the link laid before it (both its
        ends now on the table) leaves the space: pinned at both ends it would fight the
        chain joint's small error for ever."""
        j = pymunk.PivotJoint(static, links[k].body, end_of(k))
        j.error_bias = 1e-10
        space.add(j)
        tabled[k] = j
        old = k - 1
        if old in tabled:
            space.remove(tabled.pop(old), links[old].up_joint, links[old].body)
            links[old].up_joint = None

    def grip(k: int) -> pymunk.GrooveJoint:
        """Hold vertex ``k`` at its angle on the roller, free along the radius by ``play``."""
        q = roller.world_to_local(end_of(k))
        u = q / abs(q)
        j = pymunk.GrooveJoint(roller, links[k].body, u * (R - play), u * (R + play),
                               (0.5 * L, 0.0))
        j.error_bias = 1e-10
        space.add(j)
        return j

    play = 1.0e-3
    pin_table(n_laid - 1)
    held = {k: grip(k) for k in range(n_laid, i_top + 1)}
    low = n_laid  # the lowest vertex still on the roller
    nxt_grip = i_top + 1

    # the port: kinematic links behind the strand, pushing in at v
    def port_link(x: float) -> None:
        chain.append_unjoined(chain.make_body((x, y0), math.pi, kinematic=True,
                                              velocity=(-v, 0.0)))

    for i in range(4):
        port_link(float(P[-1][0]) + (i + 0.5) * L)
    n_port = 4
    chain.join(len(links) - n_port - 1)  # the strand's last link to the first port link
    steps = int(round(seconds / dt))
    T: list[float] = []
    VR: list[float] = []
    for _ in range(steps):
        set_roll(roll)
        roller.apply_force_at_world_point((-cart, 0.0), roller.position)  # it rolls
        space.step(dt)
        xc = roller.position.x
        # grip: a strand vertex that has passed over the roller's top
        while nxt_grip < len(links) - n_port and end_of(nxt_grip).x <= xc:
            held[nxt_grip] = grip(nxt_grip)
            nxt_grip += 1
        # lay: a vertex that has passed under the roller's bottom is pinned to the table
        while low in held and end_of(low).x >= xc:
            space.remove(held.pop(low))
            pin_table(low)
            low += 1
        # the port: release its front link into the strand once within the strand's length
        front = len(links) - n_port
        if links[front].body.position.x < xc + (strand_links + 0.5) * L:
            chain.make_dynamic(links[front])
            n_port -= 1
            chain.join(front)  # to the next port link
            port_link(links[-1].body.position.x + L)
            n_port += 1
        mid = nxt_grip + strand_links // 2
        ok = mid < len(links) - n_port - 1 and links[mid].up_joint is not None
        T.append(links[mid].up_joint.impulse / dt if ok else math.nan)
        VR.append(-roller.velocity.x)
    n = max(1, int(round(window / dt)))
    out = []
    for a in range(0, steps - n + 1, n):
        out.append({"t": (a + n) * dt, "vR": float(np.mean(VR[a:a + n])),
                    "T_bar": float(np.nanmean(T[a:a + n])) / (lam * v * v)})
    return {"dt": dt, "windows": out, "pred": 0.25 + 0.5 * cart / (lam * v * v)}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speed", type=float, default=3.0)
    ap.add_argument("--cart", type=float, default=0.0, help="cart force F_c (N)")
    ap.add_argument("--seconds", type=float, default=0.3)
    ap.add_argument("--dts", type=float, nargs="+", default=[5e-4, 2.5e-4, 1.25e-4])
    a = ap.parse_args(argv)
    for dt in a.dts:
        o = run(a.speed, a.cart, dt, a.seconds)
        rows = ", ".join(f"{w['t']:.2f} s {w['vR']:.3f} m/s Tbar {w['T_bar']:.3f}"
                         for w in o["windows"])
        print(f"dt {dt * 1e3:.4g} ms (v/2 = {0.5 * a.speed:g} m/s, loss-free Tbar "
              f"{o['pred']:.3f}): {rows}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
