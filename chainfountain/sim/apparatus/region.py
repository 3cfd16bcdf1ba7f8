"""Where the contact machines form from rest and hold: their measured start regions.

**A gripped fold** started from rest (``initial.mode = "stub"``, the starter of
:mod:`.starter`) launches the chain's head onto the predicted fountain's end, has the end
guide catch it and threads it round the folding roller. Whether that works depends on
the fountain it is built for through one number, how near it is to critical,

    Q = Tbar_E + k H,  k = g / v**2

(``v`` = ``apparatus.speed``, the speed the end guide is placed for; the paper needs
``Q < 1`` for a fountain at all), and on the launch angle. Measured on
``apparatus_fold_gripped`` from rest, two starts each, 30 s (``chainfountain sweep
research/contact_region/fold_drop.toml``, ``fold_speed``, ``fold_angle``;
docs/apparatus.md, "Where the machines start from rest"): over the drop 0.3-0.625 m at
3 m/s and the speed 2.6-3.6 m/s at 0.5 m, every start with ``Q`` from 0.606 to 0.796
formed and held, whichever of the two moved it. At ``Q`` 0.594 and below (a wide, high
fountain) the launched head stores up to 1.36 times the fountain's length, the fountain
lands beyond the end guide's mouth and the run ends within 1.8 s (both starts); at 0.824
one start lost the chain at 2.7 s and the other still swung at 30 s; at 0.878 and 0.896
both lost it (too narrow a fountain: the slow launch leaves it too little chain to
stand). Over the launch angle at the shipped ``Q`` (0.715), 40-70 deg held both starts;
35 deg lost one (it ran away at 7.7 s), 75 deg swung 1-8 % below the law at 30 s, 80 deg
lost both. Settings drawn at random inside those bands (``research/contact_region/
draws.py``) showed that the start speed matters beyond ``Q``: above 3.2 m/s four of four
lost the chain. Every field measured alone holds over its band, but drawn all at once
over their whole bands some starts fail (3-4 of 30, scattered), so a start from rest is
admitted only in the inner half of each band (:data:`FROM_REST_MARGIN`):
:data:`FROM_REST_Q`, :data:`FROM_REST_SPEED`, :data:`FROM_REST_ANGLE`, the other fields'
:data:`FROM_REST_RANGE` and the carts' bands, at the tables they were measured with
(:data:`FROM_REST_TABLES`); at the special case's level tables the same, with links up to
21 mm (:data:`SPECIAL_LINKS`).

**The floor machine** from rest stops where its cart holds the chain back too hard, as
it does when the cart is changed live: :func:`floor_problem` refuses what
:func:`~chainfountain.sim.apparatus.laws.floor_runs_on` does not admit (measured from rest,
``research/contact_region/floor_drop.toml``: a drop of 0.25 m with the 9-g cart stopped at
12.6 and 12.9 s; 0.4-0.85 m held); its launch angle is held to :data:`FLOOR_ANGLE`, its
start speed short of a near-critical launch (:data:`FLOOR_START_Q`) and its upper table
above the launch (:data:`FLOOR_XI2_MIN`).

**The rest of the build.** The chain's links, friction and joints, the rollers and the
treadmill were swept one at a time (:data:`FROM_REST_RANGE`, :data:`FLOOR_FROM_REST_RANGE`);
a gripped fold's brake, bearing drag, tracks and carts range where
:func:`~chainfountain.sim.apparatus.laws.fold_runs_on` holds against its preset's balance
(:attr:`Bands.carts`), the floor's cart, track, drag and upper table where
:func:`~chainfountain.sim.apparatus.laws.floor_runs_on` does; every other field is
admitted only as built (:mod:`.builds`, :func:`pinned`).

``apparatus.start_region = "unchecked"`` runs a start outside these regions, for a study
of the regions themselves.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, NamedTuple

from chainfountain.fields import get_value, set_value
from chainfountain.sim.apparatus import builds
from chainfountain.sim.apparatus.builds import off_build

if TYPE_CHECKING:
    from chainfountain.sim.config import SimConfig

FROM_REST_MARGIN = 0.5
"""The part of each measured band a gripped fold from rest is admitted in: every band
(:data:`MEASURED_Q`, :data:`MEASURED_SPEED`, :data:`MEASURED_ANGLE`,
:data:`MEASURED_RANGE` and the carts' bands of
:func:`~chainfountain.sim.apparatus.laws.fold_runs_on`) shrunk by this factor towards the
shipped presets' value (:data:`SHIPPED`). Each band was measured with the other fields
at the build (or, for the geometry and carts, drawn together); with every field drawn at
once over its whole band, 26 of 30 starts of ``apparatus_fold_gripped`` and 27 of 30 of
``apparatus_special_gripped`` held 30 s, the failures scattered over the fields (the
folding roller rolling backwards, a runaway, a lost catch 2.5-18 s in;
``python -m research.contact_region.draws PRESET --n 30 --seed 101``). Inside the inner
half (``--seed 202``) 29 of 30 of ``apparatus_fold_gripped`` and 30 of 30 of
``apparatus_special_gripped`` held; the one failure (the folding roller rolling
backwards at 19.4 s, friction 1.27, 61.7 deg, a stiffness of 4.4e-6 N m/rad) is marginal:
moved back to the shipped value, any one of eight fields alone lets it hold. With 150
draws each (``--n 150``): ``apparatus_fold_gripped`` 150 of 150 (seed 303);
``apparatus_special_gripped`` 146 of 150 (seed 303, every failure with links over
21.4 mm: :data:`SPECIAL_LINKS`), then 150 of 150 inside its narrower link band (seed
404)."""

SHIPPED: dict[str, float] = {
    "q": 0.715, "apparatus.speed": 3.0, "apparatus.launch_angle": math.pi / 3.0,
    "apparatus.swing_damper": 0.5, "chain.friction": 0.6, "chain.link_length": 0.02,
    "apparatus.roller_radius": 0.03, "apparatus.fold_roller_radius": 0.1,
    "apparatus.plate_links": 20, "chain.bending_stiffness": 0.0,
    "chain.bending_damping": 0.0}
"""The gripped presets' values (both alike; ``q``: ``Tbar_E + g H/v**2``), about which
the admitted bands lie (:data:`FROM_REST_MARGIN`)."""


def _inner(path: str, band: tuple[float, float]) -> tuple[float, float]:
    """``band`` shrunk by :data:`FROM_REST_MARGIN` towards :data:`SHIPPED`'s ``path``."""
    lo, hi, mid = band[0], band[1], SHIPPED[path]
    out = (mid - FROM_REST_MARGIN * (mid - lo), mid + FROM_REST_MARGIN * (hi - mid))
    if isinstance(lo, int) and isinstance(hi, int):
        return (math.floor(out[0] + 0.5), math.floor(out[1] + 0.5))  # type: ignore[return-value]
    return (float(f"{out[0]:.6g}"), float(f"{out[1]:.6g}"))


