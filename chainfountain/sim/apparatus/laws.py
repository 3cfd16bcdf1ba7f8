"""The apparatus model's measured pick-up and put-down laws and its speed selection.

Figures of the rollers alone (the rigs of ``research/pickup_study.py``,
``docs/apparatus.md``), used to predict a run's speed and tensions (the report,
:mod:`chainfountain.sim.apparatus_report`; the energy budget,
:mod:`chainfountain.sim.budget`; the window's readout and the machines' slider spans,
:func:`floor_speeds`, :func:`floor_runs_on`, :func:`fold_cart_span`); the physics does
not read them.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from chainfountain.sim.config import SimConfig

PICKUP_BAR = 0.27
"""Measured pick-up force at alpha = 0 over ``lambda*v**2`` (``docs/apparatus.md``;
paper: 1/2, loss-free energy balance 1/4)."""
PUTDOWN_BAR = 0.24
"""Measured put-down force at alpha = 0 over ``lambda*v**2`` with a forward push,
extrapolated to no push (``docs/apparatus.md``; by pivots 0.244 + 0.50*Fbar_c, the
loss-free 1/4 + Fbar_c/2; paper: 1/2 + Fbar_c)."""

PICKUP_RIG_2CM = (0.266, 0.0230)
"""Pick-up exit tension at alpha = 0 with the presets' 2-cm links, ``(p_inf, R)`` of
``Tbar = p_inf + R/(lambda*v**2) + G*Fbar_c`` (``R`` in N, ``G`` :data:`CART_GAIN_2CM`);
the fit: docs/apparatus.md#pick-up-force."""
RIG_2CM_LAMBDA = 0.05
"""Linear density (kg/m) of the chain :data:`PICKUP_RIG_2CM` was measured with."""
PICKUP_RIG_2CM_ERR = 0.002
"""Standard uncertainty of :func:`pickup_rig_2cm` at 2.6-3.2 m/s (0.003 at 5.1 m/s;
docs/apparatus.md#pick-up-force)."""
CART_GAIN_2CM = 0.526
"""Rise of the pick-up exit tension per unit cart force in the same fit (the paper: 1;
the loss-free power balance ``F_c v_R/v``: 1/2)."""
CART_GAIN_2CM_ERR = 0.010

PUTDOWN_RIG_2CM = (0.172, 0.618)
"""Put-down (folding) entry tension at alpha = 0 with 2-cm links, ``Tbar = d + G_d*Fbar_c``
(intercept ``d``, cart gain ``G_d``), steady from ``Fbar_c`` of about 0.25; the fit:
docs/apparatus.md#put-down."""


def gripped_putdown(lc_bar: float, k: float, R: float) -> float:
    """The gripped folding roller's loss-free entry tension at ``alpha = 0``,
    ``Tbar = 1/4 + Tbar_lc/2 + k R`` (``R``: the chain's radius on the roller, which it
    descends twice; :mod:`~chainfountain.sim.apparatus.grip`). Measured in
    ``apparatus_fold`` with a 100-mm roller: 0.368 against 0.372 at 0.5 and 0.25 ms
    (``docs/apparatus.md``, "The gripped folding roller")."""
    return 0.25 + 0.5 * lc_bar + k * R


def pickup_rig_2cm(v: float) -> float:
    """:data:`PICKUP_RIG_2CM` at chain speed ``v`` (m/s), no cart: ``p_inf + R/(lambda
    v**2)``."""
    p_inf, R = PICKUP_RIG_2CM
    return p_inf + R / (RIG_2CM_LAMBDA * v * v)


def pickup_rig_2cm_drag(v: float, lam: float) -> float:
    """``d(p(v)*lambda*v**2)/dv`` of :data:`PICKUP_RIG_2CM` at speed ``v`` (N s/m): how
    fast the pick-up's exit tension rises with the chain speed, the cart aside. The
    rolling resistance does not depend on the speed, so this is ``2*p_inf*lambda*v``."""
    return 2.0 * PICKUP_RIG_2CM[0] * lam * v


def rig_exit_tension(v: float, lam: float, F_uc: float) -> float:
    """Pick-up exit tension (N) the 2 cm rig law gives at chain speed ``v`` (m/s), linear
    density ``lam`` and cart force ``F_uc`` (N): ``p(v) lambda v**2 + G F_uc``
    (:func:`pickup_rig_2cm`, :data:`CART_GAIN_2CM`; paper ``(1/2 + Tbar_uc) lambda v**2``)."""
    return pickup_rig_2cm(v) * lam * v * v + CART_GAIN_2CM * F_uc


