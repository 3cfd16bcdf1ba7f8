"""A run's window against the paper's apparatus relations and this model's rig laws:
:func:`report`, the ``apparatus`` object of ``summary.json``."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from chainfountain.sim.apparatus import (
    CART_GAIN_2CM,
    CART_GAIN_2CM_ERR,
    PICKUP_BAR,
    PICKUP_RIG_2CM_ERR,
    PUTDOWN_BAR,
    PUTDOWN_RIG_2CM,
    Apparatus,
    braked_fold_speed,
    gripped_putdown,
    pickup_rig_2cm,
    rig_exit_tension,
    selected_speed,
)
from chainfountain.sim.apparatus_report.sample import ApparatusSample
from chainfountain.sim.apparatus_report.step_change import step_section
from chainfountain.theory.design import MEASURED_CART_GAIN


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
    ``p`` = :data:`~chainfountain.sim.apparatus.PICKUP_BAR`, put-down ``d`` =
    :data:`~chainfountain.sim.apparatus.PUTDOWN_BAR`, cart gain ``G`` =
    :data:`~chainfountain.theory.design.MEASURED_CART_GAIN` (1/2, the loss-free power
    balance; the paper's is 1)::

        Tbar_0 = p + G*Tbar_uc + xi2*k*H,   Tbar_E = d + G*Tbar_lc - xi3*k*H,
        steady: Tbar_uc = Tbar_lc + (k*H*(1 - xi2 - xi3) + d - p)/G.

    ``measured.pickup_p`` is ``T_exit - G*Tbar_uc`` and ``measured.putdown_d``
    ``T_entry - G*Tbar_lc`` with that ``G``.

    The ``floor`` variant with ``end = "absorbing"`` has ``Tbar_E = 0``, so its
    speed follows from ``p + G*Tbar_uc + xi2*k*H = k*H``
    (:func:`~chainfountain.sim.apparatus.selected_speed`); with the floor
    ``floor_depth`` below the fountain end, ``Tbar_E = k*floor_depth`` and the
    right-hand side is ``k*(H + floor_depth)``. The speed is reported under
    ``speed_selection`` for the paper's ``p = 1/2`` (cart gain 1), the 10-mm rig's 0.27
    (cart gain 1/2) and the rig law for the presets' 2 cm links
    (:data:`~chainfountain.sim.apparatus.PICKUP_RIG_2CM`,
    :data:`~chainfountain.sim.apparatus.CART_GAIN_2CM`).
    """
    app: Apparatus = sim.apparatus
    w = _window(sim, rec, t0, t1)
    out: dict = {"variant": app.variant, "window": [float(w.t[0]), float(w.t[-1])],
                 "measured": _measured(app, w)}
    out["catenary"], out["paper_ranges"] = _catenary_and_ranges(app, w)
    out["flight"] = _flight(w, out["catenary"])
    out["flight"]["step"] = step_section(sim.config)
    paper, law = _predictions(app, w)
    if app.variant == "floor":
        out["speed_selection"] = _speed_selection(app, w, paper, law)
    if app.variant == "open":
        out["open"] = _open_run(app, w)
    if w.fold:
        out["fold"] = _fold_run(app, w)
    out["predicted_paper"] = paper
    out["predicted_measured_laws"] = law
    return out


@dataclass(frozen=True)
class _Window:
    """The window's samples and the figures every part of the report reads (tensions
    scaled by ``lambda*v**2``)."""

    S: list[ApparatusSample]
    t: np.ndarray
    lam: float
    g: float
    H: float
    xi2: float
    xi3: float
    fold: bool
    v: float
    """Mean chain speed in flight (m/s)."""
    slope: float
    """Its least-squares trend (m/s^2; nan with 2 samples or fewer)."""
    k: float
    kH: float
    uc: float
    lc: float
    T0: float
    TE: float
    T_up: float
    T_lo: float
    G10: float
    """Cart gain of the measured mechanism laws (:data:`MEASURED_CART_GAIN`)."""
    p_meas: float
    d_meas: float