MEASURED_Q = (0.606, 0.796)
"""The band of ``Q = Tbar_E + g H / v**2`` in which every measured gripped fold formed from
rest and held 30 s, the rest as built (two starts each; the nearest failures: 0.594 below,
0.824 above)."""

MEASURED_ANGLE = (math.radians(40.0), math.radians(65.0))
"""The launch angles (rad) at which a gripped fold from rest held. Along the angle alone,
at the shipped ``Q`` of 0.715 and 3 m/s, 40-70 deg held both starts (the nearest failures:
35 and 75 deg); with the drop and speed drawn at random inside their bands, one start at
69 deg lost the chain at 2.3 s, so the band stops at 65."""

MEASURED_SPEED = (2.7, 3.2)
"""The start speeds (m/s, ``apparatus.speed``) at which a gripped fold from rest held.
Along the speed alone at 0.5 m, 2.8-3.2 m/s held; with the drop drawn to keep ``Q`` in its
band, every start at 2.72-3.18 m/s held and four of four at 3.23-3.37 m/s lost the chain
within 2.4 s (the end guide, placed for a fountain faster than the one the carts and brake
select, about 3 m/s, misses it or loses it at the hand-over)."""

FROM_REST_Q = _inner("q", MEASURED_Q)
"""The admitted band of ``Q`` (:data:`FROM_REST_MARGIN` of :data:`MEASURED_Q`)."""
FROM_REST_ANGLE = _inner("apparatus.launch_angle", MEASURED_ANGLE)
"""The admitted launch angles (rad; :data:`FROM_REST_MARGIN` of :data:`MEASURED_ANGLE`)."""
FROM_REST_SPEED = _inner("apparatus.speed", MEASURED_SPEED)
"""The admitted start speeds (m/s; :data:`FROM_REST_MARGIN` of :data:`MEASURED_SPEED`)."""

