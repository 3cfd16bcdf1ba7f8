"""How accurate a fed fountain is at given settings, and the cheapest settings for an accuracy.

A fed fountain (absorbing floor, optional floor pull ``Tbar_E``) is compared with the paper's
inverted catenary (section "Inverted Catenary"). Its error at link length ``L``, time step
``dt`` and solver iterations comes from a model measured by ``research/error_model.py``
(34 fountains, links of 4-50 mm, ``q*L`` 0.02-0.12, ``k/q`` 0.06-0.35, ``Tbar_E`` 0-0.25;
128 runs from the catenary, 1.5 s settled and 3 s averaged; ``docs/convergence.md``,
"Error model and solver.accuracy"):

1. **Solver convergence.** Pymunk's iterative solver leaves part of each step's joint
   impulses unsolved; on a long chain that shows as a longitudinal oscillation (the
   link-speed spread) and, beyond a threshold, as a fountain that sinks by up to several
   per cent (``classroom`` at 1-cm links and 10 iterations: -3.9 %). The solve converges
   (spread at most 0.2 %) while the links in flight satisfy

       n <= N_SOLVER * sqrt(iterations / 10) * (DT0 / dt)**0.6

   (:func:`iterations_needed`; measured brackets: 10 iterations at 250 us hold up to 170
   links and fail from 230, at 62.5 us they hold 414).
2. **Discretisation** (solver converged): for each figure ``f`` (vertex height, vertex x,
   landing) the error is first order in the link length over the vertex's radius of
   curvature and over the fountain's height ``h``,

       e_f = A_L[f]*q*L + A_H[f]*L/h,

   fitted on the 79 converged runs whose step term (below) is small, with the margin
   ``MARGIN[f]``, the larger of the fit's largest miss and three times its rms. A floor
   pull near critical tension adds an error first order in the step whose size the runs
   bound but do not pin down (+1.6 % at 250 us, +1.0 % at 125 us, +0.56 % at 62.5 us for
   a 4.6-m/s launch with ``Tbar_E = 0.15`` and ``k/q = 0.063``):

       |step error| <= C_STEP[f] * q*v*dt*Tbar_E/(k/q).

   The bound given for a figure is ``|e_f| + MARGIN[f] + C_STEP[f]*q*v*dt*Tbar_E/(k/q)``.

3. **Joint resistance** (``chain.bending_stiffness`` c, ``chain.bending_damping`` d): the
   figures are compared with the steady stiff theory (:mod:`chainfountain.theory.stiff`),
   and the link term above stays; the margin is :data:`STIFF_MARGIN` instead of
   ``MARGIN``, 1.25 times the largest miss beyond the link term of 19 steady runs
   (``research/stiff_runs.py``; ``wide_low`` and a 75-deg, 3.5-m/s launch, c 0.003-0.08,
   d 1e-5-1e-3, links of 1 and 2 cm, the damper's sub-steps at ``2 d h/I <= 0.3``; the sim
   sits 0.2-0.7 % below the theory in height). It holds for joints no stiffer than
   ``e q^2 <=`` :data:`STIFF_EQ2` and ``delta q^3 <=`` :data:`STIFF_DQ3` (stiffness and
   damping over the vertex's bend, ``e`` and ``delta`` of
   :func:`chainfountain.theory.stiff.scaled_stiffness` and ``scaled_damping``), and only
   for a steady run: an undamped stiff fountain does not settle (docs/stiff_stability.md).

4. **An ideal machine's flight** (``feed.drive`` not ``"motor"``), compared with the paper's
   fountain at the speed the machine runs (``summary.json`` ``theory.at_speed``): the link
   term above predicts it (window means at 62.5 us: ``ideal_limit`` +0.48 % against
   +0.48 % predicted, ``ideal_fold`` +0.30 against +0.31 %), but the four presets' worst
   10-s windows (20-80 s, 250/125/62.5 us; ``python -m research.ideal_machine_holds --duration 80
   --dt-factors 1 0.5 0.25``) leave the bound by up to 0.75 % in the vertex height at
   250 us (``ideal_floor``; -0.04 % at 125 us), and by up to 0.59 % in the vertex's x at
   every step (``ideal_floor``, not monotonic in the step). The bound of a machine's
   flight adds :data:`IDEAL_STEP` (first order in the step) and :data:`IDEAL_MARGIN`,
   1.25 times those. Its speed is not bounded here: it sits a few tenths of a per cent
   off the laws' (the simulated chain's own imbalance over the bearing drag).

The cost model (wall seconds per simulated second, ``(n*(C_LINK + C_ITER*iterations))/dt``)
is the same grid's timing, two runs side by side on this 2-core machine; read it to +-50 %.
Near-critical fountains (``k/q`` below :data:`MIN_KQ`, the paper's fountain D) are outside
the model: their vertex creeps at a rate first order in ``dt`` (docs/convergence.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from chainfountain.sim.config import (
    ChainConfig,
    FeedConfig,
    InitialConfig,
    SimConfig,
    SolverConfig,
)
from chainfountain.sim.reference import LaunchReference

DT0 = 2.5e-4
"""Reference step (s)."""
N_SOLVER = 170.0
"""Links in flight the solver converges on at 10 iterations and ``DT0``."""
FIGURES = ("vertex_y", "vertex_x", "landing_x")
"""The figures the model bounds (relative errors, keyed as ``Summary.errors``)."""
A_L = {"vertex_y": 0.0156, "vertex_x": -0.0409, "landing_x": -0.0200}
"""Error per unit ``q*L`` (fit)."""
A_H = {"vertex_y": 0.0357, "vertex_x": 0.0230, "landing_x": -0.0054}
"""Error per unit ``L/h`` (fit)."""
MARGIN = {"vertex_y": 0.0028, "vertex_x": 0.0015, "landing_x": 0.0017}
"""The larger of the fit's largest residual and three times its rms (largest 0.28 / 0.12 /
0.15 %, rms 0.085 / 0.051 / 0.055 %)."""
C_STEP = {"vertex_y": 0.60, "vertex_x": 0.30, "landing_x": 0.25}
"""Bound on the step error per unit ``q*v*dt*Tbar_E/(k/q)``: 1.25 times the smallest
coefficient that covers every converged run's miss beyond the margin (0.48 / 0.24 / 0.20)."""
STIFF_MARGIN = {"vertex_y": 0.0082, "vertex_x": 0.0076, "landing_x": 0.0070}
"""A stiff chain's margin: 1.25 times the largest miss beyond the link term of the 19
steady stiff runs (0.66 / 0.61 / 0.56 %)."""
IDEAL_STEP = {"vertex_y": 0.0094, "vertex_x": 0.0, "landing_x": 0.0}
"""An ideal machine's flight: its added bound at :data:`DT0`, first order in the step
(1.25 times ``ideal_floor``'s 0.75 % beyond the bound in the vertex height at 250 us)."""
IDEAL_MARGIN = {"vertex_y": 0.0, "vertex_x": 0.0074, "landing_x": 0.0}
"""An ideal machine's flight: its added margin at every step (1.25 times ``ideal_floor``'s
0.59 % beyond the bound in the vertex's x; the landing never left it)."""
STIFF_EQ2 = 0.018
"""Largest ``e q^2`` measured (0.017)."""
STIFF_DQ3 = 1.6e-3
"""Largest ``delta q^3`` measured (1.57e-3)."""
MACHINE_MAX_LINK = 0.02
"""An ideal machine's longest links chosen (m): the presets' 2 cm, where
:data:`IDEAL_STEP` and :data:`IDEAL_MARGIN` were measured; its flight with coarser links
was not."""
MIN_KQ = 0.06
"""Smallest ``k/q`` measured; nearer criticality the model does not apply."""
MAX_QL = 0.12
"""Largest ``q*L`` measured."""
C_LINK, C_ITER = 0.23e-6, 0.023e-6
"""Wall seconds per link per step, and per link per iteration per step (fit of the grid)."""
LINKS_MM = (50, 40, 30, 25, 20, 15, 12, 10, 8, 6, 5, 4, 3, 2)
"""Candidate link lengths (mm); each also has to keep ``q*L <= MAX_QL``."""
STEPS_US = (250.0, 125.0, 62.5, 31.25)
"""Candidate time steps (us)."""
MIN_ITERATIONS, MAX_ITERATIONS = 10, 60


