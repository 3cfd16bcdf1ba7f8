"""When a fed stiff fountain is steady, over a grid of joint stiffness ``c`` and damping
``d``, and the mechanism of its unsteadiness measured (issue 62, item 6;
``docs/stiff_stability.md``).

Each run is a fountain of :mod:`research.stiff_runs` (its base link and step, the
substeps chosen there for the spring and the damper), started on the catenary and run
``--duration`` seconds, sampled every ``--sample`` seconds. From the vertex height after
``--skip`` seconds:

- ``sigma``: the growth rate (1/s) of its oscillation: a least-squares line through
  ``ln rms`` of the vertex about its linear trend in consecutive 1-s windows;
- ``period``: the oscillation's dominant period (s), from the spectrum of the last half;
- ``amp_last``: the last 1-s window's vertex rms over the mean height;
- the class: ``steady`` (the last ``--window`` seconds' vertex std and half-to-half drift
  both at most 0.3 % of the height), ``cycling`` (the vertex's peak-to-peak over the
  last half more than 10 % of its height: large climbs and collapses), ``growing``
  (``sigma > 0.1 /s``), else ``unsteady``.

The mechanism, over the last ``--window`` seconds, from the chain's shape at each
sample (the recorder's profiles: joint ``i`` from the guide sits at arc length
``s = i L``, a fixed place on the curve the chain runs through):

- ``w(s, t)``: the normal displacement of the chain from its mean curve (the window's
  mean joint positions), at the arc positions ``--at`` (fractions of the flight), and its
  rms there;
- ``lags``: the cross-correlation lag of ``w`` between consecutive positions (within
  half a period), and the speed ``ds/lag`` it gives (positive: downstream, with the
  chain; negative: upstream);
- ``spectrum``: the 2-D spectrum of ``w(s, t)`` over the flight: the share of its power
  in waves running upstream, the dominant frequency and wavenumber, their phase speed,
  and the phase speed the stiff string's dispersion relation gives at that wavenumber
  (``(omega - v k)^2 (1 + k^2 L^2/12) = v^2 k^2 (Tbar + e_B k^2)``, ``e_B = c L/(lambda
  v^2)``, ``Tbar`` the mean over the flight; the upstream branch; its ``omega = 0`` wave
  is the BVP's standing one, of wavelength ``2 pi sqrt(e/(1 - Tbar))``, and shorter waves
  run upstream), and ``attenuation``: ``delta (1 - Tbar) S/(2 e^2)``, the decay
  exponent over the flight ``S`` of the standing-wavelength waves by the damper (the
  stiff BVP's rate; ``delta`` from ``d`` plus ``solver.wave_damping``'s damper);
- ``bending``: the same over the bending band (wavelengths 0.5-2 times the standing
  one), with the string's group speeds there and the measured ``envelope_speed``: the
  speed at which the band's amplitude travels from 30 % to 70 % of the flight (the
  group speed, the way energy goes, where one branch carries the band);
- ``guide``/``floor``: over the first/last ``--guide-part`` of the flight, the bending
  band's power with downstream phase over that with upstream phase at its dominant
  frequency.

Each is taken over two windows: ``early`` (``--skip`` to ``--skip + --window``, while the
oscillation is small) and ``late`` (the last ``--window`` seconds).

Usage::

    python -m research.stiff_stability --out /tmp/stab.json          # the docs' grid
    python -m research.stiff_stability --fountain steep --c 0.003 0.01 --d 0 1e-5

Cost: 0.15-0.8 s of wall time per simulated second at ``d <= 1e-4`` (1-5 substeps),
about 7 s per second at ``d = 1e-3`` (50 substeps).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

from chainfountain.study.api import start
from chainfountain.study.changes import with_changes
from chainfountain.theory.stiff import scaled_stiffness
from research.stiff_runs import FOUNTAINS, case_level, record

GRIDS: dict[str, tuple[list[float], list[float]]] = {
    "wide_low": ([0.01, 0.04, 0.121, 0.25], [0.0, 1e-5, 1e-4, 1e-3]),
    "steep": ([0.003, 0.01, 0.04], [0.0, 1e-5, 1e-4]),
}
"""The default grid per fountain: stiffnesses (N*m/rad) and dampers (N*m*s/rad)."""


def _detrended_rms(t: np.ndarray, y: np.ndarray) -> float:
    p = np.polyfit(t, y, 1)
    return float(np.sqrt(np.mean((y - np.polyval(p, t)) ** 2)))


def vertex_analysis(t: np.ndarray, y: np.ndarray, skip: float, window: float) -> dict:
    """Growth rate, period, amplitude and class of the vertex height series."""
    sel = t >= skip
    t, y = t[sel], y[sel]
    edges = np.arange(t[0], t[-1] + 1e-9, 1.0)
    cen, rms = [], []
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        m = (t >= a) & (t < b)
        if m.sum() > 5:
            cen.append(0.5 * (a + b))
            rms.append(_detrended_rms(t[m], y[m]))
    cen, rms = np.array(cen), np.array(rms)
    ok = rms > 0
    sigma = float(np.polyfit(cen[ok], np.log(rms[ok]), 1)[0]) if ok.sum() >= 3 else math.nan
    half = t >= 0.5 * (t[0] + t[-1])
    yh = y[half] - np.polyval(np.polyfit(t[half], y[half], 1), t[half])
    dt = float(np.median(np.diff(t)))
    spec = np.abs(np.fft.rfft(yh * np.hanning(len(yh)))) ** 2
    freqs = np.fft.rfftfreq(len(yh), dt)
    k = int(np.argmax(spec[1:]) + 1)
    period = float(1.0 / freqs[k])
    last = t >= t[-1] - window
    mean = float(y[last].mean())
    mid = 0.5 * (t[last][0] + t[-1])
    drift = float((y[last & (t >= mid)].mean() - y[last & (t < mid)].mean()) / mean)
    rel_std = float(y[last].std() / mean)
    p2p = float((y[half].max() - y[half].min()) / y[half].mean())
    if abs(drift) <= 3e-3 and rel_std <= 3e-3:
        cls = "steady"
    elif p2p > 0.10:
        cls = "cycling"
    elif sigma > 0.1:
        cls = "growing"
    else:
        cls = "unsteady"
    return {"sigma": sigma, "period": period, "amp_last": float(rms[-1] / mean),
            "rel_std": rel_std, "drift": drift, "p2p_last_half": p2p, "class": cls,
            "vertex_h": mean, "rms_windows": [[float(a), float(b)] for a, b in zip(cen, rms,
                                                                                strict=True)]}


def normal_displacement(profiles: list, t0: float) -> tuple[np.ndarray, np.ndarray,
                                                               np.ndarray, np.ndarray]:
    """``(t, w, xbar, ybar)``: each profile's normal displacement from the mean curve of
    the profiles from ``t0`` on (joints common to all), and that mean curve."""
    profs = [p for p in profiles if p.t >= t0 - 1e-12]
    n = min(len(p.x) for p in profs)
    X = np.array([p.x[:n] for p in profs])
    Y = np.array([p.y[:n] for p in profs])
    xb, yb = X.mean(axis=0), Y.mean(axis=0)
    tx, ty = np.gradient(xb), np.gradient(yb)
    norm = np.hypot(tx, ty)
    nx, ny = -ty / norm, tx / norm
    w = (X - xb) * nx + (Y - yb) * ny
    return np.array([p.t for p in profs]), w, xb, yb


def _lag(a: np.ndarray, b: np.ndarray, dt: float, max_lag: float) -> float:
    """The lag (s) by which ``b`` follows ``a`` (positive: ``b`` later), at the largest
    cross-correlation within ``max_lag``."""
    a = (a - a.mean()) / (a.std() or 1.0)
    b = (b - b.mean()) / (b.std() or 1.0)
    m = max(1, int(round(max_lag / dt)))
    lags = np.arange(-m, m + 1)
    cc = [np.mean(a[max(0, -k): len(a) - max(0, k)] * b[max(0, k): len(b) - max(0, -k)])
          for k in lags]
    i = int(np.argmax(cc))
    if 0 < i < len(cc) - 1:  # parabolic refinement
        y0, y1, y2 = cc[i - 1], cc[i], cc[i + 1]
        den = y0 - 2 * y1 + y2
        off = 0.5 * (y0 - y2) / den if den != 0 else 0.0
    else:
        off = 0.0
    return float((lags[i] + off) * dt)


def spectrum(w: np.ndarray, dt: float, ds: float,
             band: tuple[float, float] | None = None) -> dict[str, float]:
    """The 2-D spectrum of ``w[t, s]``: the share of power upstream, the dominant
    frequency (Hz), wavenumber (1/m, cycles) and phase speed (m/s, positive downstream),
    over all wavenumbers or those in ``band`` (1/m). A wave ``cos(2 pi (kappa s - f t))``
    runs downstream; numpy's transform puts it at ``(f, kappa)`` of opposite signs."""
    nt, ns = w.shape
    win = np.outer(np.hanning(nt), np.hanning(ns))
    W = np.fft.fft2((w - w.mean(axis=0)) * win)
    P = np.abs(W) ** 2
    f = np.fft.fftfreq(nt, dt)[:, None]
    k = np.fft.fftfreq(ns, ds)[None, :]
    keep = (f != 0) & (k != 0)
    if band is not None:
        keep &= (np.abs(k) >= band[0]) & (np.abs(k) <= band[1])
    prod = f * k
    up = float(P[keep & (prod > 0)].sum())
    down = float(P[keep & (prod < 0)].sum())
    Pm = np.where(keep, P, 0.0)
    i, j = np.unravel_index(int(np.argmax(Pm)), P.shape)
    fd, kd = float(f[i, 0]), float(k[0, j])
    return {"upstream_share": up / (up + down) if up + down > 0 else math.nan,
            "f": abs(fd), "kappa": abs(kd), "phase_speed": -fd / kd if kd else math.nan,
            "direction": "upstream" if fd * kd > 0 else "downstream"}