def _mean(S: list[ApparatusSample], name: str) -> float:
    """Mean of a sample field over the window, nan where it is nan throughout."""
    vals = np.array([getattr(s, name) for s in S], dtype=float)
    return float(np.nanmean(vals)) if np.any(np.isfinite(vals)) else math.nan


SOKAL_C = 5.0
"""Sokal's window constant: the autocorrelation is summed out to the least lag ``M`` with
``M >= SOKAL_C * tau(M)`` (:func:`mean_se`)."""


def mean_se(x: np.ndarray) -> float:
    """Standard error of the mean of the evenly sampled series ``x`` (its finite values),
    correlated samples counted by their integrated autocorrelation time ``tau`` (in
    samples, summed out to Sokal's automatic window ``M``, :data:`SOKAL_C`):
    ``sd * sqrt(tau / N / (1 - (2M+1)/N))``, the last factor the bias the series' own
    mean puts into its autocorrelations. nan with fewer than 20 samples, or where the
    window is too short to tell (``2M+1`` above 60 % of ``N``: under about 6 ``tau``)."""
    x = np.asarray(x, dtype=float)
    x = x[np.isfinite(x)]
    n = len(x)
    if n < 20:
        return math.nan
    d = x - x.mean()
    var = float(np.dot(d, d) / n)
    if var == 0.0:
        return 0.0
    f = np.fft.rfft(d, 2 * n)
    acf = np.fft.irfft(f * np.conjugate(f))[:n] / (var * n)
    tau = 2.0 * np.cumsum(acf) - 1.0
    m = np.flatnonzero(np.arange(n) >= SOKAL_C * tau)
    if not len(m):
        return math.nan
    M = int(m[0])
    shrink = 1.0 - (2 * M + 1) / n
    if shrink < 0.4:
        return math.nan
    return math.sqrt(var * max(float(tau[M]), 1.0) / n / shrink)


def _flight(w: _Window, catenary: dict) -> dict:
    """``flight``: is what flies the paper's fountain? The window means of ``Tbar_0``,
    ``Tbar_E`` and of the paper's relation across a steady flight,
    ``Tbar_0 - Tbar_E = k (y_0 - y_E)`` (the tension less ``lambda v^2`` grows as
    ``lambda g y``; the ends' measured heights, the start at ``y = 0``), with the
    standard errors of their means (:func:`mean_se`), and the vertex against the
    catenary through the measured ends. The step's error is not in these bars: halving
    the step moves them by more (``flight.step``, :mod:`.step_change`)."""
    S = w.S
    T0 = np.array([s.T0_bar for s in S], dtype=float)
    TE = np.array([s.TE_bar for s in S], dtype=float)
    k = w.g / np.array([s.v for s in S], dtype=float) ** 2
    miss = T0 - TE - k * -np.array([s.end_y for s in S], dtype=float)
    return {
        "T0_bar": w.T0, "T0_bar_se": mean_se(T0),
        "TE_bar": w.TE, "TE_bar_se": mean_se(TE),
        "relation_miss": float(np.nanmean(miss)) if np.any(np.isfinite(miss)) else math.nan,
        "relation_miss_se": mean_se(miss),
        "kH": w.kH,
        "v_se": mean_se(np.array([s.v for s in S], dtype=float)),
        "vertex_y_rel_error": catenary["vertex_y_rel_error"],
        "how": "window means; _se: their standard errors, the samples' correlation "
               "counted (integrated autocorrelation time); relation_miss = Tbar_0 - "
               "Tbar_E - k (y_0 - y_E); not the step's error",
    }


