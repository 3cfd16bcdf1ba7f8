"""One sampled step of a running apparatus: :func:`analyse` turns it into tensions
along the path (the exact momentum balance of :mod:`chainfountain.sim.measure`, with
the guide joints' impulses reconstructed, :mod:`.impulses`), speeds and the fountain's
shape (:class:`ApparatusSample`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from chainfountain.sim.apparatus import Apparatus
from chainfountain.sim.apparatus_report.impulses import (
    guided_impulses,
    open_guide_impulses,
    pivot_offset,
)
from chainfountain.sim.measure import ChainState, joint_forces, signed_tension, vertex_of


@dataclass
class ApparatusSample:
    """One measurement of a running apparatus (tensions scaled by ``lambda*v**2``)."""

    t: float
    v: float
    """Mean speed of the links in free flight (m/s)."""
    v_roller_up: float
    v_roller_lo: float
    T0_bar: float
    """Tension at the fountain start (guide exit)."""
    TE_bar: float
    """Tension at the fountain end (floor contact or end channel mouth)."""
    T_up_bar: float
    """Tension in the strand leaving the pick-up roller (on the upper plate)."""
    T_lo_bar: float
    """Tension in the strand arriving at the folding roller (nan without one)."""
    uc_bar: float
    lc_bar: float
    vertex_x: float
    vertex_y: float
    end_x: float
    end_y: float
    n_flight: int
    stretch: float
    channel_force_x: float
    """Net contact force of the end channel on the chain, x (N; 'fold', 'open')."""
    channel_force_y: float
    tail_reaction: float = math.nan
    """'open' with the joint turn: upward force of the lower plate's grooves on the tail
    (N), the lumped end included: the supported weight of the chain moving away, which
    grows as ``lambda g v`` per second (the paper's "reaction force change ... exactly
    known over time")."""


def analyse(app: Apparatus, t: float, pre_vel: np.ndarray, post, contacts: np.ndarray,
            dt: float, lam: float,
            roller: tuple[float, float, float, float],
            pivots: np.ndarray | None = None, pre_w: np.ndarray | None = None,
            lower: tuple[int, int, float, float] | None = None,
            pivot_x: np.ndarray | None = None, mouth: int | None = None
            ) -> tuple[ApparatusSample, dict]:
    """Measure one sampled step: signed tension from the exact momentum balance summed
    from the downstream end (:func:`chainfountain.sim.measure.joint_forces`, all contact
    impulses of floor, channels, plates, rollers and tables subtracted), located on
    the path. Returns the sample and per-joint profiles of the free flight.

    ``pivots`` ('fold'): the size of every chain joint's force in this step from the
    solver's pivot impulses (N). They correct the lower guide's reconstruction by
    :func:`~.impulses.pivot_offset`. ``pre_w`` and ``lower`` ('open' with the joint
    turn): the links' angular velocities before the step and the lower guide's state
    (:func:`~.impulses.open_guide_impulses`). ``pivot_x`` (the gripped fold): every
    chain joint's force along ``x`` (N), the lower plate strand's tension. ``mouth``
    ('fold' guide): one past the last link the guide held in this step
    (:attr:`~chainfountain.sim.apparatus.Apparatus.fold_mouth`); without it the mouth
    is found from the positions."""
    chain = app.chain
    n = len(post.angle)
    pre = ChainState(position=post.position, angle=post.angle, velocity=pre_vel,
                     angular_velocity=post.angular_velocity)
    contacts, k, T_lo_fold, tail_reaction = _with_guide_impulses(
        app, pre, pre_vel, post, contacts, dt, roller, pre_w, lower, pivot_x, mouth)
    F = joint_forces(pre, post, chain.mass, dt, app.g, n - 1, contacts)
    L = app.L
    J, gaps = _joints(post, L)
    d0 = np.hypot(J[:, 0], J[:, 1])
    j0 = int(np.argmin(d0))
    if app.fold_guided and k > 0 and pivots is not None:
        c = pivot_offset(F, pivots, np.arange(k + 3, j0 - 1))
        if c is not None:
            F[k - 1:] += c  # the reconstruction reaches the joints from the mouth up
    ten, _ = signed_tension(F, post, n - 1)
    jE = _end_joint(app, J, j0, k)
    links = np.arange(jE + 1, j0 + 1)
    speed = np.hypot(post.velocity[links, 0], post.velocity[links, 1]) if len(links) \
        else np.array([np.nan])
    v = float(np.mean(speed))
    scale = lam * v * v
    # strand tensions a few links away from the roller tops
    def at(x: float, y: float) -> float:
        k = int(np.argmin(np.hypot(J[:, 0] - x, J[:, 1] - y)))
        lo, hi = max(k - 2, 0), min(k + 3, len(ten))
        return float(np.mean(ten[lo:hi])) / scale

    xu, vu, xl, vl = roller
    if app.plate_mode == "groove":
        T_up = _plate_strand_tension(app, pre, post, contacts, F, J, dt, xu) / scale
    else:
        T_up = at(xu + 6 * L, app.y_up)
    if app.fold_guided:
        T_lo = T_lo_fold / scale
    else:
        T_lo = at(xl - 6 * L, app.y_lo) if app.lower is not None else math.nan
    flight = J[jE:j0 + 1]
    xv, yv = vertex_of(flight[::-1]) if len(flight) > 2 else (math.nan, math.nan)
    uc, lc = app.cart_bars(v, lam)
    end_contacts = _end_channel_force(app, post, contacts, jE, dt)
    TE, end_x, end_y = _fountain_end(app, ten, J, jE, j0)
    s = ApparatusSample(
        t=t, v=v, v_roller_up=vu, v_roller_lo=vl, T0_bar=float(ten[j0]) / scale,
        TE_bar=TE / scale, T_up_bar=T_up, T_lo_bar=T_lo, uc_bar=uc, lc_bar=lc,
        vertex_x=xv, vertex_y=yv, end_x=end_x, end_y=end_y,
        n_flight=len(links), stretch=float(gaps.sum() / (n * L)),
        channel_force_x=end_contacts[0], channel_force_y=end_contacts[1],
        tail_reaction=tail_reaction)
    prof = {"tension_bar": ten[jE:j0 + 1][::-1] / scale, "x": flight[::-1, 0].copy(),
            "y": flight[::-1, 1].copy(), "speed": speed[::-1].copy()}
    return s, prof


def _with_guide_impulses(app: Apparatus, pre: ChainState, pre_vel: np.ndarray, post,
                         contacts: np.ndarray, dt: float,
                         roller: tuple[float, float, float, float],
                         pre_w: np.ndarray | None,
                         lower: tuple[int, int, float, float] | None,
                         pivot_x: np.ndarray | None = None,
                         mouth: int | None = None
                         ) -> tuple[np.ndarray, int, float, float]:
    """The contact impulses with the lower guides' (and the end pull's) added as
    'contact' rows for the first ``k`` links. Returns the rows, ``k`` ('fold': one past
    the last guided link, the mouth; 0 if none), the tension on the lower plate
    ('fold', N; nan otherwise) and the tail grooves' upward force ('open' with the joint
    turn, N; nan otherwise)."""
    chain = app.chain
    n = len(post.angle)
    k = min(lower[0] + lower[1], n) if lower is not None else 0
    T_lo_fold = tail_reaction = math.nan
    if app.fold_guided:
        # tension on the lower plate from the horizontal joint force (grooves add none),
        # then along the guided links' axes up to the mouth
        ip, k = app.fold_guided_range(post.position, roller[2], mouth)
        if ip >= 2 and k > ip + 1:
            if app.gripped and pivot_x is not None:
                # the welds' and the table pin's impulses are not among the contacts, so
                # the sum from the end misses them; the horizontal strand's joint forces
                # along x are its tension (their size rings, fastbody.pivot_impulse)
                T_lo_fold = float(np.mean(pivot_x[ip - 2:ip + 3]))
                T_ip = float(pivot_x[ip])
            else:
                F1 = joint_forces(pre, post, chain.mass, dt, app.g, n - 1, contacts)
                T_lo_fold = float(-np.mean(F1[ip - 2:ip + 3, 0]))
                T_ip = float(-F1[ip, 0])
            contacts = contacts.copy()
            contacts[:k] = guided_impulses(app, pre_vel, post, dt, k, start=(ip, T_ip))
        else:
            k = 0
    elif app.end_pull or k:
        contacts = contacts.copy()
        if k:
            contacts[:k], tail_imp = open_guide_impulses(app, pre_vel, pre_w, post, dt,
                                                         lower)
            tail_reaction = tail_imp / dt
        else:  # external force on the end link, like a contact
            contacts[0, 0] += app.end_pull * dt
    return contacts, k, T_lo_fold, tail_reaction


def _joints(post, L: float) -> tuple[np.ndarray, np.ndarray]:
    """Position of each joint ``j`` (between links ``j`` and ``j+1``: the mean of their
    touching ends) and the gap between those ends (m)."""
    u = np.column_stack((np.cos(post.angle), np.sin(post.angle)))
    back = post.position - 0.5 * L * u
    front = post.position + 0.5 * L * u
    J = 0.5 * (back[:-1] + front[1:])  # joint j between link j and j+1
    gaps = np.linalg.norm(back[:-1] - front[1:], axis=1)
    return J, gaps


def _end_joint(app: Apparatus, J: np.ndarray, j0: int, k: int) -> int:
    """Index of the joint at the fountain's end, by arrangement (``j0``: the joint at
    the fountain start; ``k``: one past the 'fold' guide's last link)."""
    if app.fold_guided and k > 0:
        jE = k - 1  # the last guided link: the mouth of the joint guide
    elif app.end_mode == "absorbing" and app.floor_depth > 0:
        # the fountain end is where the falling chain crosses y = -H (the floor lies
        # floor_depth lower): the first joint at or above that height
        below = np.flatnonzero(J[:j0, 1] < -app.H)
        jE = int(below[-1]) + 1 if len(below) else 0
    elif app.end_mode == "absorbing":
        jE = 0  # joint behind the end link: the free end (Tbar_E = 0) is one link ahead
    elif app.variant == "floor":
        below = np.flatnonzero(J[:j0, 1] < -app.H + app.rho)
        jE = int(below[-1]) if len(below) else 0
    else:
        ex, ey = app.end
        dE = np.hypot(J[:j0, 0] - ex, J[:j0, 1] - ey)
        jE = int(np.argmin(dE)) if j0 > 0 else 0
    return jE


def _plate_strand_tension(app: Apparatus, pre: ChainState, post, contacts: np.ndarray,
                          F: np.ndarray, J: np.ndarray, dt: float, xu: float) -> float:
    """``plate = "groove"``: the tension (N) of the upper plate strand 6 links past the
    pick-up roller at ``xu``. The grooves' vertical impulses are not in ``contacts``: on
    the horizontal plate the tension is the horizontal joint force alone (grooves add
    none)."""
    L = app.L
    n = len(post.angle)
    k = int(np.argmin(np.hypot(J[:, 0] - xu - 6 * L, J[:, 1] - app.y_up)))
    Fu = F
    if app.upper_guided:
        # the upper guide's joint impulses are not among the contacts either (and
        # have horizontal parts on its bend and straight): sum from the upstream
        # end instead, the resting chain, whose table and roller contacts are all
        # recorded (F_j = -(momentum change of the links beyond joint j) / dt: the
        # sum over all links less the sum up to j)
        Fall = joint_forces(pre, post, app.chain.mass, dt, app.g, n, contacts)
        Fu = Fall[:-1] - Fall[-1]
    # (not the pivot forces: the grooves and the pivots over-constrain the straight
    # strand, and the pivots carry an alternating vertical part that adds about
    # 0.008 lambda v^2; the contacts are read with their stale impulses taken out,
    # docs/apparatus.md)
    return float(np.mean(-Fu[max(k - 2, 0):min(k + 3, len(Fu)), 0]))


def _end_channel_force(app: Apparatus, post, contacts: np.ndarray, jE: int,
                       dt: float) -> tuple[float, float]:
    """Net contact force (N) of the end channel on the chain ('fold', 'open'; nan
    otherwise)."""
    end_contacts = (math.nan, math.nan)
    if app.channel_lo is not None and jE > 0:
        lo_x, hi_x = app.channel_lo[:, 0].min() - 0.01, app.channel_lo[:, 0].max()
        pos = post.position[:jE + 1]
        inside = (pos[:, 0] > lo_x) & (pos[:, 0] < hi_x) & (pos[:, 1] < app.y_lo + 0.01)
        imp = contacts[:jE + 1][inside].sum(axis=0) / dt
        end_contacts = (float(imp[0]), float(imp[1]))
    return end_contacts


def _fountain_end(app: Apparatus, ten: np.ndarray, J: np.ndarray, jE: int,
                  j0: int) -> tuple[float, float, float]:
    """Tension (N) and position of the fountain end: joint ``jE``, or with a floor
    ``floor_depth`` below the end, interpolated between the joints on either side of
    ``y = -H``."""
    TE, end_x, end_y = float(ten[jE]), float(J[jE, 0]), float(J[jE, 1])
    if app.floor_depth > 0 and 0 < jE <= j0:
        # interpolate between the joints on either side of y = -H
        ya, yb = float(J[jE - 1, 1]), end_y
        w = (-app.H - ya) / (yb - ya) if yb > ya else 1.0
        TE = float(ten[jE - 1]) + w * (TE - float(ten[jE - 1]))
        end_x = float(J[jE - 1, 0]) + w * (end_x - float(J[jE - 1, 0]))
        end_y = -app.H
    return TE, end_x, end_y