MEASURED_RANGE: dict[str, tuple[float, float]] = {
    "apparatus.swing_damper": (0.5, 1.5), "chain.friction": (0.3, 2.0),
    "chain.link_length": (0.015, 0.025), "apparatus.roller_radius": (0.02, 0.045),
    "apparatus.fold_roller_radius": (0.07, 0.13), "apparatus.plate_links": (10, 40),
    "chain.bending_stiffness": (0.0, 1e-5), "chain.bending_damping": (0.0, 1e-7)}
"""The bands of a gripped fold's other fields, besides its geometry and carts, in which
it held, each measured alone at the shipped geometry, two starts each, 30 s
(``research/contact_region/fold_*.toml``). The swing damper (N s/m): with none both starts
lost the chain at 20.8 and 22.4 s, at 0.1 one at 28.4 s and the other still swung 17 %
below the law; 0.5 (shipped), 1.0 and 1.5 held. The chain's friction: with none both lost
it at 5.7 s (the pick-up roller slips); 0.3, 0.6 (shipped), 1.2 and 2.0 held. Links of
15 and 25 mm (20 shipped) held at 3.01 and 2.95 m/s; a pick-up roller of 20 and 45 mm
(30) and a folding roller of 70 and 130 mm (100) held; treadmill plates of 10 and 40 links
(20) held. Joint resistance: a spring of 1e-5 N m/rad and a damper of 1e-7 N m s/rad held
at 2.99 m/s; from 1e-4 N m/rad and 1e-6 N m s/rad up (to 0.13 and 1e-5) every start lost
the head at 1.2-1.4 s, before the end guide caught it (the stiffened head flies at
1.9 m/s, not the 3 m/s the guide is placed for). The upper ends of the damper's and
friction's bands are their sliders' ends."""

FROM_REST_RANGE: dict[str, tuple[float, float]] = {
    path: _inner(path, band) for path, band in MEASURED_RANGE.items()}
"""The bands a gripped fold from rest is admitted in, besides its geometry and carts
(:data:`FROM_REST_MARGIN` of :data:`MEASURED_RANGE`)."""

class Bands(NamedTuple):
    """The bands a gripped fold from rest is admitted in, at one pair of table offsets."""

    q: tuple[float, float]
    speed: tuple[float, float]
    angle: tuple[float, float]
    preset: str
    """The shipped preset they were measured on."""
    carts: tuple[float, float] = (0.019, 0.311)
    """The preset's cart masses (kg), the balance its carts, brake and bearing drag range
    about (:func:`~chainfountain.sim.apparatus.laws.fold_runs_on`)."""
    ranges: dict[str, tuple[float, float]] | None = None
    """The preset's own bands of fields of :data:`FROM_REST_RANGE` (narrower there)."""

    def other_ranges(self) -> dict[str, tuple[float, float]]:
        """The bands of the fields besides geometry and carts: :data:`FROM_REST_RANGE`
        with :attr:`ranges` over it."""
        return {**FROM_REST_RANGE, **(self.ranges or {})}


SPECIAL_LINKS = (FROM_REST_RANGE["chain.link_length"][0], 0.021)
"""The link lengths (m) a gripped fold from rest at the special case's tables is admitted
with: links longer than 21 mm fail there. Of 150 settings drawn inside the inner half of
every band at once (``python -m research.contact_region.draws apparatus_special_gripped
--n 150 --seed 303``, 30 s from rest each), the four that failed (the folding roller
rolling backwards at 15.8, 23.0 and 27.7 s, a head lost at 1.2 s) had links of 21.4-22.5
mm, 4 of the 36 draws above 21.4 mm, none of the 114 below; the other fields of the
failures lay inside the held draws' spread. ``apparatus_fold_gripped``'s 150 draws of the
same seed held all 31 of theirs above 21.4 mm."""


