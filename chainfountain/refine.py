"""Discretisation error of a fed fountain, estimated by refinement.

A fed level is run at its own link length ``L`` and step ``dt`` and again at ``L/2`` and
``dt/2`` (and, for a longer ladder, ``L/4`` and ``dt/4``), each started on the predicted
catenary, settled and then time-averaged (``docs/convergence.md``). The fountain's
discretisation error is first order in ``L`` and ``dt`` together (the table in
``docs/convergence.md``), so the error of the coarse run's figure ``f(L)`` is estimated as

    e(L) = 2 * (f(L) - f(L/2))        (Richardson, order 1)

and the figure at zero link length and step as ``f(L/2) - (f(L) - f(L/2))``. Each window
mean also has a statistical error (standard error of four block means), which bounds how
small a difference the estimate resolves: the error bar given for a figure is
``|e(L)| + 2 sigma``.
"""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from chainfountain.errors import UserError
from chainfountain.sim import joints
from chainfountain.sim.kinds import kind_of

if TYPE_CHECKING:
    from chainfountain.sim.config import SimConfig

SETTLE = 1.5
"""Simulated seconds from the catenary start before averaging (as tests/sim/test_feed.py)."""
WINDOW = 2.0
"""Simulated seconds averaged."""
BLOCKS = 4
"""Blocks of the window for the statistical error of its mean."""
FIGURES: dict[str, str] = {
    "h": "vertex height h (relative error)",
    "vertex_x": "vertex x (relative error)",
    "l": "landing l (relative error)",
    "v": "mean speed (relative error)",
    "T0_bar": "Tbar_0 (absolute error)",
}
"""Figures compared with the paper's catenary, keyed as in ``summary.json``."""



def method(settle: float, window: float, refinements: int) -> str:
    """How the estimate was made, in words (``converge.json``, ``summary.json``)."""
    ladder = ", ".join(["(L, dt)"] + [f"(L/{2**i}, dt/{2**i})" for i in range(1, refinements)])
    return (f"refinement: the level at {ladder}, each started on the predicted catenary, "
            f"settled {settle:g} s and averaged {window:g} s; discretisation error of "
            "(L, dt) = 2 (f(L) - f(L/2)) (first order)")


@dataclass
class RefinementRun:
    """One run of the ladder: its settings and figures (errors against the theory)."""

    factor: int
    link_length: float
    dt: float
    links: int
    errors: dict[str, float]
    """Error of each :data:`FIGURES` entry against the paper's catenary."""
    stat: dict[str, float]
    """Standard error of each figure's window mean (:data:`BLOCKS` block means)."""
    stretch: float
    """Largest total joint gap over the chain length in the window."""
    realtime_factor: float
    spread: float = math.nan
    """Window mean of the instantaneous link-speed spread ``(max - min)/mean``."""


@dataclass
class Refinement:
    """The ladder of runs and the first-order estimate for the coarsest."""

    level: str
    settle: float = SETTLE
    window: float = WINDOW
    runs: list[RefinementRun] = field(default_factory=list)

    def discretisation_error(self) -> dict[str, float]:
        """``2 (f(L) - f(L/2))`` for every figure (needs two runs)."""
        a, b = self.runs[0].errors, self.runs[1].errors
        return {f: 2.0 * (a[f] - b[f]) for f in FIGURES}

    def extrapolated(self) -> dict[str, float]:
        """The figures' errors at zero link length and step, from the two finest runs."""
        a, b = self.runs[-2].errors, self.runs[-1].errors
        return {f: b[f] - (a[f] - b[f]) for f in FIGURES}

    def statistical_error(self) -> dict[str, float]:
        """Standard error of the estimate ``2 (f(L) - f(L/2))`` from the window scatter."""
        a, b = self.runs[0].stat, self.runs[1].stat
        return {f: 2.0 * math.hypot(a[f], b[f]) for f in FIGURES}

    def error_bar(self) -> dict[str, float]:
        """What each figure of the coarse run may be off by its discretisation:
        ``|2 (f(L) - f(L/2))| + 2 sigma`` (``sigma`` the :meth:`statistical_error`), so that
        an estimate the windows do not resolve still gives an honest bound."""
        d, s = self.discretisation_error(), self.statistical_error()
        return {f: abs(d[f]) + 2.0 * s[f] for f in FIGURES}

    def resolved(self) -> dict[str, bool]:
        """Whether each estimate exceeds twice its statistical error."""
        d, s = self.discretisation_error(), self.statistical_error()
        return {f: abs(d[f]) > 2.0 * s[f] for f in FIGURES}

    def observed_order(self) -> dict[str, float | None]:
        """``log2`` of successive differences' ratio (three runs or more; ``None`` when a
        difference is within the statistical error)."""
        out: dict[str, float | None] = {}
        for f in FIGURES:
            if len(self.runs) < 3:
                out[f] = None
                continue
            r0, r1, r2 = self.runs[0], self.runs[1], self.runs[2]
            d1, d2 = r0.errors[f] - r1.errors[f], r1.errors[f] - r2.errors[f]
            noise = 2.0 * math.hypot(r1.stat[f], r2.stat[f])
            ok = abs(d2) > noise and d1 * d2 > 0
            out[f] = math.log2(d1 / d2) if ok else None
        return out

    def as_dict(self) -> dict:
        """JSON-ready form (``converge.json``, ``summary.json``'s ``error_bars``)."""
        out: dict = {"method": method(self.settle, self.window, len(self.runs)),
                     "level": self.level,
                     "runs": [vars(r) for r in self.runs]}
        if len(self.runs) >= 2:
            out["discretisation_error"] = self.discretisation_error()
            out["statistical_error"] = self.statistical_error()
            out["error_bar"] = self.error_bar()
            out["resolved"] = self.resolved()
            out["extrapolated_error"] = self.extrapolated()
            out["observed_order"] = self.observed_order()
        return out