def guide_ratio(w: np.ndarray, dt: float, ds: float, f0: float,
                band: tuple[float, float] | None = None) -> float:
    """Downstream-running over upstream-running power within 30 % of ``f0`` (and the
    wavenumbers of ``band``, 1/m), over the arc ``w`` covers."""
    nt, ns = w.shape
    win = np.outer(np.hanning(nt), np.hanning(ns))
    P = np.abs(np.fft.fft2((w - w.mean(axis=0)) * win)) ** 2
    f = np.fft.fftfreq(nt, dt)[:, None]
    k = np.fft.fftfreq(ns, ds)[None, :]
    sel = (np.abs(np.abs(f) - f0) <= 0.3 * f0) & (k != 0)
    if band is not None:
        sel &= (np.abs(k) >= band[0]) & (np.abs(k) <= band[1])
    up = float(P[sel & (f * k > 0)].sum())
    down = float(P[sel & (f * k < 0)].sum())
    return down / up if up > 0 else math.nan


def _string(spec: dict, v: float, tb: float, e_b: float, L: float) -> None:
    """The stiff string's phase and group speeds at the spectrum's dominant wavenumber,
    on its slow branch (``omega = v k (1 - R)``, the one whose ``omega = 0`` wave is the
    BVP's standing wave, running upstream for shorter waves) and its fast one
    (``v k (1 + R)``), ``R = sqrt((Tbar + e_B k^2)/(1 + k^2 L^2/12))``."""
    def root(kk: float) -> float:
        return math.sqrt(max(0.0, (tb + e_b * kk * kk) / (1.0 + kk * kk * L * L / 12.0)))

    kk = 2 * math.pi * spec["kappa"]
    r = root(kk)
    spec["phase_speed_theory_upstream"] = v * (1.0 - r)
    spec["phase_speed_theory_downstream"] = v * (1.0 + r)
    dk = 1e-4 * max(kk, 1e-6)
    dr = (root(kk + dk) * (kk + dk) - root(kk - dk) * (kk - dk)) / (2 * dk)
    spec["group_speed_theory_slow"] = v * (1.0 - dr)
    spec["group_speed_theory_fast"] = v * (1.0 + dr)