FROM_REST_TABLES: dict[tuple[float, float], Bands] = {
    (0.5, 0.303): Bands(FROM_REST_Q, FROM_REST_SPEED, FROM_REST_ANGLE,
                        "apparatus_fold_gripped"),
    (0.5, 0.5): Bands(FROM_REST_Q, FROM_REST_SPEED, FROM_REST_ANGLE,
                      "apparatus_special_gripped", (0.019, 0.328),
                      {"chain.link_length": SPECIAL_LINKS}),
}
"""The table offsets ``(xi2, xi3)`` at which a gripped fold from rest was measured, and
its bands there; other offsets are refused (the carts are balanced, and the start
threads the head, for the tables the machine is built with). At the special case's
tables (``apparatus_special_gripped``) the same inner-half bands of drop, start speed and
launch angle hold: 150 settings drawn with every field at once
(``python -m research.contact_region.draws apparatus_special_gripped --n 60 --seed 505``
and ``--n 90 --seed 606``, 30 s from rest each) all held (145 steady), -3.9 ... +1.1 % of
the laws with the brake (mean -2.2 %, sd 0.7 %)."""


FLOOR_FROM_REST_KH = 0.595
"""The largest ``g (H + floor_depth)/v**2`` (at the speed this model's pick-up law gives)
admitted for the floor machine from rest, below the live limit
:data:`~chainfountain.sim.apparatus.laws.FLOOR_KH_MAX` (0.6). Measured from rest, three
starts each (seeds), 40 s, 5-s means: ``apparatus_floor`` at a drop of 0.3672 m (0.600)
held at 2.37-2.38 m/s in two starts while the third drifted from 2.38 to 2.25 m/s and was
still falling at 40 s; at 0.372 m (0.5955) all three held at 2.395-2.405 m/s, at 0.39 m
(0.580) at 2.497-2.502; ``apparatus_floor_heavy`` (0.593) held at 2.78-2.79 m/s in all
three."""

FLOOR_ANGLE = (math.radians(30.0), math.radians(75.0))
"""The launch angles (rad) at which the floor machine from rest is admitted. Along the
angle alone ``apparatus_floor`` formed and ran 30 s at 30-80 deg, two starts each
(``research/contact_region/floor_angle.toml``: 30-70 deg steady, 80 deg one start still
swinging at 30 s; lower and higher not measured); with every field drawn at once
(``python -m research.contact_region.draws apparatus_floor --n 150 --seed 303``, 30 s from
rest each) 4 of the 13 draws at 77-80 deg stopped 10.8-26.5 s in (the upper cart holding
the chain back harder than the pick-up pulls), none of the 137 below 77 deg: the band
stops at 75."""


FLOOR_START_Q = 0.97
"""The largest ``Tbar_E + g (H + floor_depth)/v0**2`` at the start speed ``v0``
(``apparatus.speed``: the fountain the starter launches, near critical as it nears 1)
admitted for the floor machine from rest. ``apparatus_floor_heavy`` (15-g cart, 0.5 m),
30 s from rest: at the level check's edge, 1 - 1e-9 (``v0 = sqrt(g H)``), it stopped 5 s
in, three starts of three in a real window; at 0.990 (2.226 m/s) two of three stopped at
5.1 s; at 0.969 (2.25 m/s) seeds 0-5 all held, and at 0.927 (2.3 m/s) seeds 0-5. The
lighter carts hold nearer: with every field drawn at once (the 300 draws of seeds 303 and
404, upper carts of 2.7-13.5 g) starts held up to 0.9991."""

FLOOR_XI2_MIN = 0.1
"""The least upper table offset ``xi2`` admitted for the floor machine from rest (its
largest is where :func:`~chainfountain.sim.apparatus.laws.floor_runs_on` holds). Measured:
0.1 held (``research/contact_region/floor_xi2.toml``, two starts), and every draw at
0.100-0.440 (seeds 303 and 404); at 0, in a real window, the chain ran on but never rose
above the launch point, so no fountain formed."""

