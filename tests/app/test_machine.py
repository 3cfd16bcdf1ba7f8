"""The window's side of the ideal machines (no window): sliders that span only where the
machine runs, a loss-free machine's upper cart that follows, and the laws' prediction in
the readout."""

from __future__ import annotations

import pytest

from chainfountain.app import controls, spans
from chainfountain.app.panel import tooltip as _tooltip
from chainfountain.app.readout import machine_line
from chainfountain.app.session import Session
from chainfountain.level import io
from chainfountain.level.model import Level
from chainfountain.study.changes import with_changes
from chainfountain.theory import apparatus as ap
from tests import shipped


@pytest.fixture(autouse=True)
def _home(tmp_path, monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))


def _spec(level, path):
    return controls.spec_for(level.sim, path)


def test_a_carts_slider_spans_where_the_machine_runs_and_no_further(level) -> None:
    """``ideal_fold``'s lower cart: every value in the span loads, a little beyond either
    end is refused by the level check or the window's budget."""
    lvl = level("ideal_fold")
    origin = level("ideal_fold").sim
    spec = _spec(lvl, "feed.lower_cart_force")
    lo, hi = spans.admissible(lvl, spec, origin)
    assert 0.0 <= lo < lvl.sim.feed.lower_cart_force < hi < spec.hi
    ok = spans._accepts(lvl, spec.path, origin)
    for x in (lo, 0.5 * (lo + hi), hi):
        assert ok(x)
    width = hi - lo
    assert not ok(hi + 0.01 * width)
    if lo > 0.0:
        assert not ok(lo - 0.01 * width)
    narrowed = spans.narrowed(lvl, spec, origin)
    assert (narrowed.slider_lo, narrowed.slider_hi, narrowed.log) == (lo, hi, False)


def _loss_free_special() -> io.Level:
    lvl = shipped.level("ideal_special")
    lvl.sim.feed.bearing_drag, lvl.sim.feed.cart_force = 0.0, lvl.sim.feed.lower_cart_force
    return lvl


def test_a_loss_free_machines_upper_cart_has_one_value() -> None:
    lvl = _loss_free_special()
    from chainfountain.sim.kinds.ideal.checks import BALANCE_TOLERANCE

    lo, hi = spans.admissible(lvl, _spec(lvl, "feed.cart_force"))
    tol = BALANCE_TOLERANCE * 0.05 * 9.81 * 1.0  # the check's tolerance, lambda g H units
    assert lo <= lvl.sim.feed.cart_force <= hi and hi - lo <= 2.0 * tol * 1.0001


def test_motor_levels_keep_their_schema_sliders(level) -> None:
    lvl = level("classroom")
    spec = _spec(lvl, "feed.speed")
    assert spans.narrowed(lvl, spec) is spec


def test_the_upper_cart_follows_a_typed_offset_and_the_message_says_so(level) -> None:
    """Bearing drag typed to 0 makes the special case loss-free: the upper cart moves to the
    balance (the lower cart's 0.183 N), and with it when xi3 is typed."""
    s = Session(level("ideal_special"))
    res = s.set_field("feed.bearing_drag", 0.0)
    assert res.ok and "the upper cart follows to 0.183 N" in res.message, res.message
    res = s.set_field("feed.xi3", 0.6)
    assert res.ok and res.live, res.message
    F = ap.balanced_cart_force(0.183, 0.5, 0.6, 0.05, 1.0, 9.81)
    assert s.value("feed.cart_force") == pytest.approx(F)
    assert s.sim.config.feed.cart_force == pytest.approx(F)
    assert f"the upper cart follows to {F:.4g} N" in res.message
    refused = s.set_field("feed.cart_force", 0.2)
    assert not refused.ok and "does not balance" in refused.message