@dataclass(frozen=True)
class Settings:
    """What the model chooses: link length (m), step (s), solver iterations."""

    link_length: float
    dt: float
    iterations: int


@dataclass(frozen=True)
class Estimate:
    """The model's prediction for one fountain at one :class:`Settings`."""

    settings: Settings
    links: int
    """Links in flight (fountain arc length over link length)."""
    converged: bool
    """Whether the solver converges (:func:`iterations_needed` iterations or more)."""
    errors: dict[str, float] = field(default_factory=dict)
    """Predicted signed relative error of each figure from the link length (converged
    solver)."""
    bounds: dict[str, float] = field(default_factory=dict)
    """``|error| + MARGIN + C_STEP*step_term``: what each figure may be off by."""
    cost: float = math.nan
    """Estimated wall seconds per simulated second (one core)."""

    @property
    def worst(self) -> float:
        """The largest bound (``inf`` when the solver does not converge)."""
        return max(self.bounds.values()) if self.converged else math.inf


def in_domain(ref: LaunchReference, chain: ChainConfig | None = None,
              machine: bool = False) -> str | None:
    """Why the model does not apply to ``ref`` with ``chain``'s joints (``None`` when it
    does); ``machine``: an ideal machine's flight with ``chain``'s own links, measured no
    longer than :data:`MACHINE_MAX_LINK`."""
    if machine and chain is not None and chain.link_length > MACHINE_MAX_LINK + 1e-12:
        return (f"chain.link_length = {chain.link_length:g}: an ideal machine's flight was "
                f"measured at links up to {MACHINE_MAX_LINK:g} m")
    kq = ref.k / ref.q
    if kq < MIN_KQ:
        return (f"the fountain is near-critical (k/q = {kq:.3f} below {MIN_KQ}), where the "
                "vertex creeps at a rate first order in the step (docs/convergence.md)")
    if chain is not None and is_stiff(chain):
        eq2, dq3 = stiff_scales(ref, chain)
        if eq2 > STIFF_EQ2 or dq3 > STIFF_DQ3:
            return (f"the joints are stiffer than measured (e q^2 = {eq2:.3g}, delta q^3 = "
                    f"{dq3:.3g}; measured up to {STIFF_EQ2:g} and {STIFF_DQ3:g}; "
                    "docs/stiff_chain.md)")
    return None