FLOOR_FROM_REST_RANGE: dict[str, tuple[float, float]] = {
    "chain.link_length": (0.015, 0.025), "apparatus.roller_radius": (0.03, 0.045),
    "apparatus.plate_links": (20, 40), "chain.bending_stiffness": (0.0, 1e-4),
    "chain.bending_damping": (0.0, 1e-5), "chain.friction": (0.3, 2.0)}
"""The fields besides its geometry and cart a floor machine from rest is admitted within,
each measured alone at ``apparatus_floor``'s build, two starts each, 30 s
(``research/contact_region/floor_*.toml``; the cart, its track, the bearing drag and the
upper table's offset range where :func:`~chainfountain.sim.apparatus.laws.floor_runs_on`
holds, which predicted every one of those sweeps' outcomes). Links of 15 and 25 mm (20
shipped) held at 3.01 and 2.91 m/s; a pick-up roller of 45 mm held, of 20 mm one start
ran its roller into the channel at 5.7 s (the band stops at the shipped 30 mm); a
treadmill plate of 40 links held, of 10 both stopped at 4.0 s (the band stops at the
shipped 20). Joint springs of 1e-5 and 1e-4 N m/rad held steady at 2.95 and 2.93 m/s;
from 1e-3 to 0.03 every start ran 30 s but none settled (2.69-3.01 m/s, swinging); dampers
of 1e-7 to 1e-5 N m s/rad (the last the damper's step limit at this step) held steady,
slowed to 2.74 m/s at 1e-5. The chain's friction: 0.3, 1.2 and 2.0 (0.6 shipped) held at
3.04, 2.87 and 2.82 m/s."""


def applies(cfg: SimConfig) -> bool:
    """Whether ``cfg`` is a gripped fold started from rest, the machine the region was
    measured on."""
    a = cfg.apparatus
    return (a.variant == "fold" and a.fold_roller == "gripped"
            and cfg.initial.mode == "stub")


def cart_scale(cfg: SimConfig) -> float:
    """The factor a fold's carts' bands are shrunk by
    (:func:`~chainfountain.sim.apparatus.laws.fold_runs_on`): :data:`FROM_REST_MARGIN` for
    a gripped fold from rest whose region is checked, 1 otherwise."""
    checked = applies(cfg) and cfg.apparatus.start_region != "unchecked"
    return FROM_REST_MARGIN if checked else 1.0


def from_rest(cfg: SimConfig) -> bool:
    """Whether ``cfg`` is a contact machine started from rest whose start is checked here:
    a gripped fold (:func:`problem`) or the floor machine (:func:`floor_problem`)."""
    return applies(cfg) or (cfg.apparatus.variant == "floor" and cfg.initial.mode == "stub")


def start_q(cfg: SimConfig) -> float:
    """``Q = Tbar_E + g H / v**2`` of the fountain the machine is built for."""
    a = cfg.apparatus
    return float(a.end_tension) + float(cfg.gravity) * float(a.drop) / float(a.speed) ** 2