def refined_config(cfg: SimConfig, factor: int, level: str = "level") -> SimConfig:
    """``cfg`` with link length and step divided by ``factor`` (the same chain: joint springs
    and dampers scaled to keep its bending rigidity, :func:`chainfountain.sim.joints.
    same_chain`, with the sub-steps their spring needs), started on the catenary
    (:class:`~chainfountain.errors.UserError` when the level is not fed, or the link would
    be shorter than the schema allows)."""
    from chainfountain.fields import allowed_text, in_range
    from chainfountain.level.io import field_meta

    if not kind_of(cfg).predicted:
        raise UserError(f"{level}: kind = {cfg.kind!r}; allowed: refinement works on fed "
                        "levels (kind 'feed'), whose fountain the paper predicts from the feed")
    out = copy.deepcopy(cfg)
    joints.same_chain(out.chain, cfg.chain.link_length / factor)
    meta = field_meta("chain.link_length")
    if not in_range(out.chain.link_length, meta):
        most = 1
        while in_range(cfg.chain.link_length / 2**most, meta):
            most += 1
        raise UserError(
            f"--refinements {int(math.log2(factor)) + 1}: {level}'s chain.link_length "
            f"{cfg.chain.link_length:g} m / {factor} = {out.chain.link_length:g} m, but a link "
            f"length must be {allowed_text(meta)}; allowed: at most {most} refinements for "
            "this level")
    out.chain.link_radius = min(cfg.chain.link_radius, 0.4 * out.chain.link_length)
    out.solver.dt = cfg.solver.dt / factor
    out.solver.substeps = joints.substeps_for_spring(out.chain, out.solver)
    out.solver.accuracy = 0.0
    out.initial.mode = "catenary"
    out.feed.starter = 0.0  # on the fountain, a machine needs no starter
    if out.feed.drive != "motor":  # a machine: start on the fountain at the speed it selects
        from chainfountain.sim.reference import LaunchReference

        try:
            out.feed.speed = LaunchReference.of_level(out).v
        except ValueError:
            pass
    _converged_iterations(out)
    return out


def _converged_iterations(cfg: SimConfig) -> None:
    """Raise ``cfg``'s solver iterations to what the finer chain needs to converge
    (:func:`chainfountain.sim.accuracy.iterations_needed`): twice the links at half the step
    need more iterations, and an unconverged solve would lower the fountain and spoil the
    estimate."""
    from chainfountain.sim import accuracy
    from chainfountain.sim.reference import LaunchReference

    try:
        ref = LaunchReference.of_level(cfg)
    except ValueError:
        return
    n = accuracy.links_in_flight(ref, cfg.chain.link_length)
    h = cfg.solver.dt / cfg.solver.substeps
    cfg.solver.iterations = max(cfg.solver.iterations, accuracy.iterations_needed(n, h))


def measure(cfg: SimConfig, factor: int = 1, *, settle: float = SETTLE,
            window: float = WINDOW) -> RefinementRun:
    """Run ``cfg`` from the catenary: settle, then average ``window`` seconds."""
    from chainfountain.sim import Recorder, Simulation

    sim = Simulation(cfg)
    wall = time.perf_counter()
    sim.advance(settle)
    rec = Recorder(sim, profiles=False)
    sim.advance(window)
    wall = time.perf_counter() - wall
    ref = sim.reference
    t = rec.series("t")
    series = {
        "h": rec.series("vertex_y") / ref.h - 1.0,
        "vertex_x": rec.series("vertex_x") / ref.x_rise - 1.0,
        "l": rec.series("landing_x") / ref.landing_x - 1.0,
        "v": rec.series("speed_mean") / ref.v - 1.0,
        "T0_bar": rec.series("T0_bar") - ref.T0_bar,
    }
    blocks = np.array_split(np.arange(len(t)), BLOCKS)
    errors, stat = {}, {}
    for f, s in series.items():
        errors[f] = float(np.mean(s))
        means = [float(np.mean(s[b])) for b in blocks if len(b)]
        stat[f] = float(np.std(means, ddof=1) / math.sqrt(len(means))) if len(means) > 1 \
            else math.nan
    return RefinementRun(
        factor=factor, link_length=cfg.chain.link_length, dt=cfg.solver.dt,
        links=sim.n_links, errors=errors, stat=stat,
        stretch=float(np.max(rec.series("stretch"))),
        realtime_factor=(settle + window) / wall if wall > 0 else math.nan,
        spread=float(np.mean((rec.series("speed_max") - rec.series("speed_min"))
                             / rec.series("speed_mean"))),
    )


def refine(cfg: SimConfig, level: str = "level", *, refinements: int = 2,
           settle: float = SETTLE, window: float = WINDOW,
           progress: Callable[[str], None] | None = None) -> Refinement:
    """The ladder ``factor = 1, 2, 4, ...`` (``refinements`` runs) of a fed level."""
    if refinements < 2:
        raise UserError(f"refinements = {refinements}; allowed: at least 2")
    configs = [refined_config(cfg, 2**i, level) for i in range(refinements)]
    out = Refinement(level=level, settle=settle, window=window)
    for i, c in enumerate(configs):
        if progress is not None:
            progress(f"run {i + 1}/{refinements}: L = {c.chain.link_length * 1e3:g} mm, "
                     f"dt = {c.solver.dt * 1e6:g} us")
        out.runs.append(measure(c, 2**i, settle=settle, window=window))
    return out
