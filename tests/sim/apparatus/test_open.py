"""The apparatus level kind, variant 'open' (paper: no deceleration after landing).

What is asserted is what the simulation does (``docs/apparatus.md``, "Open
variant"). The turn after landing is a frictionless joint guide (slide joints to
the centre of the end channel's bend, then plate grooves), the tail slides away
horizontally. Over the first 0.8 s (the run later loses its catch, see the docs):

- the falling chain is caught and turned cleanly: the tension at the mouth is
  the weight of the chain hanging in the turn, ``Tbar_E = g*R*(1 - cos alphaE)/v**2``
  (+ the end pull, zero here): a steady chain along a frictionless path, the
  paper's Eq. for the tension along the fountain continued into the guide;
- the fountain carries ``Tbar_0 - Tbar_E = k*H``;
- the moving mass grows at ``lambda*v/2`` (the roller rolls up resting chain at
  ``v_R = v/2``; the tail grows at ``v``, the plate strand shrinks at ``v/2``),
  and the speed does not change: ``M(t) dv/dt = lambda g (y_up - y_lo) - T_exit(v)``
  vanishes at the selected speed, which depends on the drop and the cart only,
  so it is the floor preset's (same drop 0.35 m, same cart);
- the lower plate's reaction grows as the chain moving away, ``lambda g v`` per second.

The guided links (tail grooves, turn) are read exactly, with the energy budget's impulse
sweep (neglecting their shear reads ``Tbar_0 - Tbar_E`` 0.47 and the exit tension 0.342).

With the upper joint guide the energy budget (:func:`~chainfountain.sim.budget.open_windows`,
an exact impulse sweep from the lumped tail's end to the upper plate) finds where the
drive goes: the turn after landing loses a growing share, and the chain's acceleration
is the momentum law's with that loss taken off (docs/apparatus.md, "Open variant: where
the drive goes"). The loss-free law misses it.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus_report import report
from chainfountain.sim.budget import open_windows
from tests import shipped
from tests.sim.apparatus.runs import load_on_path

LEVEL = shipped.path("apparatus_open")
FLOOR = shipped.path("apparatus_floor")
RUN = 2.2
FLOOR_SPEED = 2.929
"""Measured speed of ``apparatus_floor`` with the channel's walls (same chain, cart and
drop; docs/apparatus.md)."""


pytestmark = pytest.mark.xdist_group("apparatus_open")
"""The module-scoped run is computed once, on one worker (``--dist loadgroup``)."""


def open_sim(upper_guide: str) -> Simulation:
    """The shipped preset ``apparatus_open`` (its upper channel the walls), or with
    another upper guide."""
    cfg = io.load(LEVEL).sim
    a = dataclasses.replace(cfg.apparatus, upper_guide=upper_guide)
    return Simulation(dataclasses.replace(cfg, apparatus=a))


def test_open_preset_is_the_floor_presets_chain_and_cart() -> None:
    """The preset is the floor preset's chain, roller, cart and drop to the outgoing
    strand: ``xi2`` raised so that the drop to the turn's exit equals the floor preset's
    drop to its floor (0.35 m), so it selects the same speed. It starts at 2.92 m/s (the
    floor preset's speed with the walls, FLOOR_SPEED: the floor preset now uses the joint
    guide, which runs 2 % faster, and starts at 2.98)."""
    cfg, floor = io.load(LEVEL).sim, load_on_path(FLOOR).sim
    assert cfg.chain == floor.chain and cfg.carts == floor.carts
    a, f = cfg.apparatus, floor.apparatus
    assert (a.variant, a.upper_guide, a.plate_links) == ("open", "walls", 0)
    app = Simulation(cfg).apparatus
    assert app.y_up - app.y_lo == pytest.approx(f.drop * (1.0 - f.xi2), abs=0.005)  # 0.352


SEEDS = (0, 1, 2, 3)
"""The run is chaotic: each test reads the mean over these nudged starts
(:meth:`Simulation.nudge`) against a tolerance that takes in the single runs' spread.
Over 8 starts (sd of one run): the fountain's ``Tbar_0 - Tbar_E - k*H`` 0.023, the plate
reaction's rate in the last third 2.5 %, the exit tension 0.004, the speed's drift
0.4 %/s; everything else below 1 %."""


@dataclasses.dataclass
class OpenRun:
    sim: Simulation
    rec: Recorder
    masses: np.ndarray  # (t, moving mass) every 0.1 s

    def report(self, start: float, end: float) -> dict:
        return report(self.sim, self.rec, start, end)


@pytest.fixture(scope="module")
def runs() -> list[OpenRun]:
    out = []
    for seed in SEEDS:
        sim = open_sim("walls")
        if seed:
            sim.nudge(seed)
        rec = Recorder(sim, profiles=False)
        masses = []
        while sim.time < RUN - 1e-9:
            sim.advance(0.1)
            masses.append((sim.time, sim.apparatus.moving_mass(0.5)))
        out.append(OpenRun(sim, rec, np.array(masses)))
    return out


def mean(values) -> float:
    return float(np.mean(list(values)))


@pytest.mark.slow
def test_open_guide_catches_the_chain(runs) -> None:
    for r in runs:
        app = r.sim.apparatus
        assert app.variant == "open" and app.guided and app.lower is None
        assert app.tail_grooved >= 25 and app.tail_mass > 0.05  # the tail slides away (lumped)


@pytest.mark.slow
def test_open_end_tension_is_the_weight_in_the_turn(runs) -> None:
    """Over 0.1-0.8 s, while the turn loses little: measured 0.139 against 0.144 (one
    start; 8 starts differ by 0.006). Later the turn's growing loss lowers it (0.086 over
    0.8-1.5 s, 0.047 over 1.5-2.2 s; a dissipating segment lowers the tension entering it
    by ``D/v``; docs/apparatus.md, "Open variant: where the drive goes")."""

    def excess(r: OpenRun) -> float:
        app = r.sim.apparatus
        m = r.report(0.1, 0.8)["measured"]
        drop = app.guide_radius * (1.0 - math.cos(app.alphaE))
        return m["TE_bar"] - r.sim.config.gravity * drop / m["v"] ** 2

    assert mean(excess(r) for r in runs) == pytest.approx(0.0, abs=0.04)


@pytest.mark.slow
def test_open_fountain_carries_kH(runs) -> None:
    """``Tbar_0 - Tbar_E = k*H`` within 0.06 (as for the fold presets) over 0.1-2.2 s:
    one start reads 0.627 against 0.584; 8 starts give -0.035 ... +0.035 about ``k*H``,
    mean +0.004."""
    dev = [r.report(0.1, RUN)["measured"] for r in runs]
    assert mean(m["T0_bar"] - m["TE_bar"] - m["kH"] for m in dev) == pytest.approx(0.0,
                                                                                 abs=0.06)


@pytest.mark.slow
def test_open_moving_mass_grows_at_half_the_chain_speed(runs) -> None:
    for r in runs:
        lam = r.sim.config.chain.linear_density
        v = float(np.mean([s.v for s in r.rec.apparatus_samples if s.t >= 0.1]))
        rate = float(np.polyfit(r.masses[:, 0], r.masses[:, 1], 1)[0])
        assert rate == pytest.approx(0.5 * lam * v, rel=0.05)  # 8 starts: +0.2 ... +0.8 %


@pytest.mark.slow
def test_open_exit_tension_is_the_rig_laws(runs) -> None:
    """The pick-up's exit tension, read through the turn, the flight and the channel's
    corrected contacts from the tail's end, is the rig law's at the measured speed and
    cart within two sigma of the law (its 0.002 and a single rig run's scatter 0.0065):
    one start reads 0.377 against 0.378 over 0.1-2.2 s; 8 starts -0.005 ... +0.007."""

    def dev(r: OpenRun) -> float:
        rep = r.report(0.1, RUN)
        m, o = rep["measured"], rep["open"]
        lam = r.sim.config.chain.linear_density
        return m["T_pickup_exit_bar"] - o["exit_tension_rig_N"] / (lam * m["v"] ** 2)

    assert abs(mean(dev(r) for r in runs)) <= 2.0 * math.hypot(0.002, 0.0065)


@pytest.mark.slow
def test_open_plate_reaction_grows_with_the_tail(runs) -> None:
    """The paper's point of the arrangement: "the reaction force change is exactly known
    over time". The lower plate carries the chain moving away, so its reaction grows at
    ``lambda g v``: one start 1.421 against 1.422 N/s over 0.1-2.2 s (Theil-Sen slope;
    least squares 1.377, pulled by single-sample spikes, see below), within the 5 % the
    issue sets for rates. Read exactly from the grooves' impulses (the budget's sweep),
    the lumped tail included."""
    rates = []
    for r in runs:
        o = r.report(0.1, RUN)["open"]
        first, last = o["tail_reaction_N"]
        assert last > 10.0 * first > 0.0
        rates.append(o["tail_reaction_rate_N_per_s"] / o["tail_reaction_rate_predicted"])
    assert mean(rates) == pytest.approx(1.0, rel=0.05)


@pytest.mark.slow
@pytest.mark.parametrize("start, end", [(0.1, 0.8), (0.8, 1.5), (1.5, 2.2)])
def test_open_plate_reaction_rate_in_each_third(runs, start, end) -> None:
    """The rate holds in each third of the run, also while the turn's loss grows: over 8
    starts -1.1 ... +1.0 %, -1.2 ... +0.1 % and -3.1 ... +5.3 % (Theil-Sen; the last
    third's single samples spike by up to +-2 N once the fountain lands off the turn's
    circle, after about 1.3 s)."""
    rates = []
    for r in runs:
        o = r.report(start, end)["open"]
        rates.append(o["tail_reaction_rate_N_per_s"] / o["tail_reaction_rate_predicted"])
    assert mean(rates) == pytest.approx(1.0, rel=0.05)


@pytest.mark.slow
def test_open_speed_is_the_floor_presets(runs) -> None:
    v = mean(r.report(0.1, RUN)["measured"]["v"] for r in runs)
    assert v == pytest.approx(FLOOR_SPEED, rel=0.02)  # 8 starts: -0.9 ... -0.04 %


@pytest.mark.slow
def test_open_speed_falls_where_the_loss_free_balance_says_it_rises(runs) -> None:
    """The loss-free momentum balance with the measured exit tension (the rig law's)
    predicts +1.1 %/s; the chain slows, -1.0 +- 0.2 %/s over 8 starts (-1.5 ... -0.1 %/s):
    the turn after landing loses a growing share of the drive (budget tests below;
    docs/apparatus.md). The mean of the starts is more than 1 %/s below the law."""
    drift = mean(r.report(0.1, RUN)["measured"]["speed_drift_per_s"] for r in runs)
    assert drift < 0.011 - 0.01


BUDGET_WINDOWS = (0.6, 1.4, 0.4)
"""Start, end and width (s) of the budget's windows: after the start-up (over 0.2-0.6 s
the chain gains 0.044 m/s^2 more than the law with the loss says, not understood; docs),
before the fountain leaves the catch (about 2 s with the joint guide)."""
A_FIT_SIGMA = 0.015
"""Standard error (m/s^2) of a 0.4-s window's speed slope: the strand speed's residual
about the fit is 9-12 mm/s with a correlation time of about 10 ms (measured sampling
every 2 ms), so about 40 independent samples over 0.115 s of spread in time."""


@pytest.fixture(scope="module")
def budget_run():
    sim = open_sim("joints")
    return sim, open_windows(sim, *BUDGET_WINDOWS)


@pytest.mark.slow
def test_open_budget_sweep_is_exact(budget_run) -> None:
    """The sweep closes through the lumped tail (its end link heavier), the turn's slide
    joints and the grooves: the free links' rotation residual stays at rounding."""
    _, windows = budget_run
    assert len(windows) == 2
    for w in windows:
        assert w.budget.steps > 300 and w.budget.exact