def problem(cfg: SimConfig) -> tuple[str, str] | None:
    """``(field, message)`` when a gripped fold from rest lies outside its measured start
    region (:data:`FROM_REST_SPEED`, :data:`FROM_REST_RANGE`, :data:`FROM_REST_ANGLE`,
    :data:`FROM_REST_Q`, checked in that order), the message naming the value
    and the admissible range at the other fields' values; ``None`` inside it, or when the
    region does not apply (:func:`applies`)."""
    if not applies(cfg) or cfg.apparatus.start_region == "unchecked":
        return None
    a, g = cfg.apparatus, float(cfg.gravity)
    found = _tables_problem(cfg) or off_build(cfg)
    if found is not None:
        return found
    band = bands(cfg)
    assert band is not None
    v_lo, v_hi = band.speed
    if not v_lo - 1e-9 <= a.speed <= v_hi + 1e-9:
        return ("apparatus.speed",
                f"{a.speed!r} m/s is outside the start speeds at which a gripped fold was "
                f"measured to form from rest and hold; allowed: {v_lo:g}-{v_hi:g} m/s, or "
                "initial.mode = 'catenary' (laid on its path)")
    found = _range_problem(cfg, band.other_ranges(), f"a gripped fold with these tables "
                           f"({band.preset})")
    if found is not None:
        return found
    found = _carts_problem(cfg, band)
    if found is not None:
        return found
    found = _angle_problem(a.launch_angle, band.angle, f"a gripped fold with these tables "
                           f"({band.preset})", "hold")
    if found is not None:
        return found
    q = start_q(cfg)
    q_lo, q_hi = band.q
    if q_lo - 1e-9 <= q <= q_hi + 1e-9:
        return None
    te, v, H = float(a.end_tension), float(a.speed), float(a.drop)
    short = q < q_lo
    why = ("too wide a fountain: it lands beyond the end guide" if short else
           "too near critical: too little chain to stand")
    drops = f"a drop of {max(q_lo - te, 0.0) * v * v / g:.4g}-{(q_hi - te) * v * v / g:.4g} m"
    s_lo = max(math.sqrt(g * H / (q_hi - te)), v_lo)
    s_hi = min(math.sqrt(g * H / (q_lo - te)), v_hi) if q_lo > te else v_hi
    speeds = f"a start speed of {s_lo:.4g}-{s_hi:.4g} m/s" if s_lo < s_hi else ""
    other = f" (or {speeds} at this drop)" if speeds else ""
    return ("apparatus.drop",
            f"{H!r} m is too {'short' if short else 'tall'} a drop for a gripped fold to "
            f"form from rest at apparatus.speed = {v:g} m/s ({why}); allowed: {drops} at "
            f"this speed{other}, or initial.mode = 'catenary' (laid on its path) "
            f"(Tbar_E + g*H/v^2 = {q:.3f} here, admitted {q_lo:.3f}-{q_hi:.3f})")


def _range_problem(cfg: SimConfig, ranges: dict[str, tuple[float, float]],
                   machine: str) -> tuple[str, str] | None:
    """``(field, message)`` for the first field of ``ranges`` outside its band."""
    for path, (least, most) in ranges.items():
        value = float(get_value(cfg, path))
        if not least - 1e-12 <= value <= most + 1e-12:
            return (path, f"{get_value(cfg, path)!r} is outside where {machine} was measured "
                    f"to form from rest and hold; allowed: {least:g}-{most:g}, or "
                    "initial.mode = 'catenary' (laid on its path)")
    return None


def _carts_problem(cfg: SimConfig, band: Bands) -> tuple[str, str] | None:
    """``(field, message)`` when a gripped fold's carts, brake and bearing drag push it off
    the balance of the preset its tables were measured on (:attr:`Bands.carts`; the bands
    of :func:`~chainfountain.sim.apparatus.laws.fold_runs_on`, measured from rest with the
    following end guide)."""
    import copy

    from chainfountain.sim.apparatus.laws import fold_runs_on

    balance = copy.deepcopy(cfg)
    for cart, mass in zip(balance.carts, band.carts, strict=True):
        cart.mass, cart.incline = mass, math.radians(30.0)
    balance.apparatus.fold_brake, balance.apparatus.bearing_drag = 1.0, 0.0
    if fold_runs_on(cfg, balance, FROM_REST_MARGIN):
        return None
    trial = copy.deepcopy(cfg)

    def runs(path: str, x: float) -> bool:
        set_value(trial, path, x)
        return fold_runs_on(trial, balance, FROM_REST_MARGIN)

    up, lo = (1e3 * m for m in band.carts)
    built = (f"the balance {band.preset} holds at ({up:g} and {lo:g} g on 30-deg tracks, a "
             "brake of 1 N*s/m, no bearing drag)")
    for path in _CART_PUSHES:  # the first field off the balance whose own span is found
        now, home = float(get_value(cfg, path)), float(get_value(balance, path))
        if abs(now - home) <= 1e-12 or not runs(path, home):
            set_value(trial, path, now)
            continue
        lo_x, hi_x = (_bisect(lambda x, p=path: runs(p, x), home, end) for end in
                      (max(0.0, home - 10.0 * abs(now - home)), home + 10.0 * abs(now - home)))
        return (path, f"{now!r} pushes the gripped fold too far from {built} for a start "
                f"from rest (the carts' measured bands, laws.fold_runs_on); allowed: "
                f"{lo_x:.4g}-{hi_x:.4g} with the other fields as they are, or initial.mode = "
                "'catenary' (laid on its path)")
    return ("carts[1].mass", f"{cfg.carts[1].mass!r} kg with the upper cart at "
            f"{cfg.carts[0].mass:g} kg pushes the gripped fold too far from {built} for a "
            "start from rest; allowed: the carts within their bands of it (the window's cart "
            "sliders span them), or initial.mode = 'catenary' (laid on its path)")