def is_stiff(chain: ChainConfig) -> bool:
    """Whether the chain's joints have springs or dampers (the stiff theory applies)."""
    return chain.bending_stiffness > 0.0 or chain.bending_damping > 0.0


def stiff_scales(ref: LaunchReference, chain: ChainConfig) -> tuple[float, float]:
    """``(e q^2, delta q^3)``: the joints' stiffness and damping over the vertex's bend."""
    from chainfountain.theory.stiff import scaled_damping, scaled_stiffness

    L, lam = chain.link_length, chain.linear_density
    e = scaled_stiffness(chain.bending_stiffness, L, lam, ref.v)
    delta = scaled_damping(chain.bending_damping, L, lam, ref.v)
    return e * ref.q**2, delta * ref.q**3


def flight_length(ref: LaunchReference) -> float:
    """Arc length of the catenary from the launch point to the landing point (m)."""
    a = math.acosh(1.0 + ref.q * ref.h)
    b = math.acosh(1.0 + ref.q * (ref.h + ref.H))
    return (math.sinh(a) + math.sinh(b)) / ref.q


def step_term(ref: LaunchReference, dt: float) -> float:
    """``q*v*dt*Tbar_E/(k/q)``: the vertex's turn in one step over its distance from
    critical tension, times the floor pull (item 2 of the module docstring)."""
    return ref.q * ref.v * dt * max(0.0, ref.TE_bar) / (ref.k / ref.q)


def links_in_flight(ref: LaunchReference, link_length: float) -> int:
    """Links on the catenary from the launch to the landing point (at least 1)."""
    return max(1, round(flight_length(ref) / link_length))


def wall_cost(links: int, dt: float, iterations: int) -> float:
    """Estimated wall seconds per simulated second on one core (the cost model)."""
    return links * (C_LINK + C_ITER * iterations) / dt


def iterations_needed(links: int, dt: float) -> int:
    """Fewest iterations (at least :data:`MIN_ITERATIONS`) at which the solver converges
    on ``links`` links in flight at step ``dt`` (item 1 of the module docstring)."""
    reach = N_SOLVER * (DT0 / dt) ** 0.6
    return max(MIN_ITERATIONS, math.ceil(10.0 * (links / reach) ** 2))