def selected_speed(g: float, H: float, xi2: float, F_uc: float, lam: float,
                   p: float | None = None, gain: float = 1.0, dp: float = 0.0,
                   drag: float = 0.0) -> float:
    """Speed a free-ended ('floor', Tbar_E = 0) apparatus selects.

    Steady state needs the fountain's ``Tbar_0 = Tbar_E + k*H = k*H`` (paper: along
    the catenary ``Tbar_0 - Tbar_E = k*H``) to equal the mechanism's
    ``Tbar_0 = p + G*Tbar_uc + xi2*k*H`` (paper, apparatus section, with the pick-up
    intercept ``p`` and cart gain ``G``; paper ``p = 1/2``, ``G = 1``), so
    ``v**2 = (g*H*(1 - xi2) - G*F_uc/lambda)/p``. With ``p=None`` the rig law
    :func:`pickup_rig_2cm` ``+ dp`` is used, ``p_inf + dp + R/(lambda_rig v**2)``:
    ``v**2 = (g*H*(1 - xi2) - G*F_uc/lambda - R/lambda_rig)/(p_inf + dp)``. nan if
    there is no positive root.

    ``drag`` (``apparatus.bearing_drag`` c, N s/m) acts on the pick-up's carriage like
    more cart: ``F_uc + c*v/2`` at the roller's speed ``v/2``, so ``v`` is the positive
    root of ``p*v**2 + G*c/(2*lambda)*v - num = 0``.
    """
    num = g * H * (1.0 - xi2) - gain * F_uc / lam
    if p is None:
        p_inf, R = PICKUP_RIG_2CM
        num -= R / RIG_2CM_LAMBDA
        p = p_inf + dp
    if num <= 0 or p <= 0:
        return math.nan
    b = gain * drag / (2.0 * lam)
    return (math.sqrt(b * b + 4.0 * p * num) - b) / (2.0 * p)


FLOOR_KH_MAX = 0.6
"""Largest ``g*(H + floor_depth)/v**2`` at the speed :func:`floor_speeds` gives for which
the contact floor machine runs on: near the fountain's end (1) its speed falls ever
further below the law and the chain stops. Measured from ``apparatus_floor`` (9 g, law
3.071 m/s, 0.52) with the upper cart changed live at 8 s, speeds 5-30 s after: 15 g
(0.59; the shipped ``apparatus_floor_heavy``, 600 s held) steady; 20 g (0.67) wandering
2.45-2.58 m/s; 25 g (0.77) stopped within 7 s, 28 g within 6 s, 30 g within 5 s (from the
laid start changed at 1 s, 25 g ran at 2.29-2.37 m/s and stopped at 19.2 s, 28 and 30 g at
7.5 and 6.0 s). A bearing drag agrees: 0.02 N s/m (0.59) held 30 s 4-5 % below the
law, 0.05 (0.72) and 0.1 stopped (``docs/apparatus.md``, "Declared losses";
``tests/sim/apparatus/test_live_cart.py``)."""


_GRAM_AT_30 = 0.001 * 9.81 * 0.5
"""The force (N) of 1 g of cart on the presets' 30-deg tracks."""
FOLD_CART_BAND = ((-0.5 * _GRAM_AT_30, 1.5 * _GRAM_AT_30), (-1.0 * _GRAM_AT_30, _GRAM_AT_30))
"""How far the upper and the lower cart of a contact 'fold' machine can each move from
the balance the level was built with and the machine keep running: ``(lo, hi)`` in N of
cart force ``m*g*sin(beta)`` for each. Measured, not from a law (the paper's loss-free
machine has a single balance; this model's fold holds within a few grams of its own):
``python -m research.live_tuning LEVEL 'carts[i].mass' VALUES --starts 3 --after 40``,
each value set at 10, 10.7 and 11.4 s (three phases of the landing swing), then 40 s.
``apparatus_special`` (17.5 / 58 g): upper 16.5-19 g and lower 57-59.5 g held 3 of 3,
lower 56 g 2 of 3, lower 55 and 60 g none. ``apparatus_fold`` (17.5 / 41 g): upper
16.5-19 g and lower 39-42 g held 3 of 3, upper 16 g 2 of 3, lower 43 g 1 of 3 and 38 g
none. The band is the part that held every time in both (``docs/apparatus.md``,
"Tuning the damped folds live")."""
FOLD_UPPER_WEIGHT = 1.5
"""A gram off the upper cart counts as this many grams onto the lower one in the fold's
net push ``dF_lc - FOLD_UPPER_WEIGHT*dF_uc`` (:data:`FOLD_PUSH_BAND`). Measured with both
carts moved at once (``live_tuning.py ... --also 'carts[0].mass=M'``, 3 starts each):
``apparatus_special`` upper 17 g with lower 56 g held 3 of 3, with 59 g none; upper 19 g
with 56 g none, with 59 g 3 of 3; ``apparatus_fold`` upper 17 g with lower 39 g 3 of 3,
with 42 g 2 of 3; upper 19 g with 39 g none, with 42 g 3 of 3. The rig laws' gains (0.526
and 0.618) would give 0.85; the fold's own response to its carts is not the rigs'."""
FOLD_PUSH_BAND = (-2.0 * _GRAM_AT_30, _GRAM_AT_30)
"""Band (N) of the fold's net push from its balance, ``dF_lc - FOLD_UPPER_WEIGHT*dF_uc``,
within which every measured run kept going (:data:`FOLD_UPPER_WEIGHT`). A bearing drag
``c`` counts as ``c*v/2`` on each cart, and then allows ``c`` up to 0.0026 N s/m from the
build: measured, ``apparatus_special`` with 0.005, 0.01 and 0.02 N s/m held none of 3 runs
(``live_tuning.py apparatus_special apparatus.bearing_drag 0.005 0.01 0.02 --starts 3``),
``apparatus_fold`` 1 of 3 at 0.005 and none at 0.01 and 0.02."""