def envelope_speed(w: np.ndarray, dt: float, ds: float, f0: float, a: int, b: int,
                   max_lag: float) -> float:
    """The speed (m/s, positive downstream) at which the envelope of ``w`` in the
    frequency band ``f0 +- 30 %`` travels from arc index ``a`` to ``b``: the lag of the
    largest cross-correlation of the band's amplitude (the group speed where one
    branch carries the band)."""
    nt = w.shape[0]
    fr = np.fft.fftfreq(nt, dt)
    mask = (fr > 0.7 * f0) & (fr < 1.3 * f0)  # the analytic signal of the band

    def env(x: np.ndarray) -> np.ndarray:
        X = np.fft.fft(x - x.mean())
        return np.abs(np.fft.ifft(np.where(mask, 2 * X, 0.0)))

    lag = _lag(env(w[:, a]), env(w[:, b]), dt, max_lag)
    return (b - a) * ds / lag if lag != 0 else math.inf


def wave_analysis(runner, settings: dict, t_from: float, t_to: float, at: list[float],
                  guide_part: float) -> dict[str, Any]:
    """The mechanism over ``[t_from, t_to]`` (see the module docstring)."""
    rec = runner.recorder
    profiles = [p for p in rec.profiles if t_from - 1e-12 <= p.t <= t_to + 1e-12]
    t, w, xb, yb = normal_displacement(profiles, t_from)
    L = settings["L"]
    n = w.shape[1]
    dt = float(np.median(np.diff(t)))
    idx = [min(n - 1, int(round(a * (n - 1)))) for a in at]
    rms = [float(w[:, i].std()) for i in idx]
    # the dominant frequency of w where it is largest
    i_big = idx[int(np.argmax(rms))]
    sp = np.abs(np.fft.rfft(w[:, i_big] - w[:, i_big].mean())) ** 2
    fr = np.fft.rfftfreq(len(t), dt)
    f0 = float(fr[int(np.argmax(sp[1:]) + 1)])
    lags = []
    for a, b in zip(idx[:-1], idx[1:], strict=True):
        lag = _lag(w[:, a], w[:, b], dt, 0.5 / f0)
        ds = (b - a) * L
        lags.append({"s_from": a * L, "s_to": b * L, "lag": lag,
                     "speed": ds / lag if lag != 0 else math.inf})
    tb = float(np.mean([np.mean(p.tension_bar[:n]) for p in profiles]))
    ts = rec.series("t")
    sel = (ts >= t_from - 1e-12) & (ts <= t_to + 1e-12)
    v = float(np.mean(rec.series("speed_mean")[sel]))
    e = scaled_stiffness(settings["c"], L, settings["lambda"], v)
    e_b = settings["c"] * L / (settings["lambda"] * v * v)
    lam_s = 2 * math.pi * math.sqrt(e / (1.0 - tb)) if e > 0 and tb < 1 else math.nan
    whole = spectrum(w, dt, L)
    _string(whole, v, tb, e_b, L)
    m = max(4, int(round(guide_part * n)))
    out: dict[str, Any] = {
        "window": [float(t[0]), float(t[-1])], "arc": n * L, "at_s": [i * L for i in idx],
        "w_rms": rms, "f0": f0, "lags": lags, "spectrum": whole, "Tbar_mean": tb, "v": v,
        "e": e, "standing_wavelength": lam_s}
    # the damper's decay of the standing-wavelength waves over the flight (the stiff
    # BVP's rate delta (1 - Tbar)/(2 e^2)), with the numerical wave damper added
    delta = (settings["d"] + settings["wave_damper"]) * L / (settings["lambda"] * v)
    out["attenuation"] = delta * (1.0 - tb) * n * L / (2.0 * e * e) if e > 0 else math.nan
    if math.isfinite(lam_s):
        band = (0.5 / lam_s, min(2.0 / lam_s, 0.5 / L))
        bend = spectrum(w, dt, L, band)
        _string(bend, v, tb, e_b, L)
        out["bending"] = bend
        out["bending_band"] = list(band)
        fb = bend["f"] or f0
        i30, i70 = idx[1], idx[3] if len(idx) > 3 else idx[-1]
        bend["envelope_speed"] = envelope_speed(w, dt, L, fb, i30, i70,
                                                0.5 * (t[-1] - t[0]))
        out["guide_down_over_up"] = guide_ratio(w[:, :m], dt, L, fb, band)
        out["floor_down_over_up"] = guide_ratio(w[:, -m:], dt, L, fb, band)
    return out