def test_the_readout_gives_the_laws_prediction(level) -> None:
    s = Session(level("ideal_fold"))
    assert machine_line(s.sim) == "paper's laws: v 5.000 m/s, Tbar_0 0.736, Tbar_E 0.344"
    s2 = Session(_loss_free_special())
    assert machine_line(s2.sim).startswith("paper's laws keep any v: Tbar_0 0.")
    assert machine_line(Session(level("classroom")).sim) == ""


def test_the_contact_floor_machines_sliders_span_where_its_chain_runs_on(level) -> None:
    """``apparatus_floor``: the upper cart, bearing drag and offset span where this model's
    pick-up law leaves the chain running (``floor_runs_on``; its measured limit and what
    happens beyond: ``tests/sim/apparatus/test_live_cart.py``); the cart's span ends
    just above the heavy preset's 15 g. The near-critical fountain-D presets, set beyond
    it on purpose, keep the schema's sliders."""
    from chainfountain.sim.apparatus.laws import floor_runs_on

    lvl = level("apparatus_floor")
    for path in spans.FLOOR_FIELDS:
        spec = _spec(lvl, path)
        lo, hi = spans.admissible(lvl, spec, lvl.sim)
        assert lo <= controls.get_value(lvl.sim, path) < hi
        ok = spans._accepts(lvl, path, lvl.sim, floor_runs_on)
        assert ok(hi) and not ok(hi + 0.01 * (hi - lo))
    lo, hi = spans.admissible(lvl, _spec(lvl, "carts[0].mass"), lvl.sim)
    assert 0.015 < hi < 0.016
    b_lo, b_hi = spans.admissible(lvl, _spec(lvl, "carts[0].incline"), lvl.sim)
    # holding back, up to 57 deg (from rest: g (H + d)/v^2 <= region.FLOOR_FROM_REST_KH)
    assert b_lo == pytest.approx(0.0, abs=1e-8) and 0.99 < b_hi < 1.01
    typed = level("apparatus_floor")  # 30 g typed: it runs, and stops
    typed.sim.carts[0].mass = 0.03  # the span stays (its handle at the end)
    assert spans.admissible(typed, _spec(typed, "carts[0].mass"), lvl.sim) == (lo, hi)
    d = level("apparatus_fountain_d")
    assert spans.admissible(d, _spec(d, "carts[0].mass"), d.sim) is None