def _window(sim, rec, t0: float, t1: float) -> _Window:
    """The samples in ``[t0, t1]`` and their means."""
    app: Apparatus = sim.apparatus
    S = [s for s in rec.apparatus_samples if t0 - 1e-9 <= s.t <= t1 + 1e-9]
    if not S:
        raise ValueError("no apparatus samples in the window")
    cfg = sim.config
    a = cfg.apparatus
    lam, g, H = cfg.chain.linear_density, cfg.gravity, a.drop
    t = np.array([s.t for s in S])
    v_series = np.array([s.v for s in S])
    v = float(np.mean(v_series))
    slope = float(np.polyfit(t, v_series, 1)[0]) if len(S) > 2 else math.nan
    k = g / v**2
    kH = k * H
    uc, lc = app.cart_bars(v, lam)
    T0, TE = _mean(S, "T0_bar"), _mean(S, "TE_bar")
    T_up, T_lo = _mean(S, "T_up_bar"), _mean(S, "T_lo_bar")
    G10 = MEASURED_CART_GAIN
    p_meas = T_up - G10 * uc
    d_meas = T_lo - G10 * lc if app.lower is not None else math.nan
    return _Window(S=S, t=t, lam=lam, g=g, H=H, xi2=a.xi2, xi3=a.xi3,
                   fold=app.variant == "fold", v=v, slope=slope, k=k, kH=kH, uc=uc, lc=lc,
                   T0=T0, TE=TE, T_up=T_up, T_lo=T_lo, G10=G10, p_meas=p_meas,
                   d_meas=d_meas)


def _measured(app: Apparatus, w: _Window) -> dict:
    """The ``measured`` object: the window's means."""
    S, v, fold = w.S, w.v, w.fold
    return {
        "v": v, "k": w.k, "kH": w.kH, "xi2": w.xi2, "xi3": w.xi3 if fold else None,
        "T0_bar": w.T0, "TE_bar": w.TE, "Tbar_uc": w.uc, "Tbar_lc": w.lc if fold else None,
        "T_pickup_exit_bar": w.T_up, "T_putdown_entry_bar": w.T_lo if fold else None,
        "pickup_p": w.p_meas, "putdown_d": w.d_meas if fold else None,
        "roller_ratio_up": _mean(S, "v_roller_up") / v,
        "roller_ratio_lo": _mean(S, "v_roller_lo") / v if app.lower is not None else None,
        "speed_drift_per_s": w.slope / v,
        "acceleration": w.slope,
        "vertex": [_mean(S, "vertex_x"), _mean(S, "vertex_y")],
        "end": [_mean(S, "end_x"), _mean(S, "end_y")],
        "cart_force_uc_N": app.upper.force,
        "cart_force_lc_N": app.lower.force if app.lower is not None else None,
        "end_channel_force_N": [_mean(S, "channel_force_x"), _mean(S, "channel_force_y")]
        if app.channel_lo is not None else None,
    }


def _catenary_and_ranges(app: Apparatus, w: _Window) -> tuple[dict, dict]:
    """The ``catenary`` object (the catenary through the measured ends, and the one
    ``k`` and ``Tbar_0`` give) and ``paper_ranges`` (the paper's bounds on ``Tbar_E``
    and ``Tbar_0``)."""
    k, T0, TE = w.k, w.T0, w.TE
    end = (_mean(w.S, "end_x"), _mean(w.S, "end_y"))
    vy = _mean(w.S, "vertex_y")
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
    catenary = {
        "q_through_ends": q_ends, "vertex_y_through_ends": h_ends,
        "vertex_y_rel_error": vy / h_ends - 1.0 if h_ends == h_ends else math.nan,
        "q_from_k_T0": q_forces, "vertex_y_from_k_T0": h_forces,
    }
    ranges = {
        "TE_bar": [0.0, 0.5], "TE_in_range": bool(0.0 - 0.02 <= TE < 0.5),
        "T0_bar": [T0_lo, T0_hi], "T0_in_range": bool(T0_lo <= T0 < T0_hi),
        "k_max": q_ends / (1.0 + q_ends * (vy + drop)),
    }
    return catenary, ranges


def _driving_drop(app: Apparatus, w: _Window) -> tuple[float, float]:
    """Height (m) that drives a free-ended run and its ``xi2``: to the floor ('floor';
    ``H + floor_depth``), to the guide's horizontal exit plus the end pull as an
    equivalent height ('open')."""
    H, d_fl = w.H, app.floor_depth
    return (H + d_fl, w.xi2 * H / (H + d_fl)) if app.variant == "floor" else \
        (app.y_up - app.y_lo + app.end_pull / (w.lam * w.g), 0.0)