def figure(runner, settings: dict, path: Path, title: str) -> None:
    """The normal displacement ``w(s, t)`` over the whole run as a space-time map (arc
    length from the guide across, time up), and the vertex height against time."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rec = runner.recorder
    profs = rec.profiles
    late = [p for p in profs if p.t >= profs[-1].t - 4.0]
    # every profile's displacement from the last 4 s's mean curve
    _, _, xb, yb = normal_displacement(late, late[0].t)
    n = min(len(xb), min(len(p.x) for p in profs))
    t_all = np.array([p.t for p in profs])
    X = np.array([p.x[:n] for p in profs])
    Y = np.array([p.y[:n] for p in profs])
    tx, ty = np.gradient(xb[:n]), np.gradient(yb[:n])
    nrm = np.hypot(tx, ty)
    W = (X - xb[:n]) * (-ty / nrm) + (Y - yb[:n]) * (tx / nrm)
    fig, ax = plt.subplots(1, 2, figsize=(11, 5), gridspec_kw={"width_ratios": [3, 1]})
    s = np.arange(n) * settings["L"]
    lim = float(np.percentile(np.abs(W), 99)) or 1e-6
    im = ax[0].pcolormesh(s, t_all, W * 1e3, cmap="RdBu_r", vmin=-lim * 1e3, vmax=lim * 1e3,
                          shading="auto")
    fig.colorbar(im, ax=ax[0], label="w (mm)")
    ax[0].set_xlabel("arc length from the guide (m)")
    ax[0].set_ylabel("t (s)")
    ax[0].set_title(title)
    ax[1].plot(rec.series("vertex_y"), rec.series("t"))
    ax[1].set_xlabel("vertex height (m)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def run_one(fountain: str, c: float, d: float, duration: float, sample: float,
            skip: float, window: float, at: list[float], guide_part: float,
            fig: Path | None = None) -> dict:
    lvl, settings = case_level(fountain, c, d, 1)
    lvl = with_changes(lvl, {"recording.sample_interval": sample}, where="stability")
    runner = start(lvl)
    t0 = time.perf_counter()
    ended = runner.advance(duration)
    out: dict[str, Any] = {"fountain": fountain, "c": c, "d": d, "settings": settings,
                           "duration": runner.time, "wall_s": time.perf_counter() - t0,
                           "sample": sample, "start": "catenary",
                           "ended": None if ended is None else ended.reason}
    if ended is not None:
        out["class"] = "diverged"
        return out
    rec = runner.recorder
    out.update(vertex_analysis(rec.series("t"), rec.series("vertex_y"), skip, window))
    out["waves_early"] = wave_analysis(runner, settings, skip, skip + window, at,
                                       guide_part)
    out["waves_late"] = wave_analysis(runner, settings, runner.time - window, runner.time,
                                      at, guide_part)
    if fig is not None:
        figure(runner, settings, fig.with_name(f"{fig.stem}_{fountain}_c{c:g}_d{d:g}"
                                               f"{fig.suffix}"), f"{fountain} c={c:g} d={d:g}")
    return out


def _waves_line(wv: dict) -> str:
    sp = wv["spectrum"]
    lags = " ".join(f"{x['speed']:+.1f}" for x in wv["lags"])
    out = (f"[{wv['window'][0]:.0f}-{wv['window'][1]:.0f}s] f0={wv['f0']:.2f}Hz "
           "w_rms(mm)=" + ",".join(f"{1e3 * x:.2f}" for x in wv["w_rms"])
           + f" lags {lags} m/s; all: up {sp['upstream_share']:.2f} {sp['direction']} "
           f"f={sp['f']:.2f} c_ph={sp['phase_speed']:+.2f}; A={wv['attenuation']:.2f}")
    b = wv.get("bending")
    if b is not None:
        out += (f"; bending (lam_s={wv['standing_wavelength']:.3f}m): up "
                f"{b['upstream_share']:.2f} {b['direction']} f={b['f']:.2f} "
                f"lam={1 / b['kappa'] if b['kappa'] else 0:.3f} c_ph={b['phase_speed']:+.2f} "
                f"(string {b['phase_speed_theory_upstream']:+.2f}/"
                f"{b['phase_speed_theory_downstream']:+.2f}; group "
                f"{b['group_speed_theory_slow']:+.2f}/{b['group_speed_theory_fast']:+.2f}) "
                f"envelope {b['envelope_speed']:+.2f} m/s guide d/u="
                f"{wv['guide_down_over_up']:.2f} floor d/u={wv['floor_down_over_up']:.2f}")
    return out


def _line(r: dict) -> str:
    head = (f"{r['fountain']:8s} c={r['c']:<6g} d={r['d']:<7g} sub={r['settings']['substeps']}"
            f" wall={r['wall_s']:.0f}s")
    if r.get("ended"):
        return head + f" ENDED {r['ended']}"
    return (head + f" {r['class']:9s} sigma={r['sigma']:+.2f}/s T={r['period']:.2f}s "
            f"amp={100 * r['amp_last']:.3f}% p2p={100 * r['p2p_last_half']:.1f}%\n  early "
            + _waves_line(r["waves_early"]) + "\n  late  " + _waves_line(r["waves_late"]))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m research.stiff_stability",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("--fountain", choices=sorted(FOUNTAINS), nargs="+",
                    default=["wide_low", "steep"])
    ap.add_argument("--c", type=float, nargs="+", help="stiffnesses (default: the grid's)")
    ap.add_argument("--d", type=float, nargs="+", help="dampers (default: the grid's)")
    ap.add_argument("--duration", type=float, default=16.0)
    ap.add_argument("--sample", type=float, default=0.01)
    ap.add_argument("--skip", type=float, default=2.0)
    ap.add_argument("--window", type=float, default=4.0)
    ap.add_argument("--at", type=float, nargs="+", default=[0.1, 0.3, 0.5, 0.7, 0.9])
    ap.add_argument("--guide-part", type=float, default=0.3)
    ap.add_argument("--out", type=Path)
    ap.add_argument("--figure", type=Path, metavar="PATH.png",
                    help="also draw each run's w(s, t) to PATH_<fountain>_c<c>_d<d>.png")
    a = ap.parse_args(argv)
    runs = []
    for f in a.fountain:
        cs = a.c or GRIDS[f][0]
        ds = a.d if a.d is not None else GRIDS[f][1]
        for c in cs:
            for d in ds:
                r = run_one(f, c, d, a.duration, a.sample, a.skip, a.window, a.at,
                            a.guide_part, a.figure)
                record(runs, r, _line(r), a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
