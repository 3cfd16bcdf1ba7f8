"""Pick-up and put-down by a roller rolling on a resting chain (paper section
"Pick-Up and Pull-Down Forces"), measured with :mod:`research.rigs.pickup`.

What is asserted is the measured law (see ``docs/apparatus.md``), not a fit. The strand
tension is read from the solver's pivot impulses (:attr:`RigResult.pivot_bar`). The
reading summed through the contacts (:attr:`RigResult.force_bar`) takes out pymunk's stale
impulses of contacts that touch again (left in, they make a cart force look fully passed
on) and agrees with it (``test_contact_reading_corrects_retouching_contacts``).

- roller speed ``v_R = v/(1 + cos(alpha))`` (paper) within 3 %;
- pick-up force: equals the paper's ``lambda*v^2/(1 + cos(alpha))`` only at
  alpha = 90 deg (within 10 %); at 0 and 45 deg it is close to the loss-free
  energy balance (:func:`lossless_bar`, about half the paper's value) and far
  below the paper. The remaining excess at 0 deg (about +13 % with 1 cm links
  on a 3 cm roller, +9 % with 5 mm links) shrinks with the link length;
- a cart force ``F_c`` on the roller raises the strand tension by ``F_c*v_R/v =
  F_c/2`` (slope 1/2 within 10 %), the loss-free power balance, not by ``F_c`` as the
  paper assumes;
- put-down needs a forward push; extrapolated to zero push it gives a quarter of
  ``lambda*v^2`` (the loss-free energy balance), not the paper's half, and at 0, 45
  and 90 deg it follows the loss-free energy balance within 5 %.
"""

from __future__ import annotations

import math

import pytest

from research.rigs.pickup import RigConfig, RigResult, lossless_bar, run_rig

pytestmark = pytest.mark.slow  # half a minute of rig runs (a research rig, not the package)

LAM, V = 0.05, 5.0
_cache: dict[tuple, RigResult] = {}


def _run(mode: str, alpha_deg: float, f_bar: float) -> RigResult:
    cfg = RigConfig(mode=mode, angle=math.radians(alpha_deg), speed=V,
                    cart_force=f_bar * LAM * V * V)
    return run_rig(cfg, duration=0.6, settle=0.25)


def rig(mode: str, alpha_deg: float, f_bar: float = 0.0) -> RigResult:
    key = (mode, alpha_deg, f_bar)
    if key not in _cache:
        _cache[key] = _run(mode, alpha_deg, f_bar)
    return _cache[key]


@pytest.mark.parametrize("alpha", [0.0, 45.0, 90.0])
def test_pickup_roller_speed_is_paper_kinematics(alpha: float) -> None:
    r = rig("pickup", alpha)
    # at 90 deg (quarter wrap, roller as fast as the chain) the strand leans back by
    # about 4 deg and reads 2 % fast along the nominal direction
    assert r.speed == pytest.approx(V, rel=0.03)
    assert r.roller_ratio == pytest.approx(1.0 / (1.0 + math.cos(math.radians(alpha))), rel=0.03)
    assert math.degrees(abs(float(r.alpha.mean()) - math.radians(alpha))) < 5.0


def test_pickup_force_at_90_deg_matches_paper() -> None:
    r = rig("pickup", 90.0)
    assert r.pivot_bar == pytest.approx(r.paper_bar, rel=0.10)


@pytest.mark.parametrize("alpha,tol", [(0.0, 0.15), (45.0, 0.10)])
def test_pickup_force_below_paper_near_energy_balance(alpha: float, tol: float) -> None:
    r = rig("pickup", alpha)
    a = math.radians(alpha)
    assert r.pivot_bar < 0.7 * r.paper_bar  # the paper's law is off by far more than 10 %
    assert r.pivot_bar == pytest.approx(lossless_bar("pickup", a), rel=tol)


def test_cart_force_adds_half_to_the_tension() -> None:
    """The power balance of a rolling pulley: the cart is pulled at ``v_R = v/2``, so the
    strand pays ``F_c*v_R`` (measured slope 0.49; the paper's 1 is off by half)."""
    base, pulled = rig("pickup", 0.0), rig("pickup", 0.0, 0.5)
    slope = (pulled.pivot_bar - base.pivot_bar) / 0.5
    assert slope == pytest.approx(0.5, rel=0.10)
    assert pulled.roller_ratio == pytest.approx(0.5, rel=0.03)