def test_the_contact_fold_machines_carts_span_their_measured_band(level) -> None:
    """``apparatus_special`` and ``apparatus_fold``: each cart spans the part of its balance
    that held every time it was changed live, with the other cart as it is
    (``laws.FOLD_CART_BAND`` and the net push ``FOLD_PUSH_BAND``: at the build, upper
    17-18.83 g, lower 57-59 g and 40-42 g; the upper cart 1 g heavier takes the lower's
    span's bottom to 0.5 g below the build, by the net push); the bearing drag and the
    inclines span where the carts' push stays in its band; a span's ends are where
    ``fold_runs_on`` stops holding; a cart so far off that the other has no span leaves it
    the span of the level as built; the limit case (no lower cart) keeps the schema's
    slider."""
    from chainfountain.sim.apparatus.laws import fold_runs_on

    for name, lower in (("apparatus_special", (0.057, 0.059)),
                        ("apparatus_fold", (0.040, 0.042))):
        lvl = level(name)
        for path, want in (("carts[0].mass", (0.017, 0.0175 + 1.0 / 750)),
                           ("carts[1].mass", lower)):
            lo, hi = spans.admissible(lvl, _spec(lvl, path), lvl.sim)
            assert (lo, hi) == pytest.approx(want, abs=1e-9)
            i = spans.FOLD_FIELDS.index(path)
            for m, runs in ((lo, True), (hi, True), (lo - 1e-5, False), (hi + 1e-5, False)):
                cand = level(name)
                cand.sim.carts[i].mass = m
                assert fold_runs_on(cand.sim, lvl.sim) is runs
        moved = level(name)
        moved.sim.carts[0].mass = 0.0185
        built = lvl.sim.carts[1].mass  # net push -2 g + 1.5 * 1 g: 0.5 g below the build
        assert spans.admissible(moved, _spec(moved, "carts[1].mass"), lvl.sim) == \
            pytest.approx((built - 0.0005, lower[1]), abs=1e-9)
        moved.sim.carts[0].mass = 0.03  # typed beyond: the lower cart keeps the built span
        assert spans.admissible(moved, _spec(moved, "carts[1].mass"), lvl.sim) == \
            pytest.approx(lower, abs=1e-9)
        assert spans.admissible(lvl, _spec(lvl, "carts[0].mass"), None) is None
        # a bearing drag counts as c*v/2 on each cart: at most 0.0026 N s/m (0.005 stopped
        # every measured run); an incline moves a cart's force like its mass does
        lo, hi = spans.admissible(lvl, _spec(lvl, "apparatus.bearing_drag"), lvl.sim)
        assert lo == 0.0 and 0.0025 < hi < 0.0027
        lo, hi = spans.admissible(lvl, _spec(lvl, "carts[1].incline"), lvl.sim)
        assert lo < lvl.sim.carts[1].incline < hi and hi - lo < 0.05
        for incline in (0.0, -0.5):  # typed: a level or reversed track moves no span
            moved.sim.carts[1].incline = incline
            assert spans.admissible(moved, _spec(moved, "carts[1].mass"), lvl.sim) == \
                pytest.approx(lower, abs=1e-9)
        for path in spans.FOLD_OFFSETS:  # balanced for its own offsets only
            built = controls.get_value(lvl.sim, path)
            assert spans.admissible(moved, _spec(moved, path), lvl.sim) == (built, built)
        tip = _tooltip(spans.narrowed(lvl, _spec(lvl, "carts[1].mass"), lvl.sim))
        assert (f"spans {lower[0] * 1e3:g}-{lower[1] * 1e3:g} g, where this machine keeps "
                "running") in tip
    limit = level("apparatus_limit")
    assert spans.admissible(limit, _spec(limit, "carts[0].mass"), limit.sim) is None


@pytest.mark.parametrize("follow, upper, lower", [
    (2.0, (0.0135, 0.023), (0.3085, 0.326)),  # from rest: half laws.FOLLOW_CART_BAND
    (0.0, (0.017, 0.020), (0.309, 0.316)),  # a fixed end guide: laws.BRAKED_CART_BAND
])
def test_the_braked_gripped_folds_carts_span_where_it_keeps_running(level,
        follow: float, upper: tuple[float, float], lower: tuple[float, float]) -> None:
    """``apparatus_fold_gripped`` (19 / 311 g): with its end guide following the landing,
    from rest, upper 13.5-23 g and lower 308.5-326 g, the inner half
    (region.FROM_REST_MARGIN) of the measured band where every pair held from rest
    (upper 8-27 g and lower 306-341 g, but upper 8 g with 306 g: laws.FOLLOW_LIGHT_CORNER);
    with the guide fixed, laid on its path, upper 17-20 g and lower 309-316 g (where the
    fountain still lands in the catch). The upper cart 1 g lighter moves the lower's span
    down by 1.5 g; the brake spans where the carts' push stays in its band; the window
    shows a brake slider for it and none for a contact fold."""
    from chainfountain.sim.apparatus import region
    from chainfountain.sim.apparatus.laws import fold_runs_on

    def load() -> Level:
        laid = {} if follow else {"initial.mode": "catenary", "apparatus.starter": 0.0}
        return with_changes(level("apparatus_fold_gripped"),  # a fixed guide: measured laid
                            {"apparatus.end_follow": follow, **laid})

    lvl = load()
    for path, want in (("carts[0].mass", upper), ("carts[1].mass", lower)):
        lo, hi = spans.admissible(lvl, _spec(lvl, path), lvl.sim)
        assert (lo, hi) == pytest.approx(want, abs=1e-9)
        i = spans.FOLD_FIELDS.index(path)
        for m, runs in ((lo, True), (hi, True), (lo - 1e-5, False), (hi + 1e-5, False)):
            cand = load()
            cand.sim.carts[i].mass = m
            assert fold_runs_on(cand.sim, lvl.sim, region.cart_scale(cand.sim)) is runs
    moved = load()
    moved.sim.carts[0].mass = 0.018
    assert spans.admissible(moved, _spec(moved, "carts[1].mass"), lvl.sim) == \
        pytest.approx((lower[0], lower[1] - 0.0015), abs=1e-9)
    # 1 N s/m of brake at 3 m/s is 1.5 N off the lower cart's push (about 300 g): the
    # brake spans the lower cart's band over v/2 (7 g and 35 g of push: 0.023 and 0.114 N s/m)
    lo, hi = spans.admissible(lvl, _spec(lvl, "apparatus.fold_brake"), lvl.sim)
    push = (lower[1] - lower[0]) * 9.81 * 0.5
    assert lo < 1.0 < hi and hi - lo == pytest.approx(push / 1.5, rel=1e-6)
    paths = {s.path for s in controls.control_fields(lvl.sim)}
    assert "apparatus.fold_brake" in paths and "apparatus.fold_clearance" not in paths
    contact = level("apparatus_fold")
    assert "apparatus.fold_brake" not in {s.path for s in controls.control_fields(contact.sim)}


