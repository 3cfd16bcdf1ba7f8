"""Levels from a design: the fountain the paper's two-step procedure targets, as a fed level.

The written level is ``kind = "feed"``: a motor-driven guide launches the chain
at the design's speed ``v`` and launch angle ``alpha0``, and an absorbing floor
``H`` below pulls on the chain end with the design's ``Tbar_E`` (the end force
the apparatus must supply). The simulator then has to produce the target
fountain (vertex, span) on its own. The apparatus itself (rollers and carts)
is described in the level's description; the simulated apparatus is the
``apparatus`` level kind.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

from chainfountain.level import io
from chainfountain.sim import accuracy as accuracy_model
from chainfountain.sim.config import ChainConfig, FeedConfig, SimConfig, SolverConfig
from chainfountain.sim.reference import LaunchReference
from chainfountain.theory.design import Design

if TYPE_CHECKING:
    from chainfountain.sim.accuracy import Estimate

MAX_QL = 0.1
"""Largest q*L (link length times vertex curvature) the defaults accept (docs/convergence.md)."""
MAX_LINK = 0.02
MIN_LINK = 0.002
MAX_DT = 2.5e-4
"""The default time step (s), converged for ordinary fountains (docs/convergence.md)."""
MAX_VERTEX_STEP = 0.1
"""Largest ``q*v*dt / (k/q)``: the angle the chain turns at the vertex in one step,
over the vertex's distance from critical tension ``1 - Tbar = k/q`` (docs/convergence.md,
"Near-critical fountains")."""


def link_length_for(q: float) -> float:
    """Longest link (m, whole millimetres, at most 2 cm) with ``q*L <= MAX_QL``."""
    L = math.floor(min(MAX_LINK, MAX_QL / q) * 1000.0) / 1000.0
    return max(L, MIN_LINK)


def time_step_for(q: float, k: float, v: float) -> float:
    """Time step (s, whole microseconds, at most :data:`MAX_DT`) with
    ``q*v*dt/(k/q) <= MAX_VERTEX_STEP``.

    Near the vertex the tension is ``1 - k/q`` (paper, section "Inverted
    Catenary"): when ``k/q`` is small the fountain is close to critical
    (``T = lambda v^2``, where any shape is steady) and the integrator's
    first-order error makes the vertex creep upward. Measured on the paper's
    fountain D (``k/q = 0.017``, 4 mm links): +9.5, +3.8, +1.9 and +0.55 %/s
    at dt = 250, 125, 62.5 and 15.6 us. The three ordinary acceptance targets
    have ``q*v*dt/(k/q) = 0.03 ... 0.08`` at the default step.
    """
    dt = MAX_VERTEX_STEP * k / (q * q * v)
    return min(MAX_DT, math.floor(dt * 1e6) / 1e6)


def iterations_for(links_in_flight: int, dt: float = MAX_DT) -> int:
    """Solver iterations: 10 suffice up to ~250 links in flight, longer chains need more
    to keep the stretch under 0.1 % at the default step (measured on paper_tall_fine:
    24 for 414 links); at steps of 20 us and below 10 suffice (fountain D, 700 links:
    10 and 24 iterations give the same vertex to 0.1 %, stretch 0.01 %)."""
    return 10 if links_in_flight <= 250 or dt <= 2e-5 else 24


DESIGN_ACCURACY = 0.005
"""Accuracy ``chainfountain design`` asks of the error model by default (relative)."""


def design_estimate(d: Design, accuracy: float = DESIGN_ACCURACY) -> Estimate | None:
    """The error model's cheapest settings for the design's fountain at ``accuracy``
    (:func:`chainfountain.sim.accuracy.choose`), or ``None`` for a near-critical fountain
    outside the model (then :func:`time_step_for` picks the step).

    Raises :class:`~chainfountain.sim.accuracy.OutOfReach` when the model cannot reach the
    accuracy."""
    f = d.fountain
    ref = LaunchReference.from_launch(f.v, f.alpha0, f.H, f.g, TE_bar=max(0.0, f.TE_bar))
    if accuracy_model.in_domain(ref) is not None:
        return None
    return accuracy_model.choose(ref, accuracy)


def design_sim_config(d: Design, accuracy: float = DESIGN_ACCURACY) -> SimConfig:
    """The fed level's configuration for a design: link length, step and iterations from
    the error model for ``accuracy`` (``solver.accuracy``), or, for a near-critical
    fountain, from :func:`link_length_for`, :func:`time_step_for` and
    :func:`iterations_for`."""
    f = d.fountain
    est = design_estimate(d, accuracy)
    if est is not None:
        s = est.settings
        L, dt, iterations, acc = s.link_length, s.dt, s.iterations, accuracy
    else:
        L = link_length_for(f.q)
        dt = time_step_for(f.q, f.k, f.v)
        iterations, acc = iterations_for(int(math.ceil(f.length / L)), dt), 0.0
    return SimConfig(
        kind="feed",
        gravity=f.g,
        chain=ChainConfig(link_length=L, linear_density=d.lam),
        # at k = k_max, Tbar_E is zero up to rounding (-1e-16 was seen for fountain D);
        # check_target has already refused a pushing end beyond that
        feed=FeedConfig(speed=f.v, launch_angle=f.alpha0, drop=f.H,
                        end_tension=max(0.0, f.TE_bar),
                        floor_width=max(1.0, 2.5 * f.l)),
        solver=SolverConfig(dt=dt, iterations=iterations, accuracy=acc),
    )


def describe(d: Design) -> str:
    f, s = d.fountain, d.settings
    return (
        f"Designed with chainfountain design: the fountain l = {f.l:.4g} m, h = {f.h:.4g} m, "
        f"H = {f.H:.4g} m at v = {f.v:.4g} m/s (k = {f.k:.4g} 1/m, q*H = {f.qH:.4g}). "
        f"The guide launches the chain at {math.degrees(f.alpha0):.4g} deg and "
        + (f"the floor pulls its end with Tbar_E = {f.TE_bar:.4f}" if f.TE_bar > 0.0 else
           "its end lies free on the absorbing floor (Tbar_E = 0: k = k_max)")
        + "; watch the chain settle on the thin theory line "
        f"with its vertex {f.h:.3g} m above the guide and land {f.l:.3g} m downstream, with "
        f"Tbar_0 = {f.T0_bar:.4f} at the guide. The paper's apparatus for it ({d.label}): "
        f"xi2 = {s.xi2:.4f}, xi3 = {s.xi3:.4f}, Tbar_uc = {s.T_uc:.4f} "
        f"({d.m_uc:.4g} kg on a {math.degrees(d.slope_uc):.3g} deg track), "
        f"Tbar_lc = {s.T_lc:.4f} ({d.m_lc:.4g} kg)."
        + near_critical_note(d)
    )


def near_critical_note(d: Design) -> str:
    """A sentence for near-critical designs (reduced time step), else ``""``."""
    f = d.fountain
    dt = time_step_for(f.q, f.k, f.v)
    if dt >= MAX_DT:
        return ""
    return (f" This fountain is near-critical (1 - Tbar at the vertex = k/q = {f.k / f.q:.3f}), "
            f"so the level steps at dt = {dt * 1e6:.0f} us instead of {MAX_DT * 1e6:.0f} us "
            "to keep the vertex from creeping: it runs well below real time.")


def write_design_level(d: Design, path: str | Path, name: str | None = None,
                       accuracy: float = DESIGN_ACCURACY) -> Path:
    """Write the design as a fed level file (validated, atomically)."""
    p = Path(path)
    level = io.make_level(name or p.stem, describe(d), design_sim_config(d, accuracy))
    return io.save(level, p)