def test_putdown_needs_push_and_gives_a_quarter() -> None:
    lo, hi = rig("putdown", 0.0, 0.1), rig("putdown", 0.0, 0.5)
    for r in (lo, hi):
        assert r.roller_ratio == pytest.approx(0.5, rel=0.03)
    slope = (hi.pivot_bar - lo.pivot_bar) / 0.4
    intercept = lo.pivot_bar - 0.1 * slope
    # paper: 0.5 + F_c; loss-free energy balance: 0.25 + F_c/2 (measured 0.244 + 0.50 F_c)
    assert intercept == pytest.approx(0.25, rel=0.15)
    assert slope == pytest.approx(0.5, rel=0.10)


@pytest.mark.parametrize("alpha", [0.0, 45.0, 90.0])
def test_putdown_follows_the_energy_balance(alpha: float) -> None:
    """Measured 0.402 / 0.536 / 1.331 against 0.400 / 0.519 / 1.300 at ``F_c = 0.3``."""
    r = rig("putdown", alpha, 0.3)
    assert r.pivot_bar == pytest.approx(lossless_bar("putdown", math.radians(alpha), 0.3),
                                        rel=0.05)


def test_contact_reading_corrects_retouching_contacts(monkeypatch) -> None:
    """pymunk keeps a contact that stops touching for ``collision_persistence`` steps (3);
    when it touches again, its accumulated impulse starts from the old value, which was
    not applied in this step (no warm start on a first contact) but is reported by
    ``Arbiter.total_impulse``. With a cart pressing the roller, links touch the roller
    again and again. ``ChainReader.arm`` captures those starting impulses in a pre-solve
    callback, so the reading through the contacts is the pivot reading (0.5263 and
    0.5263 at ``F_c = 0.5``). Without it the contacts overstate the strand tension
    (0.73 against 0.53); the capture only reads: the pivot reading is the same to the
    last digit."""
    from chainfountain.sim.measure import ChainReader

    r = rig("pickup", 0.0, 0.5)
    assert r.force_bar == pytest.approx(r.pivot_bar, abs=0.002)
    monkeypatch.setattr(ChainReader, "arm", lambda self: None)
    raw = _run("pickup", 0.0, 0.5)
    assert raw.force_bar - raw.pivot_bar > 0.1
    assert raw.pivot_bar == r.pivot_bar


def test_rig_refuses_to_run_out_of_chain() -> None:
    from research.rigs.pickup import RollerRig

    rig = RollerRig(RigConfig(rest_length=0.2))
    with pytest.raises(RuntimeError, match="resting chain is used up"):
        for _ in range(4000):
            rig.step()


def test_grooved_feed_holds_the_strand_until_the_roller() -> None:
    """Put-down with the apparatus's feed: strand links run on the
    groove line (``clearance`` above the roller-top centre line) without shapes, and each
    leaves its groove, shape back, once it is ``release`` links from the roller's top."""
    from chainfountain.sim.config import ChainConfig, SolverConfig
    from research.rigs.pickup import RollerRig

    ch = ChainConfig(link_length=0.02, linear_density=0.05, friction=0.6, link_radius=0.002)
    cfg = RigConfig(mode="putdown", speed=3.0, cart_force=0.4 * 0.05 * 9.0, chain=ch,
                    solver=SolverConfig(dt=5e-4, iterations=10, joint_error_bias=1e-10,
                                        collision_slop=1e-4),
                    feed="groove", clearance=0.002)
    rig = RollerRig(cfg)
    released = 0
    first = rig._fed[0][0] if rig._fed else None
    for _ in range(400):  # 0.2 s: about 15 links pass the release point
        rig.step()
        if first is not None and all(lk is not first for lk, _ in rig._fed):
            released += 1
            first = rig._fed[0][0] if rig._fed else None
    assert released >= 10 and len(rig._fed) >= 3
    y_line = 3 * rig.rho + 2 * cfg.radius + cfg.clearance
    x_top = rig.roller.position.x
    for link, _ in rig._fed:
        assert link.body.position.y == pytest.approx(y_line, abs=1e-4)
        assert link.body.position.x - x_top > cfg.release * rig.L
        assert link.shape.space is None
    grooved = {id(lk) for lk, _ in rig._fed}
    free = [lk for lk in rig.chain.links[:rig.n_free] if id(lk) not in grooved]
    assert all(lk.shape.space is not None for lk in free)
    assert abs(float(rig.carriage.velocity.x)) == pytest.approx(1.5, rel=0.05)


@pytest.mark.parametrize("bad", [dict(feed="rail"), dict(feed="groove", mode="pickup"),
                                 dict(feed="groove", mode="putdown", angle=0.5)])
def test_grooved_feed_refuses_other_geometries(bad: dict) -> None:
    from research.rigs.pickup import RollerRig

    with pytest.raises(ValueError, match="feed"):
        RollerRig(RigConfig(**bad))
