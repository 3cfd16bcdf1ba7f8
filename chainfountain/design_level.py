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

from chainfountain.level import io
from chainfountain.sim.config import ChainConfig, FeedConfig, SimConfig, SolverConfig
from chainfountain.theory.design import Design

MAX_QL = 0.1
"""Largest q*L (link length times vertex curvature) the defaults accept (docs/convergence.md)."""
MAX_LINK = 0.02
MIN_LINK = 0.002


def link_length_for(q: float) -> float:
    """Longest link (m, whole millimetres, at most 2 cm) with ``q*L <= MAX_QL``."""
    L = math.floor(min(MAX_LINK, MAX_QL / q) * 1000.0) / 1000.0
    return max(L, MIN_LINK)


def iterations_for(links_in_flight: int) -> int:
    """Solver iterations: 10 suffice up to ~250 links in flight, longer chains need more
    to keep the stretch under 0.1 % (measured on paper_tall_fine: 24 for 414 links)."""
    return 10 if links_in_flight <= 250 else 24


def design_sim_config(d: Design) -> SimConfig:
    """The fed level's configuration for a design."""
    f = d.fountain
    L = link_length_for(f.q)
    n_flight = int(math.ceil(f.length / L))
    return SimConfig(
        kind="feed",
        gravity=f.g,
        chain=ChainConfig(link_length=L, linear_density=d.lam),
        feed=FeedConfig(speed=f.v, launch_angle=f.alpha0, drop=f.H, end_tension=f.TE_bar,
                        floor_width=max(1.0, 2.5 * f.l)),
        solver=SolverConfig(iterations=iterations_for(n_flight)),
    )


def describe(d: Design) -> str:
    f, s = d.fountain, d.settings
    return (
        f"Designed with chainfountain design: the fountain l = {f.l:.4g} m, h = {f.h:.4g} m, "
        f"H = {f.H:.4g} m at v = {f.v:.4g} m/s (k = {f.k:.4g} 1/m, q*H = {f.qH:.4g}). "
        f"The guide launches the chain at {math.degrees(f.alpha0):.4g} deg and the floor pulls "
        f"its end with Tbar_E = {f.TE_bar:.4f}; watch the chain settle on the thin theory line "
        f"with its vertex {f.h:.3g} m above the guide and land {f.l:.3g} m downstream, with "
        f"Tbar_0 = {f.T0_bar:.4f} at the guide. The paper's apparatus for it ({d.label}): "
        f"xi2 = {s.xi2:.4f}, xi3 = {s.xi3:.4f}, Tbar_uc = {s.T_uc:.4f} "
        f"({d.m_uc:.4g} kg on a {math.degrees(d.slope_uc):.3g} deg track), "
        f"Tbar_lc = {s.T_lc:.4f} ({d.m_lc:.4g} kg)."
    )


def write_design_level(d: Design, path: str | Path, name: str | None = None) -> Path:
    """Write the design as a fed level file (validated, atomically)."""
    p = Path(path)
    level = io.make_level(name or p.stem, describe(d), design_sim_config(d))
    return io.save(level, p)