BRAKED_CART_BAND = ((-2.0 * _GRAM_AT_30, _GRAM_AT_30), (-2.0 * _GRAM_AT_30, 5.0 * _GRAM_AT_30))
"""How far the upper and the lower cart of a gripped 'fold' machine with a brake
(``apparatus.fold_brake``) can each move from the balance the level was built with and
the fountain still land in the end guide: ``(lo, hi)`` in N of cart force. The brake holds
the speed; the catch sets the band (docs/apparatus.md, "A brake that selects the speed").
Measured on a copy of ``apparatus_fold_gripped`` (19 / 311 g) with ``end_follow = 0``,
laid on its path (``python -m research.live_tuning COPY 'carts[i].mass' VALUES --laid --at 5
--after 30``, one start each): upper 17-20 g and lower 308-316 g held 30 s; upper 21 g and
lower 306 g lost the catch at 12.8 and 14.1 s."""
BRAKED_PUSH_BAND = (-2.0 * _GRAM_AT_30, 5.0 * _GRAM_AT_30)
"""Band (N) of a braked gripped fold's net push from its balance,
``dF_lc - FOLD_UPPER_WEIGHT*dF_uc``: a gram more on the upper cart lost the catch where
two more grams off the lower one did not (upper 21 g against lower 309 g), as in the
contact fold (:data:`FOLD_UPPER_WEIGHT`). Both carts moved at once were not measured."""

FOLLOW_CART_BAND = ((-11.0 * _GRAM_AT_30, 8.0 * _GRAM_AT_30),
                    (-5.0 * _GRAM_AT_30, 30.0 * _GRAM_AT_30))
"""As :data:`BRAKED_CART_BAND`, with an end guide that follows the landing
(``apparatus.end_follow``): the catch no longer sets the band, the landing swing does.
Measured on ``apparatus_fold_gripped`` (19 / 311 g, ``end_follow = 2``), each pair of
carts set in the level and started from rest, 30 s (``python -m research.fold_tuning``,
two starts each; docs/apparatus.md, "Tuning both carts"): every pair these bands allow
held both starts (15 pairs, lower carts 306-341 g); outside them, with lower carts of
296-301 g, 8 of 20 starts lost the chain 2-25 s in. The speed then spans 2.9-3.3 m/s."""
FOLLOW_PUSH_BAND = (-15.0 * _GRAM_AT_30, 30.0 * _GRAM_AT_30)
"""Band (N) of the net push ``dF_lc - FOLD_UPPER_WEIGHT*dF_uc`` with a following end
guide (upper 27 g with lower 306 g, outside it, held both starts from rest of
``research/fold_tuning.py``)."""
FOLLOW_LIGHT_CORNER = (2.0, -22.0 * _GRAM_AT_30)
"""``(c, m)``: with a following end guide, both carts lighter at once must keep
``dF_lc + c*dF_uc >= m`` (N): the two carts far below the level's together lose the
chain. Measured on ``apparatus_fold_gripped`` (19 / 311 g) from rest
(``python -m research.fold_tuning``, two starts each): upper 8 g with lower 296 g held
one start of two, with 301 g neither, with 306 and 311 g both; 13 g with 296 g neither,
with 301 g both. With the upper cart at 8 g the lower slider starts at 311 g, one grid
step inside the lightest pair that held."""