@pytest.mark.parametrize("upper, lower, runs", [
    (0.008, 0.301, False), (0.008, 0.306, False), (0.008, 0.311, True),
    (0.013, 0.301, False), (0.013, 0.306, True), (0.019, 0.306, True),
])
def test_both_gripped_fold_carts_far_lighter_at_once_are_outside_the_spans(level,
        upper: float, lower: float, runs: bool) -> None:
    """Both carts much lighter than 19 / 311 g at once lost the chain from rest (upper 8 g
    with lower 306 g in one of three starts; laws.FOLLOW_LIGHT_CORNER), where each alone,
    and 8 g with 311 g or 13 g with 306 g, kept it: the pair is outside the measured band.
    From rest the sliders span its inner half, and each follows the other's: the lower at
    308.5 g (its lowest), the upper starts at 14.75 g; the upper at 13.5 g (its lowest),
    the lower starts at 311 g."""
    from chainfountain.sim.apparatus.laws import fold_runs_on

    lvl = level("apparatus_fold_gripped")
    cand = level("apparatus_fold_gripped")
    cand.sim.carts[0].mass, cand.sim.carts[1].mass = upper, lower
    assert fold_runs_on(cand.sim, lvl.sim) is runs
    cand.sim.carts[0].mass, cand.sim.carts[1].mass = 0.019, 0.3085
    lo, _ = spans.admissible(cand, _spec(cand, "carts[0].mass"), lvl.sim)
    assert lo == pytest.approx(0.01475, abs=1e-9)
    cand.sim.carts[0].mass, cand.sim.carts[1].mass = 0.0135, 0.311
    lo, _ = spans.admissible(cand, _spec(cand, "carts[1].mass"), lvl.sim)
    assert lo == pytest.approx(0.311, abs=1e-9)


def test_the_readout_gives_the_speed_a_braked_fold_selects(level) -> None:
    """``v = 2 (F_lc + lambda g H (1 - xi2 - xi3) - F_uc)/c`` with the preset's numbers
    (19 g and 311 g on 30-deg tracks, brake 1 N s/m): 2.961 m/s."""
    s = Session(level("apparatus_fold_gripped"))
    g, lam, H = 9.81, 0.05, 0.5
    F = [m * g * 0.5 for m in (0.019, 0.311)]
    v = 2.0 * (F[1] + lam * g * H * (1.0 - 0.5 - 0.303) - F[0]) / 1.0
    assert machine_line(s.sim) == f"the carts and the brake select {v:.2f} m/s by the paper's laws"
    s.sim.set_param("carts[0].mass", 0.4)  # holds the chain back: no speed
    assert "select no speed" in machine_line(s.sim)