def _predictions(app: Apparatus, w: _Window) -> tuple[dict, dict]:
    """The paper's predictions (``p = d = 1/2``, cart gain 1) and the measured
    mechanism laws' (``p``, ``d``, cart gain ``G10``): ``Tbar_0``, ``Tbar_E`` and the
    steady upper cart ('fold') or the speed a free-ended run selects."""
    uc, lc, kH, G10 = w.uc, w.lc, w.kH, w.G10
    xi2, xi3 = w.xi2, w.xi3
    paper = {"T0_bar": 0.5 + uc + xi2 * kH}
    law = {"T0_bar": PICKUP_BAR + G10 * uc + xi2 * kH, "cart_gain": G10}
    if w.fold:
        paper["TE_bar"] = 0.5 + lc - xi3 * kH
        law["TE_bar"] = PUTDOWN_BAR + G10 * lc - xi3 * kH
        paper["Tbar_uc_steady"] = lc + kH * (1.0 - xi2 - xi3)
        law["Tbar_uc_steady"] = lc + (kH * (1.0 - xi2 - xi3) + PUTDOWN_BAR - PICKUP_BAR) / G10
        law["Tbar_uc_steady_with_measured_p_d"] = \
            lc + (kH * (1.0 - xi2 - xi3) + w.d_meas - w.p_meas) / G10
        if app.cfg.fold_brake > 0.0:  # the brake selects the speed
            paper["v_steady"] = braked_fold_speed(app.sim_cfg)
        return paper, law
    # a floor d below the fountain end: the hanging strand's weight, Tbar_E = k*d
    d_fl = app.floor_depth
    paper["TE_bar"] = law["TE_bar"] = w.k * d_fl if app.variant == "floor" else None
    F_uc, c = app.upper.force, app.cfg.bearing_drag
    H_d, xi_d = _driving_drop(app, w)
    g, lam = w.g, w.lam
    for dct, pp, gg in ((paper, 0.5, 1.0), (law, PICKUP_BAR, G10)):
        vs = selected_speed(g, H_d, xi_d, F_uc, lam, pp, gain=gg, drag=c)
        dct["v_steady"] = vs
        dct["k_steady"] = g / vs**2 if vs == vs else math.nan
    return paper, law


def _speed_selection(app: Apparatus, w: _Window, paper: dict, law: dict) -> dict:
    """'floor': the measured speed against the speed the paper, the 10-mm rig's law and
    the 2 cm rig law select (with the rig law's standard uncertainty)."""
    g, lam, v, d_fl = w.g, w.lam, w.v, app.floor_depth
    F_uc, c = app.upper.force, app.cfg.bearing_drag
    H_d, xi_d = _driving_drop(app, w)
    G, dG, dp = CART_GAIN_2CM, CART_GAIN_2CM_ERR, PICKUP_RIG_2CM_ERR
    v_rig = selected_speed(g, H_d, xi_d, F_uc, lam, gain=G, drag=c)
    # standard uncertainty of v_rig from those of p and G (added in quadrature)
    sv_p = abs(selected_speed(g, H_d, xi_d, F_uc, lam, gain=G, dp=dp, drag=c) - v_rig)
    sv_g = abs(selected_speed(g, H_d, xi_d, F_uc, lam, gain=G + dG, drag=c) - v_rig)
    sigma = math.hypot(sv_p, sv_g)
    return {
        "end": app.end_mode, "floor_depth_m": d_fl,
        "v_measured": v,
        "v_paper_p_half": paper["v_steady"],
        "v_p_0.27_gain_0.5": law["v_steady"],
        "v_rig_2cm": v_rig, "p_rig_2cm": pickup_rig_2cm(v_rig), "gain_rig_2cm": G,
        "v_rig_2cm_sigma": sigma,
        "rel_error_rig_2cm": v / v_rig - 1.0 if v_rig == v_rig else math.nan,
        "rel_error_paper": v / paper["v_steady"] - 1.0
        if paper["v_steady"] == paper["v_steady"] else math.nan,
        "p_from_balance": w.T0 - w.xi2 * w.kH - G * w.uc,
        "formula": "v^2 = (g*(H + floor_depth - xi2*H) - G*F_uc/lambda)/p; rig: "
                   "p = p_inf + R/(lambda v^2), R the roller's rolling resistance",
    }


