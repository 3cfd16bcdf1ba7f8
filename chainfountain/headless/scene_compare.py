"""A scene run against its closed form (``scene.closed_form``,
:mod:`chainfountain.theory.falling`): the probes the comparison records and the figures
it gives for ``summary.json``."""

from __future__ import annotations

from typing import Any

import numpy as np

from chainfountain.sim.config import SimConfig
from chainfountain.sim.probe_log import ProbeLog
from chainfountain.sim.scene_config import ProbeConfig
from chainfountain.theory import falling

SHARES = (0.25, 0.5, 0.75)
"""Where a folded fall is compared: these shares of the chain's length fallen."""
FORCE_BAND = 0.05
"""A folded fall's pin force is averaged over the free end's travel within this share of
the chain's length of each mark (the force rings from sample to sample)."""
SCALE_BAND = (0.25, 0.75)
"""A scale is compared while the length landed is within these shares of the chain."""
PREFIX = "closed_form:"
"""Names of the comparison's own probes (no level probe can be so named)."""


def probes(config: SimConfig) -> tuple[ProbeConfig, ...]:
    """What the comparison records besides the level's own probes."""
    form = config.scene.closed_form
    if form == "folded_fall":
        return (ProbeConfig(name=PREFIX + "free_end", kind="point", point=-1),
                ProbeConfig(name=PREFIX + "fixed_end", kind="pin_force", point=0))
    if form == "scale":
        return (ProbeConfig(name=PREFIX + "scale", kind="floor_force"),)
    return ()


def _ratio(a: float, b: float) -> float | None:
    return float(a / b - 1.0) if np.isfinite(a) and b else None


def folded_fall(config: SimConfig, log: ProbeLog, start: np.ndarray) -> dict[str, Any]:
    """The free end's speed at :data:`SHARES` of the chain's length fallen and the pin's
    mean force around them, against Calkin and March's energy-conserving fall."""
    g, lam = config.gravity, config.chain.linear_density
    length = (len(start) - 1) * config.chain.link_length
    end = log.by_name(PREFIX + "free_end")
    pin = log.by_name(PREFIX + "fixed_end")
    x = start[-1, 1] - end["y"]
    beyond = np.flatnonzero(x > 0.8 * length)
    keep = slice(0, beyond[0] if len(beyond) else len(x))
    x, v, F = x[keep], -end["vy"][keep], pin["F"][keep]

    def at(mark: float) -> tuple[float | None, ...]:
        """Speed, the closed form's speed, and the speed's and force's errors at ``mark``."""
        if len(x) < 2 or x.max() < mark:
            return None, None, None, None
        vs = float(np.interp(mark, x, v))
        vt = float(falling.folded_fall_speed(mark, length, g))
        band = np.abs(x - mark) <= FORCE_BAND * length
        Ft = falling.folded_fall_pin_force(x[band], length, lam, g)
        return vs, vt, _ratio(vs, vt), _ratio(float(F[band].mean()), float(Ft.mean()))

    speed, speed_th, speed_err, force_err = (list(c) for c in
                                             zip(*(at(s * length) for s in SHARES), strict=True))
    return {"name": "folded_fall", "reference": "Calkin and March, Am. J. Phys. 57, 154 "
            "(1989): v^2 = g x (2 Lc - x)/(Lc - x), F = lambda (g (Lc + x)/2 + v^2/4)",
            "length_m": length, "at_share": list(SHARES), "speed_m_s": speed,
            "speed_theory_m_s": speed_th, "speed_rel_error": speed_err,
            "force_rel_error": force_err}


def scale(config: SimConfig, log: ProbeLog, start: np.ndarray) -> dict[str, Any]:
    """The scale's mean reading while the length landed is within :data:`SCALE_BAND` of
    the chain, against Hamm and Geminard's ``3*lambda*g*y``."""
    g, lam = config.gravity, config.chain.linear_density
    length = (len(start) - 1) * config.chain.link_length
    gap = float(start[:, 1].min()) - config.chain.link_radius - config.scene.floor_y
    f = log.by_name(PREFIX + "scale")
    # a reading is the mean over its sample interval: the theory at the interval's middle
    dt = np.diff(f["t"], prepend=0.0)
    landed = falling.scale_landed(f["t"] - dt / 2, gap, g)
    lo, hi = SCALE_BAND
    band = (landed > lo * length) & (landed < hi * length)
    err = None
    if band.any():
        err = _ratio(float(-f["fy"][band].mean()),
                     float(falling.scale_force(landed[band], lam, g).mean()))
    return {"name": "scale", "reference": "Hamm and Geminard, Am. J. Phys. 78, 828 (2010): "
            "the scale reads 3 lambda g y", "length_m": length, "gap_m": gap,
            "landed_share": list(SCALE_BAND), "force_rel_error": err,
            "samples": int(band.sum())}


def compare(config: SimConfig, log: ProbeLog, start: np.ndarray) -> dict[str, Any] | None:
    """The comparison ``scene.closed_form`` names (``None`` for 'none'); ``start`` is the
    chain's link ends at the start."""
    form = config.scene.closed_form
    if form == "folded_fall":
        return folded_fall(config, log, start)
    if form == "scale":
        return scale(config, log, start)
    return None