_Bands = tuple[tuple[tuple[float, float], tuple[float, float]], tuple[float, float], float,
               tuple[float, float] | None]


def _bands(cfg: SimConfig) -> _Bands:
    """The fold machine's measured bands: each cart's, the net push's, the upper cart's
    weight in it and the light corner's ``(c, m)`` or None (:data:`FOLD_CART_BAND`,
    :data:`FOLD_PUSH_BAND`, :data:`FOLD_UPPER_WEIGHT` for the contact fold;
    :data:`BRAKED_CART_BAND` and :data:`BRAKED_PUSH_BAND` for a gripped fold with a brake;
    :data:`FOLLOW_CART_BAND`, :data:`FOLLOW_PUSH_BAND` and :data:`FOLLOW_LIGHT_CORNER`
    when its end guide also follows the landing)."""
    a = cfg.apparatus
    if a.fold_roller == "gripped" and a.fold_brake > 0.0 and a.end_follow > 0.0:
        return FOLLOW_CART_BAND, FOLLOW_PUSH_BAND, FOLD_UPPER_WEIGHT, FOLLOW_LIGHT_CORNER
    if a.fold_roller == "gripped" and a.fold_brake > 0.0:
        return BRAKED_CART_BAND, BRAKED_PUSH_BAND, FOLD_UPPER_WEIGHT, None
    return FOLD_CART_BAND, FOLD_PUSH_BAND, FOLD_UPPER_WEIGHT, None


def _fold_offsets(cfg: SimConfig, balance: SimConfig) -> list[float]:
    """The two carts' forces (N) less ``balance``'s, a bearing drag ``c`` beyond
    ``balance``'s counted in as the carts (``c*v/2`` more holding the pick-up back, less
    pushing the fold on, at the level's start speed ``v``), and the fold's brake as less
    push."""
    g = float(cfg.gravity)
    half_v = 0.5 * float(balance.apparatus.speed)
    drag = half_v * (float(cfg.apparatus.bearing_drag) - float(balance.apparatus.bearing_drag))
    brake = half_v * (float(cfg.apparatus.fold_brake) - float(balance.apparatus.fold_brake))
    up, lo = (g * (c.mass * math.sin(c.incline) - r.mass * math.sin(r.incline))
              for c, r in zip(cfg.carts[:2], balance.carts[:2], strict=True))
    return [up + drag, lo - drag - brake]


def _scaled(bands: _Bands, scale: float) -> _Bands:
    """``bands`` shrunk by ``scale`` towards the balance (every offset, and the light
    corner's bound, times ``scale``)."""
    carts, pushes, w, corner = bands
    carts = tuple((scale * lo, scale * hi) for lo, hi in carts)  # type: ignore[assignment]
    pushes = (scale * pushes[0], scale * pushes[1])
    return carts, pushes, w, None if corner is None else (corner[0], scale * corner[1])


def fold_runs_on(cfg: SimConfig, balance: SimConfig, scale: float = 1.0) -> bool:
    """Whether a 'fold' machine's carts lie within their band of ``balance``'s (the level
    as built), each, and their net push within its band (:func:`_bands`), the bands shrunk
    by ``scale`` towards the balance (a start from rest: ``region.FROM_REST_MARGIN``)."""
    if len(cfg.carts) < 2 or len(balance.carts) < 2:
        return True
    carts, pushes, w, corner = _scaled(_bands(balance), scale)
    df = _fold_offsets(cfg, balance)
    for (lo, hi), d in zip(carts, df, strict=True):
        if not lo - 1e-12 <= d <= hi + 1e-12:
            return False
    if corner is not None and df[1] + corner[0] * df[0] < corner[1] - 1e-12:
        return False
    push = df[1] - w * df[0]
    return pushes[0] - 1e-12 <= push <= pushes[1] + 1e-12