_CART_PUSHES = ("apparatus.fold_brake", "apparatus.bearing_drag", "carts[1].incline",
                "carts[0].incline", "carts[1].mass", "carts[0].mass")
"""The fields that move a fold's net push (:func:`_carts_problem` names the first one off
its balance)."""


def _bisect(ok: Callable[[float], bool], inside: float, outside: float) -> float:
    """The last value from ``inside`` (accepted) towards ``outside`` that ``ok`` accepts."""
    if ok(outside):
        return outside
    for _ in range(40):
        mid = 0.5 * (inside + outside)
        inside, outside = (mid, outside) if ok(mid) else (inside, mid)
    return inside


def bands(cfg: SimConfig) -> Bands | None:
    """:data:`FROM_REST_TABLES`' bands for ``cfg``'s table offsets (``None``: none
    measured)."""
    a = cfg.apparatus
    return next((b for (xi2, xi3), b in FROM_REST_TABLES.items()
                 if abs(a.xi2 - xi2) <= 1e-9 and abs(a.xi3 - xi3) <= 1e-9), None)


def pinned(cfg: SimConfig) -> dict[str, float]:
    """Every number a contact machine from rest is admitted only at, with its value: its
    build's (:mod:`.builds`); empty where no region applies."""
    if not from_rest(cfg) or cfg.apparatus.start_region == "unchecked":
        return {}
    out = {path: float(v) for path, v in builds.pinned(cfg).items()
           if not isinstance(v, (str, bool))}
    return out


def _tables_problem(cfg: SimConfig) -> tuple[str, str] | None:
    """``(field, message)`` when a gripped fold from rest has table offsets at which it was
    not measured (:data:`FROM_REST_TABLES`)."""
    a = cfg.apparatus
    if bands(cfg) is not None:
        return None
    known = " or ".join(f"xi2 = {xi2:g} with xi3 = {xi3:g} ({b.preset})"
                        for (xi2, xi3), b in FROM_REST_TABLES.items())
    path = "apparatus.xi2" if all(abs(a.xi2 - x) > 1e-9 for x, _ in FROM_REST_TABLES) \
        else "apparatus.xi3"
    return (path, f"{get_value(cfg, path)!r}: a gripped fold was measured to form from rest "
            f"and hold only with the tables at {known}; allowed: those, or initial.mode = "
            "'catenary' (laid on its path)")


def _angle_problem(angle: float, band: tuple[float, float], machine: str,
                   holds: str) -> tuple[str, str] | None:
    """``(field, message)`` when the launch ``angle`` (rad) lies outside ``band``."""
    lo, hi = band
    if lo - 1e-9 <= angle <= hi + 1e-9:
        return None
    return ("apparatus.launch_angle",
            f"{angle!r} rad ({math.degrees(angle):.1f} deg) is outside where {machine} was "
            f"measured to form from rest and {holds}; allowed: {lo:.4f}-{hi:.4f} rad "
            f"({math.degrees(lo):.0f}-{math.degrees(hi):.0f} deg), or initial.mode = "
            "'catenary' (laid on its path)")