def _open_run(app: Apparatus, w: _Window) -> dict:
    """'open', non-stationary: ``M(t) dv/dt = lambda*g*(y_up - y_lo) + F_pull -
    T_exit(v)``, the moving mass growing at ``lambda*v/2``; the mouth tension is the
    weight hanging in the turn."""
    lam, g, v, t = w.lam, w.g, w.v, w.t
    drop = app.guide_radius * (1.0 - math.cos(app.alphaE)) if app.guided else math.nan
    M = app.moving_mass(0.5)
    drive = app.open_drive
    T_ex = w.T_up * lam * v * v
    G = CART_GAIN_2CM
    c = app.cfg.bearing_drag  # acts on the pick-up's carriage like more cart, c*v/2
    T_rig = rig_exit_tension(v, lam, app.upper.force + 0.5 * c * v)
    R = np.array([s.tail_reaction for s in w.S], dtype=float)
    ok = np.isfinite(R)
    # imported here: scipy.stats takes 0.5-1.3 s to import, and the module is loaded at
    # a running simulation's first sample (the window would stall on it)
    from scipy.stats import theilslopes

    return {
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
                                         0.0, app.upper.force, lam, gain=G, drag=c),
        "formula": "M(t) dv/dt = lambda g (y_up - y_lo) + F_pull - T_exit(v), "
                   "dM/dt = lambda v/2; tail reaction d/dt = lambda g v "
                   "(rate: Theil-Sen slope)",
    }


def _fold_run(app: Apparatus, w: _Window) -> dict:
    """'fold': the whole moving chain (upper roller exit to folding roller entry) on its
    fixed frictionless path, ``M dv/dt = lambda g H (1 - xi2 - xi3) + T_in - T_exit``,
    with the 2 cm rig laws at both rollers (the gripped folding roller's own law,
    :func:`~chainfountain.sim.apparatus.laws.gripped_putdown`, at its entry)."""
    lam, g, v, H, xi2, xi3 = w.lam, w.g, w.v, w.H, w.xi2, w.xi3
    uc, lc, kH = w.uc, w.lc, w.kH
    d_r, G_d = PUTDOWN_RIG_2CM
    if app.gripped:
        d_r, G_d = gripped_putdown(0.0, g / (v * v), app.R_lo), 0.5
    G = CART_GAIN_2CM
    T_in = (d_r + G_d * lc) * lam * v * v
    T_ex = (pickup_rig_2cm(v) + G * uc) * lam * v * v
    drive = lam * g * H * (1.0 - xi2 - xi3)
    M = app.moving_mass(0.5)
    return {
        "T_putdown_entry_rig_bar": d_r + G_d * lc,
        "T_pickup_exit_rig_bar": pickup_rig_2cm(v) + G * uc,
        "TE_bar_rig": d_r + G_d * lc - xi3 * kH,
        "T0_bar_rig": pickup_rig_2cm(v) + G * uc + xi2 * kH,
        "TE_bar_from_measured_entry": w.T_lo - xi3 * kH,
        "moving_mass_kg": M,
        "acceleration_predicted_rig": (drive + T_in - T_ex) / M,
        "released_links": app.released,
        "formula": "M dv/dt = lambda g H (1 - xi2 - xi3) + T_in - T_exit, "
                   + ("T_in = (1/4 + k R + Tbar_lc/2) lambda v^2 (gripped), " if app.gripped
                      else "T_in = (d + G_d Tbar_lc) lambda v^2, ")
                   + "T_exit = (p(v) + G Tbar_uc) lambda v^2",
    }