def fold_cart_span(cfg: SimConfig, balance: SimConfig, i: int,
                   scale: float = 1.0) -> tuple[float, float] | None:
    """The masses (kg) of cart ``i`` (0 upper, 1 lower) of a 'fold' machine for which, the
    other cart as it is, :func:`fold_runs_on` holds; ``None`` when the other cart is so
    far off that none does, or the cart's track is level (its mass pushes nothing) or
    tilted the other way (only a negative mass would run). ``scale`` as in
    :func:`fold_runs_on`."""
    df = _fold_offsets(cfg, balance)
    carts, (a, b), w, corner = _scaled(_bands(balance), scale)
    lo, hi = carts[i]
    if i == 1:  # a <= d1 - w*d0 <= b
        lo, hi = max(lo, a + w * df[0]), min(hi, b + w * df[0])
    else:  # (d1 - b)/w <= d0 <= (d1 - a)/w
        lo, hi = max(lo, (df[1] - b) / w), min(hi, (df[1] - a) / w)
    if corner is not None:  # d1 + c*d0 >= m
        c, m = corner
        lo = max(lo, m - c * df[0]) if i == 1 else max(lo, (m - df[1]) / c)
    cart = cfg.carts[i]
    per_kg = float(cfg.gravity) * math.sin(cart.incline)  # N of cart force per kg
    if lo > hi + 1e-12 or abs(per_kg) < 1e-9:  # none runs, or the mass moves no force
        return None
    f_now = per_kg * cart.mass
    m_lo, m_hi = sorted(((f_now + lo - df[i]) / per_kg, (f_now + hi - df[i]) / per_kg))
    if m_hi <= 1e-6:  # only a negative mass would run
        return None
    return max(m_lo, 1e-6), m_hi


def floor_speeds(cfg: SimConfig) -> tuple[float, float]:
    """A contact 'floor' machine (``kind = "apparatus"``): the speed (m/s) its upper cart
    selects by this model's measured pick-up law (the 2 cm rig law and its cart gain, an
    ideal guide; :func:`selected_speed`) and by the paper's laws (``p = 1/2``, cart gain
    1: ``Tbar_0 = 1/2 + Tbar_uc + xi2*k*H`` meeting the free fountain's ``Tbar_0 = k*H``).
    A floor ``floor_depth`` below the end adds its drop; the bearing drag counts as more
    cart. nan where a law has no speed, and for the other variants."""
    a = cfg.apparatus
    if a.variant != "floor" or not cfg.carts:
        return math.nan, math.nan
    g, lam = float(cfg.gravity), float(cfg.chain.linear_density)
    H = float(a.drop) + float(a.floor_depth)
    xi2 = float(a.xi2) * float(a.drop) / H
    cart = cfg.carts[0]
    F_uc, c = cart.mass * g * math.sin(cart.incline), float(a.bearing_drag)
    return (selected_speed(g, H, xi2, F_uc, lam, gain=CART_GAIN_2CM, drag=c),
            selected_speed(g, H, xi2, F_uc, lam, 0.5, gain=1.0, drag=c))


def braked_fold_speed(cfg: SimConfig) -> float:
    """A 'fold' machine with a brake on its folding roller (``apparatus.fold_brake`` c > 0):
    the speed (m/s) its carts and brake select by the paper's laws. The paper's balance
    ``Tbar_uc = Tbar_lc + k H (1 - xi2 - xi3)`` holds at every speed; the brake takes
    ``c*v/2`` (the carriage rolls at ``v/2``) off the lower cart's push, so the balance
    holds at one speed, ``v = 2 (F_lc + lambda g H (1 - xi2 - xi3) - F_uc)/c``
    (:func:`~chainfountain.theory.apparatus.ideal_fold_speed` with a drag ``c/2`` on the
    chain's speed). Any bearing drag counts in with each carriage. nan without a brake,
    or where the carts hold the chain back."""
    from chainfountain.theory.apparatus import ideal_fold_speed

    a = cfg.apparatus
    if a.variant != "fold" or a.fold_brake <= 0.0 or len(cfg.carts) < 2:
        return math.nan
    g, lam = float(cfg.gravity), float(cfg.chain.linear_density)
    up, lo = cfg.carts[0], cfg.carts[1]
    F_uc = up.mass * g * math.sin(up.incline)
    F_lc = lo.mass * g * math.sin(lo.incline)
    drag = 0.5 * (float(a.fold_brake) + 2.0 * float(a.bearing_drag))
    return ideal_fold_speed(F_uc, F_lc, float(a.xi2), float(a.xi3), drag, lam,
                            float(a.drop), g)


def floor_runs_on(cfg: SimConfig, kh_max: float = FLOOR_KH_MAX) -> bool:
    """Whether a contact 'floor' machine's cart and drag leave it a speed by this model's
    law with ``g*(H + floor_depth)/v**2`` at most ``kh_max`` (:data:`FLOOR_KH_MAX`: the
    chain runs on), its cart holding the chain back (an incline of 0 or more)."""
    if cfg.carts and cfg.carts[0].incline < 0.0:  # a cart pulling the chain on: the rig
        return False  # laws were measured with carts holding it back
    v = floor_speeds(cfg)[0]
    H = float(cfg.apparatus.drop) + float(cfg.apparatus.floor_depth)
    return math.isfinite(v) and float(cfg.gravity) * H / (v * v) <= kh_max