def floor_problem(cfg: SimConfig) -> tuple[str, str] | None:
    """``(field, message)`` when a contact floor machine started from rest would stop: the
    speed its cart selects by this model's pick-up law leaves ``g (H + floor_depth)/v**2``
    above :data:`FLOOR_FROM_REST_KH`
    (:func:`~chainfountain.sim.apparatus.laws.floor_runs_on`; measured from rest,
    ``research/contact_region/floor_drop.toml``: ``apparatus_floor`` with a drop of 0.25 m
    stopped at 12.6 and 12.9 s, two starts; nearer the limit, :data:`FLOOR_FROM_REST_KH`).
    ``None`` when it runs on, or for other machines."""
    from chainfountain.sim.apparatus.laws import floor_runs_on, floor_speeds

    a = cfg.apparatus
    if (a.variant != "floor" or cfg.initial.mode != "stub" or not cfg.carts
            or a.start_region == "unchecked"):
        return None
    found = (off_build(cfg) or _range_problem(cfg, FLOOR_FROM_REST_RANGE, "the floor machine")
             or _angle_problem(a.launch_angle, FLOOR_ANGLE, "the floor machine", "run on")
             or _floor_start_problem(cfg))
    if found is not None:
        return found
    if floor_runs_on(cfg, FLOOR_FROM_REST_KH):
        return None
    if cfg.carts[0].incline < 0.0:
        return None  # refused by the cart check with its own reason
    v = floor_speeds(cfg)[0]
    g, depth = float(cfg.gravity), float(a.floor_depth)
    kh = g * (a.drop + depth) / (v * v) if math.isfinite(v) and v > 0 else math.inf
    least, most = _edge(cfg, "drop", 20.0), _edge(cfg, "mass", 0.0)
    speed = f"{v:.3g} m/s" if math.isfinite(v) else "none"
    drop = f" or a drop of at least {least:.4g} m with this cart" if least is not None else ""
    cart = (f"an upper cart of at most {1e3 * most:.4g} g at this drop"
            if most is not None else "a lighter upper cart")
    return ("carts[0].mass",
            f"{cfg.carts[0].mass!r} kg ({1e3 * cfg.carts[0].mass:.3g} g) with a drop of "
            f"{a.drop:g} m: this model's pick-up selects {speed}, g*(H + floor_depth)/v^2 = "
            f"{kh:.3g}, and above {FLOOR_FROM_REST_KH:g} a start from rest slows and may "
            "stop (measured); "
            f"allowed: {cart}{drop}")


def _floor_start_problem(cfg: SimConfig) -> tuple[str, str] | None:
    """``(field, message)`` when a floor machine from rest starts too slow for its drop
    (:data:`FLOOR_START_Q`) or with its upper table too near the launch
    (:data:`FLOOR_XI2_MIN`)."""
    a = cfg.apparatus
    if a.xi2 < FLOOR_XI2_MIN - 1e-12:
        return ("apparatus.xi2", f"{a.xi2!r} puts the upper table too near the launch for the "
                "floor machine to form a fountain from rest (measured: at 0 the chain never "
                f"rose above the launch); allowed: at least {FLOOR_XI2_MIN:g}, or "
                "initial.mode = 'catenary' (laid on its path)")
    g, fall = float(cfg.gravity), float(a.drop) + float(a.floor_depth)
    q = float(a.end_tension) + g * fall / float(a.speed) ** 2
    if q <= FLOOR_START_Q + 1e-12:
        return None
    least = math.sqrt(g * fall / (FLOOR_START_Q - float(a.end_tension)))
    return ("apparatus.speed",
            f"{a.speed!r} m/s is too slow a start for the floor machine to form from rest "
            f"over a drop of {a.drop:g} m (Tbar_E + g*(H + floor_depth)/v0^2 = {q:.4g}, "
            f"near critical; measured to hold up to {FLOOR_START_Q:g}); allowed: a start "
            f"speed of at least {least:.4g} m/s, or initial.mode = 'catenary' (laid on its "
            "path)")


def _edge(cfg: SimConfig, what: str, far: float) -> float | None:
    """The drop (``what = "drop"``, m; the least) or the upper cart's mass (``"mass"``, kg;
    the most) at which :func:`~chainfountain.sim.apparatus.laws.floor_runs_on` holds with
    ``cfg``'s other fields, by bisection towards ``far``; ``None`` if none does."""
    import copy

    from chainfountain.sim.apparatus.laws import floor_runs_on

    trial = copy.deepcopy(cfg)

    def runs(x: float) -> bool:
        if what == "drop":
            trial.apparatus.drop = x
        else:
            trial.carts[0].mass = x
        return floor_runs_on(trial, FLOOR_FROM_REST_KH)

    bad = float(cfg.apparatus.drop) if what == "drop" else float(cfg.carts[0].mass)
    good = far
    if not runs(good):
        return None
    for _ in range(40):
        mid = 0.5 * (bad + good)
        bad, good = (bad, mid) if runs(mid) else (mid, good)
    return good
