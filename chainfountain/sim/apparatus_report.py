"""Measuring a running pulley apparatus (:mod:`chainfountain.sim.apparatus`).

:func:`analyse` turns one recorded step into tensions along the path (the exact
momentum balance of :mod:`chainfountain.sim.measure`, with the guide joints'
impulses reconstructed), speeds and the fountain's shape; :func:`report` compares
a run's window with the paper's apparatus relations and this model's rig laws
(the ``apparatus`` object of ``summary.json``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.stats import theilslopes

from chainfountain.sim.apparatus import (
    CART_GAIN_2CM,
    CART_GAIN_2CM_ERR,
    PICKUP_BAR,
    PICKUP_RIG_2CM_ERR,
    PUTDOWN_BAR,
    PUTDOWN_RIG_2CM,
    Apparatus,
    pickup_rig_2cm,
    rig_exit_tension,
    selected_speed,
)
from chainfountain.theory.design import MEASURED_CART_GAIN


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


def _guided_impulses(app: Apparatus, pre_vel: np.ndarray, post, dt: float,
                     k: int, start: tuple[int, float]) -> np.ndarray:
    """'fold': 'contact' impulses for the first ``k`` links, which the lower guide joints
    hold (their impulses are not among the contacts), such that the momentum balance
    summed from the end gives, at joint ``k-1``, the tension of the guided chain.

    The guide forces are normal to the path (frictionless grooves, slide joints to
    the turns' centres), so each guided link's balance along its own axis ``u_i``
    gives the tension recursively (shear neglected):
    ``T_i (e_i.u_i) = T_{i-1} (e_{i-1}.u_i) - m (dv_i/dt + g y).u_i`` with ``e_j`` the
    joint direction as in ``signed_tension``, starting from a known tension
    ``start = (i, T_i)`` at joint ``i`` (on the lower plate, from the horizontal joint
    force). The returned rows make the summed force at joint ``k-1`` equal
    ``-T_{k-1} e_{k-1}``. (:func:`_pivot_offset` corrects what the neglected shear
    misses; 'open' is read exactly, :func:`_open_guide_impulses`.)
    """
    m, g = app.chain.mass, app.g
    ang = post.angle
    u = np.column_stack((np.cos(ang), np.sin(ang)))
    n = len(ang)
    kk = min(k, n - 1)
    e = u[:kk] + u[1:kk + 1]
    e /= np.linalg.norm(e, axis=1)[:, None]
    acc = (post.velocity[:kk] - pre_vel[:kk]) / dt
    acc[:, 1] += g
    i_first, T = start[0] + 1, start[1]
    # the recursion in plain floats: numpy's per-call cost on 2-vectors made this loop
    # 40 % of a sample's analysis (0.4 ms at 30 guided links)
    ul, el, al = u[:kk].tolist(), e.tolist(), acc.tolist()
    epx, epy = el[start[0]]
    for i in range(i_first, kk):
        ux, uy = ul[i]
        ax, ay = al[i]
        rhs = T * (epx * ux + epy * uy) - m * (ax * ux + ay * uy)
        ex, ey = el[i]
        T = rhs / (ex * ux + ey * uy)
        epx, epy = ex, ey
    raw = m * (post.velocity[:k] - pre_vel[:k])
    raw[:, 1] += m * g * dt
    target = np.zeros((k, 2))
    if kk:
        target[kk - 1] = -T * e[kk - 1] * dt
    return raw - target


def _open_guide_impulses(app: Apparatus, pre_vel: np.ndarray, pre_w: np.ndarray, post,
                         dt: float, lower: tuple[int, int, float, float]
                         ) -> tuple[np.ndarray, float]:
    """'open' with the joint turn: the external impulses on the first ``k`` links (the
    tail's grooves, the turn's slide joints), exactly, as 'contact' rows for
    :func:`~chainfountain.sim.measure.joint_forces`.

    ``lower = (n_tail, n_turn, m_end, I_end)`` is the guide's state at the step (links
    ``0 .. n_tail-1`` in the lower plate's grooves, the next ``n_turn`` on the turn; the
    end link's mass and moment with the lumped tail). The energy budget's impulse sweep
    (:func:`chainfountain.sim.budget.sweep`) gives each joint's impulse along its known
    normal from the links' momentum and angular momentum changes, so nothing is
    neglected (the 'fold' guide's reconstruction, :func:`_guided_impulses`, takes the
    guide forces normal to each link's axis and neglects the shear). Each row also
    carries what ``joint_forces`` does not know: the end pull and the lumped mass beyond
    one link's on the end link. Also returns the grooves' summed impulse on the tail (N
    s, upward)."""
    from chainfountain.sim.budget import lower_kinds, sweep

    n_tail, n_turn, m_end, I_end = lower
    k = min(n_tail + n_turn, len(post.angle))
    kinds = lower_kinds(app, n_tail, n_turn)[:k]
    m, g = app.chain.mass, app.g
    mass = np.full(k, m)
    moment = np.full(k, app.chain.moment)
    mass[0], moment[0] = m_end, I_end
    dv = post.velocity[:k] - pre_vel[:k]
    dv[:, 1] += g * dt  # momentum change and weight, per unit mass
    dp = mass[:, None] * dv
    dp[0, 0] -= app.end_pull * dt
    _, gn, nrm, _ = sweep(kinds, post.position[:k], post.angle[:k], dp,
                          moment * (post.angular_velocity[:k] - pre_w[:k]), 0.5 * app.L)
    rows = gn[:, None] * nrm  # the guides' impulses
    rows[0] += np.array([app.end_pull * dt, 0.0]) - (m_end - m) * dv[0]
    return rows, float(np.sum(gn[:n_tail] * nrm[:n_tail, 1]))


def _pivot_offset(F: np.ndarray, pivots: np.ndarray, free: np.ndarray) -> np.ndarray | None:
    """'fold': the constant force ``c`` that the lower guide's reconstruction
    (:func:`_guided_impulses`) misses, from the free flight's pivot joints.

    Summed from the downstream end, the joint forces of the free links are exact up
    to one constant vector: the error of the guide's reconstruction (its guide forces
    taken normal to each link's axis, shear neglected), which reaches every joint
    upstream of the mouth. The solver's own pivot impulses give each joint force's
    size, ``|F_j + c| = |J_j|/dt``; ``c`` is their least-squares fit (Gauss-Newton from
    0). Measured on ``apparatus_special`` over 1-4 s (docs/apparatus.md): the fit's rms
    residual is 1e-4 ``lambda v^2`` (the flight's joint forces are exact up to ``c``),
    ``|c|`` 0.05 ``lambda v^2`` in the median, and ``Tbar_0 - Tbar_E`` then equals ``k``
    times the height between the two joints within 0.01 with either upper guide. None if
    the fit does not hold (fewer than 5 free joints, or an rms residual above 2 % of the
    mean pivot force)."""
    if len(free) < 5:
        return None
    Ff, P = F[free], pivots[free]
    if not np.all(np.isfinite(P)):
        return None
    c = np.zeros(2)
    for _ in range(4):
        G = Ff + c
        Gn = np.linalg.norm(G, axis=1)
        if np.any(Gn == 0.0):
            return None
        c = c + np.linalg.lstsq(G / Gn[:, None], P - Gn, rcond=None)[0]
    rms = float(np.sqrt(np.mean((np.linalg.norm(Ff + c, axis=1) - P) ** 2)))
    return c if rms <= 0.02 * float(np.mean(P)) else None


def analyse(app: Apparatus, t: float, pre_vel: np.ndarray, post, contacts: np.ndarray,
            dt: float, lam: float,
            roller: tuple[float, float, float, float],
            pivots: np.ndarray | None = None, pre_w: np.ndarray | None = None,
            lower: tuple[int, int, float, float] | None = None
            ) -> tuple[ApparatusSample, dict]:
    """Measure one sampled step: signed tension from the exact momentum balance summed
    from the downstream end (:func:`chainfountain.sim.measure.joint_forces`, all contact
    impulses of floor, channels, plates, rollers and tables subtracted), located on
    the path. Returns the sample and per-joint profiles of the free flight.

    ``pivots`` ('fold'): the size of every chain joint's force in this step from the
    solver's pivot impulses (N). They correct the lower guide's reconstruction by
    :func:`_pivot_offset`. ``pre_w`` and ``lower`` ('open' with the joint turn): the
    links' angular velocities before the step and the lower guide's state
    (:func:`_open_guide_impulses`)."""
    from chainfountain.sim.measure import ChainState, joint_forces, signed_tension, vertex_of

    chain = app.chain
    n = len(post.angle)
    pre = ChainState(position=post.position, angle=post.angle, velocity=pre_vel,
                     angular_velocity=post.angular_velocity)
    k = min(lower[0] + lower[1], n) if lower is not None else 0
    T_lo_fold = tail_reaction = math.nan
    if app.fold_guided:
        # tension on the lower plate from the horizontal joint force (grooves add none),
        # then along the guided links' axes up to the mouth
        ip, k = app.fold_guided_range(post.position, roller[2])
        if ip >= 2 and k > ip + 1:
            F1 = joint_forces(pre, post, chain.mass, dt, app.g, n - 1, contacts)
            T_lo_fold = float(-np.mean(F1[ip - 2:ip + 3, 0]))
            contacts = contacts.copy()
            contacts[:k] = _guided_impulses(app, pre_vel, post, dt, k,
                                            start=(ip, float(-F1[ip, 0])))
        else:
            k = 0
    elif app.end_pull or k:
        contacts = contacts.copy()
        if k:
            contacts[:k], tail_imp = _open_guide_impulses(app, pre_vel, pre_w, post, dt,
                                                          lower)
            tail_reaction = tail_imp / dt
        else:  # external force on the end link, like a contact
            contacts[0, 0] += app.end_pull * dt
    F = joint_forces(pre, post, chain.mass, dt, app.g, n - 1, contacts)
    L = app.L
    u = np.column_stack((np.cos(post.angle), np.sin(post.angle)))
    back = post.position - 0.5 * L * u
    front = post.position + 0.5 * L * u
    J = 0.5 * (back[:-1] + front[1:])  # joint j between link j and j+1
    gaps = np.linalg.norm(back[:-1] - front[1:], axis=1)
    d0 = np.hypot(J[:, 0], J[:, 1])
    j0 = int(np.argmin(d0))
    if app.fold_guided and k > 0 and pivots is not None:
        c = _pivot_offset(F, pivots, np.arange(k + 3, j0 - 1))
        if c is not None:
            F[k - 1:] += c  # the reconstruction reaches the joints from the mouth up
    ten, _ = signed_tension(F, post, n - 1)
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
        # the grooves' vertical impulses are not in ``contacts``: on the horizontal
        # plate the tension is the horizontal joint force alone (grooves add none)
        k = int(np.argmin(np.hypot(J[:, 0] - xu - 6 * L, J[:, 1] - app.y_up)))
        Fu = F
        if app.upper_guided:
            # the upper guide's joint impulses are not among the contacts either (and
            # have horizontal parts on its bend and straight): sum from the upstream
            # end instead, the resting chain, whose table and roller contacts are all
            # recorded (F_j = -(momentum change of the links beyond joint j) / dt: the
            # sum over all links less the sum up to j)
            Fall = joint_forces(pre, post, chain.mass, dt, app.g, n, contacts)
            Fu = Fall[:-1] - Fall[-1]
        # (not the pivot forces: the grooves and the pivots over-constrain the straight
        # strand, and the pivots carry an alternating vertical part that adds about
        # 0.008 lambda v^2; the contacts are read with their stale impulses taken out,
        # docs/apparatus.md)
        T_up = float(np.mean(-Fu[max(k - 2, 0):min(k + 3, len(Fu)), 0])) / scale
    else:
        T_up = at(xu + 6 * L, app.y_up)
    if app.fold_guided:
        T_lo = T_lo_fold / scale
    else:
        T_lo = at(xl - 6 * L, app.y_lo) if app.lower is not None else math.nan
    flight = J[jE:j0 + 1]
    xv, yv = vertex_of(flight[::-1]) if len(flight) > 2 else (math.nan, math.nan)
    uc, lc = app.cart_bars(v, lam)
    end_contacts = (math.nan, math.nan)
    if app.channel_lo is not None and jE > 0:
        lo_x, hi_x = app.channel_lo[:, 0].min() - 0.01, app.channel_lo[:, 0].max()
        pos = post.position[:jE + 1]
        inside = (pos[:, 0] > lo_x) & (pos[:, 0] < hi_x) & (pos[:, 1] < app.y_lo + 0.01)
        imp = contacts[:jE + 1][inside].sum(axis=0) / dt
        end_contacts = (float(imp[0]), float(imp[1]))
    TE, end_x, end_y = float(ten[jE]), float(J[jE, 0]), float(J[jE, 1])
    if app.floor_depth > 0 and 0 < jE <= j0:
        # interpolate between the joints on either side of y = -H
        ya, yb = float(J[jE - 1, 1]), end_y
        w = (-app.H - ya) / (yb - ya) if yb > ya else 1.0
        TE = float(ten[jE - 1]) + w * (TE - float(ten[jE - 1]))
        end_x = float(J[jE - 1, 0]) + w * (end_x - float(J[jE - 1, 0]))
        end_y = -app.H
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


# ----------------------------------------------------------------------------- report
def catenary_through(alpha0: float, end: tuple[float, float]) -> float:
    """``q`` of the inverted catenary leaving (0, 0) at ``alpha0`` through ``end``
    (paper Eq. func_graph in the launch frame); nan if none."""
    from scipy.optimize import brentq

    ex, ey = end
    c0 = math.cos(alpha0)

    def miss(lq: float) -> float:
        q = math.exp(lq)
        h = (1.0 / c0 - 1.0) / q
        xr = math.acosh(1.0 + q * h) / q
        z = min(abs(q * (ex - xr)), 700.0)
        return h + (1.0 - math.cosh(z)) / q - ey

    try:
        return math.exp(brentq(miss, math.log(1e-3), math.log(1e3)))
    except ValueError:
        return math.nan


def report(sim, rec, t0: float, t1: float) -> dict:
    """Measured and predicted quantities of an apparatus run over ``[t0, t1]``.

    Tensions are scaled by ``lambda*v**2`` with the measured speed. Paper
    ("Generating Steady-State Chain Fountains"), rollers ``p = d = 1/2``::

        Tbar_0 = 1/2 + Tbar_uc + xi2*k*H,   Tbar_E = 1/2 + Tbar_lc - xi3*k*H,
        steady: Tbar_uc = Tbar_lc + k*H*(1 - xi2 - xi3).

    Measured mechanism laws (``docs/apparatus.md``, alpha = 0, 10-mm rig): pick-up
    ``p`` = :data:`PICKUP_BAR`, put-down ``d`` = :data:`PUTDOWN_BAR`, cart gain
    ``G`` = :data:`~chainfountain.theory.design.MEASURED_CART_GAIN` (1/2, the loss-free
    power balance; the paper's is 1)::

        Tbar_0 = p + G*Tbar_uc + xi2*k*H,   Tbar_E = d + G*Tbar_lc - xi3*k*H,
        steady: Tbar_uc = Tbar_lc + (k*H*(1 - xi2 - xi3) + d - p)/G.

    ``measured.pickup_p`` is ``T_exit - G*Tbar_uc`` and ``measured.putdown_d``
    ``T_entry - G*Tbar_lc`` with that ``G``.

    The ``floor`` variant with ``end = "absorbing"`` has ``Tbar_E = 0``, so its
    speed follows from ``p + G*Tbar_uc + xi2*k*H = k*H`` (:func:`selected_speed`); with
    the floor ``floor_depth`` below the fountain end, ``Tbar_E = k*floor_depth``
    and the right-hand side is ``k*(H + floor_depth)``. The speed is reported under
    ``speed_selection`` for the paper's ``p = 1/2`` (cart gain 1), the 10-mm rig's 0.27
    (cart gain 1/2) and the rig law for the presets' 2 cm links
    (:data:`PICKUP_RIG_2CM`, :data:`CART_GAIN_2CM`).
    """
    app: Apparatus = sim.apparatus
    S = [s for s in rec.apparatus_samples if t0 - 1e-9 <= s.t <= t1 + 1e-9]
    if not S:
        raise ValueError("no apparatus samples in the window")
    cfg = sim.config
    a = cfg.apparatus
    lam, g, H = cfg.chain.linear_density, cfg.gravity, a.drop

    def mean(name: str) -> float:
        vals = np.array([getattr(s, name) for s in S], dtype=float)
        return float(np.nanmean(vals)) if np.any(np.isfinite(vals)) else math.nan

    t = np.array([s.t for s in S])
    v_series = np.array([s.v for s in S])
    v = float(np.mean(v_series))
    slope = float(np.polyfit(t, v_series, 1)[0]) if len(S) > 2 else math.nan
    k = g / v**2
    kH = k * H
    uc, lc = app.cart_bars(v, lam)
    T0, TE = mean("T0_bar"), mean("TE_bar")
    T_up, T_lo = mean("T_up_bar"), mean("T_lo_bar")
    G10 = MEASURED_CART_GAIN
    p_meas = T_up - G10 * uc
    d_meas = T_lo - G10 * lc if app.lower is not None else math.nan
    xi2, xi3 = a.xi2, a.xi3
    fold = app.variant == "fold"
    end = (mean("end_x"), mean("end_y"))
    vx, vy = mean("vertex_x"), mean("vertex_y")
    q_ends = catenary_through(app.alpha0, end)
    h_ends = (1.0 / math.cos(app.alpha0) - 1.0) / q_ends if q_ends == q_ends else math.nan
    q_forces = k / (math.cos(app.alpha0) * (1.0 - T0)) if T0 < 1 else math.nan
    h_forces = (1.0 / math.cos(app.alpha0) - 1.0) / q_forces if q_forces == q_forces \
        else math.nan
    drop = -end[1]  # measured fountain drop (end height below the start)
    xi = vy / drop if drop > 0 else math.nan
    qH = q_ends * drop
    T0_lo = qH / (1.0 + qH * (1.0 + xi))
    T0_hi = 1.0 - k / q_ends
    out: dict = {
        "variant": app.variant,
        "window": [float(t[0]), float(t[-1])],
        "measured": {
            "v": v, "k": k, "kH": kH, "xi2": xi2, "xi3": xi3 if fold else None,
            "T0_bar": T0, "TE_bar": TE, "Tbar_uc": uc, "Tbar_lc": lc if fold else None,
            "T_pickup_exit_bar": T_up, "T_putdown_entry_bar": T_lo if fold else None,
            "pickup_p": p_meas, "putdown_d": d_meas if fold else None,
            "roller_ratio_up": mean("v_roller_up") / v,
            "roller_ratio_lo": mean("v_roller_lo") / v if app.lower is not None else None,
            "speed_drift_per_s": slope / v,
            "acceleration": slope,
            "vertex": [vx, vy], "end": list(end),
            "cart_force_uc_N": app.upper.force,
            "cart_force_lc_N": app.lower.force if app.lower is not None else None,
            "end_channel_force_N": [mean("channel_force_x"), mean("channel_force_y")]
            if app.channel_lo is not None else None,
        },
        "catenary": {
            "q_through_ends": q_ends, "vertex_y_through_ends": h_ends,
            "vertex_y_rel_error": vy / h_ends - 1.0 if h_ends == h_ends else math.nan,
            "q_from_k_T0": q_forces, "vertex_y_from_k_T0": h_forces,
        },
        "paper_ranges": {
            "TE_bar": [0.0, 0.5], "TE_in_range": bool(0.0 - 0.02 <= TE < 0.5),
            "T0_bar": [T0_lo, T0_hi], "T0_in_range": bool(T0_lo <= T0 < T0_hi),
            "k_max": q_ends / (1.0 + q_ends * (vy + drop)),
        },
    }
    paper = {"T0_bar": 0.5 + uc + xi2 * kH}
    law = {"T0_bar": PICKUP_BAR + G10 * uc + xi2 * kH, "cart_gain": G10}
    if fold:
        paper["TE_bar"] = 0.5 + lc - xi3 * kH
        law["TE_bar"] = PUTDOWN_BAR + G10 * lc - xi3 * kH
        paper["Tbar_uc_steady"] = lc + kH * (1.0 - xi2 - xi3)
        law["Tbar_uc_steady"] = lc + (kH * (1.0 - xi2 - xi3) + PUTDOWN_BAR - PICKUP_BAR) / G10
        law["Tbar_uc_steady_with_measured_p_d"] = \
            lc + (kH * (1.0 - xi2 - xi3) + d_meas - p_meas) / G10
    else:
        # a floor d below the fountain end: the hanging strand's weight, Tbar_E = k*d
        d_fl = app.floor_depth
        paper["TE_bar"] = law["TE_bar"] = k * d_fl if app.variant == "floor" else None
        F_uc = app.upper.force
        # driving drop: to the floor ('floor'; H + d), to the guide's horizontal exit plus
        # the end pull as an equivalent height ('open')
        H_d, xi_d = (H + d_fl, xi2 * H / (H + d_fl)) if app.variant == "floor" else \
            (app.y_up - app.y_lo + app.end_pull / (lam * g), 0.0)
        for dct, pp, gg in ((paper, 0.5, 1.0), (law, PICKUP_BAR, G10)):
            vs = selected_speed(g, H_d, xi_d, F_uc, lam, pp, gain=gg)
            dct["v_steady"] = vs
            dct["k_steady"] = g / vs**2 if vs == vs else math.nan
        if app.variant == "floor":
            G, dG, dp = CART_GAIN_2CM, CART_GAIN_2CM_ERR, PICKUP_RIG_2CM_ERR
            v_rig = selected_speed(g, H_d, xi_d, F_uc, lam, gain=G)
            # standard uncertainty of v_rig from those of p and G (added in quadrature)
            sv_p = abs(selected_speed(g, H_d, xi_d, F_uc, lam, gain=G, dp=dp) - v_rig)
            sv_g = abs(selected_speed(g, H_d, xi_d, F_uc, lam, gain=G + dG) - v_rig)
            sigma = math.hypot(sv_p, sv_g)
            out["speed_selection"] = {
                "end": app.end_mode, "floor_depth_m": d_fl,
                "v_measured": v,
                "v_paper_p_half": paper["v_steady"],
                "v_p_0.27_gain_0.5": law["v_steady"],
                "v_rig_2cm": v_rig, "p_rig_2cm": pickup_rig_2cm(v_rig), "gain_rig_2cm": G,
                "v_rig_2cm_sigma": sigma,
                "rel_error_rig_2cm": v / v_rig - 1.0 if v_rig == v_rig else math.nan,
                "rel_error_paper": v / paper["v_steady"] - 1.0
                if paper["v_steady"] == paper["v_steady"] else math.nan,
                "p_from_balance": T0 - xi2 * kH - G * uc,
                "formula": "v^2 = (g*(H + floor_depth - xi2*H) - G*F_uc/lambda)/p; rig: "
                           "p = p_inf + R/(lambda v^2), R the roller's rolling resistance",
            }
    if app.variant == "open":
        # non-stationary: M(t) dv/dt = lambda*g*(y_up - y_lo) + F_pull - T_exit(v), the
        # moving mass growing at lambda*v/2; mouth tension = weight hanging in the turn
        drop = app.guide_radius * (1.0 - math.cos(app.alphaE)) if app.guided else math.nan
        M = app.moving_mass(0.5)
        drive = app.open_drive
        T_ex = T_up * lam * v * v
        G = CART_GAIN_2CM
        T_rig = rig_exit_tension(v, lam, app.upper.force)
        R = np.array([s.tail_reaction for s in S], dtype=float)
        ok = np.isfinite(R)
        out["open"] = {
            "tail_reaction_N": [float(R[ok][0]), float(R[ok][-1])] if ok.any() else None,
            # median of the pairwise slopes (Theil-Sen): a landing that strikes the
            # turn off its circle gives single-sample impulse spikes of +-2 N, which a
            # least-squares line follows (over 1.7-2.2 s: 0.02 N/s, Theil-Sen 1.22)
            "tail_reaction_rate_N_per_s": float(theilslopes(R[ok], t[ok])[0])
            if ok.sum() > 2 else math.nan,
            "tail_reaction_rate_lsq_N_per_s": float(np.polyfit(t[ok], R[ok], 1)[0])
            if ok.sum() > 2 else math.nan,
            "tail_reaction_rate_predicted": lam * g * v,
            "TE_bar_predicted": (lam * g * drop + app.end_pull) / (lam * v * v),
            "drive_N": drive, "exit_tension_N": T_ex, "exit_tension_rig_N": T_rig,
            "moving_mass_kg_end": M, "moving_mass_rate_predicted": 0.5 * lam * v,
            "acceleration_predicted_measured_exit": (drive - T_ex) / M,
            "acceleration_predicted_rig": (drive - T_rig) / M,
            "v_selected_rig": selected_speed(g, app.y_up - app.y_lo + app.end_pull / (lam * g),
                                             0.0, app.upper.force, lam, gain=G),
            "formula": "M(t) dv/dt = lambda g (y_up - y_lo) + F_pull - T_exit(v), "
                       "dM/dt = lambda v/2; tail reaction d/dt = lambda g v "
                       "(rate: Theil-Sen slope)",
        }
    if fold:
        # whole moving chain (upper roller exit to folding roller entry) on its fixed
        # frictionless path: M dv/dt = lambda g H (1 - xi2 - xi3) + T_in - T_exit
        d_r, G_d = PUTDOWN_RIG_2CM
        G = CART_GAIN_2CM
        T_in = (d_r + G_d * lc) * lam * v * v
        T_ex = (pickup_rig_2cm(v) + G * uc) * lam * v * v
        drive = lam * g * H * (1.0 - xi2 - xi3)
        M = app.moving_mass(0.5)
        out["fold"] = {
            "T_putdown_entry_rig_bar": d_r + G_d * lc,
            "T_pickup_exit_rig_bar": pickup_rig_2cm(v) + G * uc,
            "TE_bar_rig": d_r + G_d * lc - xi3 * kH,
            "T0_bar_rig": pickup_rig_2cm(v) + G * uc + xi2 * kH,
            "TE_bar_from_measured_entry": T_lo - xi3 * kH,
            "moving_mass_kg": M,
            "acceleration_predicted_rig": (drive + T_in - T_ex) / M,
            "released_links": app.released,
            "formula": "M dv/dt = lambda g H (1 - xi2 - xi3) + T_in - T_exit, "
                       "T_in = (d + G_d Tbar_lc) lambda v^2, "
                       "T_exit = (p(v) + G Tbar_uc) lambda v^2",
        }
    out["predicted_paper"] = paper
    out["predicted_measured_laws"] = law
    return out