def estimate(ref: LaunchReference, s: Settings, chain: ChainConfig | None = None,
             machine: bool = False) -> Estimate:
    """The model's errors, bounds and cost for fountain ``ref`` at settings ``s`` (with
    ``chain``'s joints: a stiff chain's margin is :data:`STIFF_MARGIN`; for an ideal
    machine's flight, ``machine``, :data:`IDEAL_STEP` and :data:`IDEAL_MARGIN` besides)."""
    margin = STIFF_MARGIN if chain is not None and is_stiff(chain) else MARGIN
    n = links_in_flight(ref, s.link_length)
    conv = s.iterations >= iterations_needed(n, s.dt)
    qL = ref.q * s.link_length
    Lh = s.link_length / ref.h
    step = step_term(ref, s.dt)
    errors = {f: A_L[f] * qL + A_H[f] * Lh for f in FIGURES}
    bounds = {f: abs(errors[f]) + margin[f] + C_STEP[f] * step for f in FIGURES}
    if machine:
        bounds = {f: b + IDEAL_STEP[f] * s.dt / DT0 + IDEAL_MARGIN[f]
                  for f, b in bounds.items()}
    return Estimate(settings=s, links=n, converged=conv, errors=errors, bounds=bounds,
                    cost=wall_cost(n, s.dt, s.iterations))


def candidates(ref: LaunchReference, chain: ChainConfig | None = None,
               machine: bool = False) -> list[Estimate]:
    """Every candidate setting in the model's range, each at the fewest iterations that
    converge (with ``chain``'s joints, an ideal machine's flight: :func:`estimate`; an
    ideal machine's links no longer than :data:`MACHINE_MAX_LINK`)."""
    out = []
    for mm in LINKS_MM:
        L = mm / 1000.0
        if ref.q * L > MAX_QL or (machine and L > MACHINE_MAX_LINK + 1e-12):
            continue
        n = links_in_flight(ref, L)
        for us in STEPS_US:
            dt = us * 1e-6
            it = iterations_needed(n, dt)
            if it > MAX_ITERATIONS:
                continue
            out.append(estimate(ref, Settings(L, dt, it), chain, machine))
    return out


class OutOfReach(ValueError):
    """No setting in the model's range reaches the accuracy asked for; ``best`` is the
    smallest bound it reaches (``inf`` outside its domain)."""

    def __init__(self, message: str, best: float = math.inf) -> None:
        super().__init__(message)
        self.best = best


def choose(ref: LaunchReference, accuracy: float, chain: ChainConfig | None = None,
           machine: bool = False) -> Estimate:
    """The cheapest settings whose every bound is at most ``accuracy`` (relative), for a
    chain with ``chain``'s joints (``machine``: an ideal machine's flight).

    Raises :class:`OutOfReach` (with the best reachable bound) when no candidate does, or
    when the fountain is outside the model's domain."""
    why = in_domain(ref, chain)
    if why is not None:
        raise OutOfReach(f"the error model does not apply: {why}")
    cands = candidates(ref, chain, machine)
    ok = [e for e in cands if e.worst <= accuracy]
    if not ok:
        best = min((e.worst for e in cands), default=math.inf)
        reach = f"{best:.2%}" if math.isfinite(best) else "none"
        raise OutOfReach(f"no link length and step in the model's range reach {accuracy:.2%} "
                         f"(best: {reach})", best)
    return min(ok, key=lambda e: e.cost)


def catenary_config(ref: LaunchReference, s: Settings, lam: float = 0.05) -> SimConfig:
    """The motor-fed level of fountain ``ref`` at settings ``s``, started on its predicted
    catenary (the runs the model is fitted and checked on)."""
    return SimConfig(
        kind="feed", gravity=ref.g,
        chain=ChainConfig(link_length=s.link_length, linear_density=lam,
                          link_radius=min(ChainConfig().link_radius, 0.4 * s.link_length)),
        feed=FeedConfig(speed=ref.v, launch_angle=ref.alpha0, drop=ref.H,
                        end_tension=max(0.0, ref.TE_bar),
                        floor_width=max(1.0, 2.5 * ref.landing_x)),
        solver=SolverConfig(dt=s.dt, iterations=s.iterations),
        initial=InitialConfig(mode="catenary"),
    )