@pytest.mark.slow
def test_open_deceleration_is_the_measured_loss(budget_run) -> None:
    """``M dv/dt = F_drive - T_exit(v) - D/v`` with the rig law's exit tension and the
    budget's loss ``D`` gives the measured acceleration within three sigma in each window;
    sigma combines the slope's error and the rig law's single-run scatter (0.0065
    ``lambda v**2``). Over 8 nudged starts the first window reads -0.022 or -0.002 m/s^2
    (two outcomes) against -0.043 or -0.038, the second -0.18 ... -0.12 against -0.15 ...
    -0.13. The loss-free law (+0.032 / +0.036) misses the second window by more than
    three sigma in every start (0.16-0.21 m/s^2): the chain slows because of the loss."""
    sim, windows = budget_run
    lam = sim.config.chain.linear_density
    for w in windows:
        sigma = math.hypot(A_FIT_SIGMA, 0.0065 * lam * w.v**2 / w.mass)
        assert abs(w.a_measured - w.a_law_loss) <= 3.0 * sigma
    late = windows[-1]
    assert late.a_law - late.a_measured > 3.0 * math.hypot(
        A_FIT_SIGMA, 0.0065 * lam * late.v**2 / late.mass)


@pytest.mark.slow
def test_open_turn_takes_a_growing_loss(budget_run) -> None:
    """The turn after landing loses most, and more as the run goes on (8 starts: 0.040-0.046
    of 0.062-0.067, then 0.125-0.150 of 0.170-0.184 ``lambda v**3``): its loss lowers the
    mouth tension, the fountain widens and lands further into the turn, off its circle
    (docs)."""
    _, (w1, w2) = budget_run
    assert w2.budget.region("turn") > 2.0 * w1.budget.region("turn")
    assert w2.budget.region("turn") > 0.5 * w2.budget.total
