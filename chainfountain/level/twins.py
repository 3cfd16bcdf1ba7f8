"""Like-for-like twins: a contact machine level as the paper's ideal machine, and back.

A contact machine (``kind = "apparatus"``, pymunk rollers and carts) and an ideal machine
(``kind = "feed"`` with ``feed.drive`` ``"ideal_floor"``, ``"ideal_fold"`` or
``"ideal_open"``: the paper's laws act on the chain's ends) show the same arrangement.
:func:`ideal_twin` builds the ideal machine with the contact level's geometry, chain and
speed, its carts chosen by the paper's laws (section "Generating Steady-State Chain
Fountains"; ``docs/apparatus.md``, "The ideal machines")::

    Tbar_0 = 1/2 + Tbar_uc + xi2 k H          (the pick-up, the upper cart, the lift)
    Tbar_E = 1/2 + Tbar_lc - xi3 k H          (the put-down, the lower cart, the lift)
    steady:  Tbar_0 - Tbar_E = k H,  i.e.  Tbar_uc = Tbar_lc + k H (1 - xi2 - xi3)

with ``k = g/v^2`` and scaled forces ``Tbar = T/(lambda v^2)``. By arrangement:

- ``'floor'`` (the idealized beaker with a real floor, ``Tbar_E = 0``): the fountain's
  ``Tbar_0 = k H`` selects ``v^2 = 2 g (H (1 - xi2) - F_uc/(lambda g))``
  (:func:`~chainfountain.theory.apparatus.ideal_floor_speed`), so the upper cart for the
  source's speed is ``F_uc = lambda (g H (1 - xi2) - v^2/2)``.
- ``'fold'`` (the full machine, the limit case included): the source's end tension
  ``apparatus.end_tension`` is the ``Tbar_E`` its fountain is laid out and its end guide
  aimed for, so the twin's carts are the paper's two-step design for that fountain
  (:func:`~chainfountain.theory.apparatus.settings_for`): ``Tbar_lc = Tbar_E - 1/2 + xi3 k
  H`` and the balanced ``Tbar_uc``. With the template's bearing drag ``c`` (``c v/2`` at
  each roller) the carts carry the drag at the source's speed, ``F_lc = Tbar_lc lambda v^2
  + c v/2`` and ``F_uc = Tbar_uc lambda v^2 - c v/2``: the machine then *selects* the
  source's speed, ``v = (F_lc + lambda g H (1 - xi2 - xi3) - F_uc)/c``
  (:func:`~chainfountain.theory.apparatus.ideal_fold_speed`), and returns to it after a
  push, which is what a class should see. Where the drag would need an upper cart that
  pushes (the paper's upper cart is lighter than ``c v/2``) or would leave the lower strand
  slack at that speed, the twin is the paper's loss-free machine (``bearing_drag = 0``,
  balanced carts), which *keeps* the source's speed.
- ``'open'`` (the non-stationary arrangement): the landed chain runs down a loss-free turn
  ``d`` whose weight pulls the end, ``Tbar_E = k d``, so the source's end tension gives
  ``d = Tbar_E v^2/g`` and the selected ``v^2 = 2 g (H (1 - xi2) + d) - 2 F_uc/lambda``
  (:func:`~chainfountain.theory.apparatus.ideal_open_speed`) gives ``F_uc``.

Carts only hold back (the paper: ``Tbar_uc > 0``, ``Tbar_lc > 0``), so a contact level
whose speed the paper's ideal rollers cannot reach at its geometry has no ideal twin: the
paper's pick-up needs ``lambda v^2/2``, the contact rollers about half that
(``docs/apparatus.md``, "Pick-up force"), so at the contact presets' 0.5-m drop and about
3 m/s the paper's machine would need carts that push. :func:`ideal_twin` then raises
:class:`~chainfountain.level.model.LevelError` with one line saying why.
"""

from __future__ import annotations

import copy
import dataclasses
import math

from chainfountain.level import io, library
from chainfountain.level.model import Level, LevelError, Meta
from chainfountain.sim.config import FeedConfig, SimConfig
from chainfountain.sim.kinds import REGISTRY, kind_of
from chainfountain.sim.kinds.ideal.checks import IDEAL_MIN_KQ
from chainfountain.theory.apparatus import balanced_cart_force, ideal_fold_TE_bar, settings_for

APPARATUS, IDEAL = REGISTRY["apparatus"], REGISTRY["ideal"]
"""The two kinds a twin joins: a contact machine and the paper's ideal one."""

TWIN_SUFFIX = " (ideal twin)"
"""Appended to the source level's name to name its ideal twin."""

DRIVE_OF_VARIANT = {"floor": "ideal_floor", "fold": "ideal_fold", "open": "ideal_open"}
"""The ideal machine's drive for each contact arrangement (``apparatus.variant``)."""

FORCE_ROUNDING = 1e-9
"""A cart force (in units of ``lambda g H``) this far below 0 is 0 rounded: the limit
case's lower cart, ``Tbar_E - 1/2 + xi3 k H`` with ``xi3 = 1/(2 k H)``, comes out about
``1e-17`` either side of 0. It moves the selected speed by about ``1e-9`` of itself."""


@dataclasses.dataclass(frozen=True)
class _Machine:
    """The ideal machine's own settings for one twin (``feed.*``)."""

    drive: str
    cart_force: float
    lower_cart_force: float = 0.0
    bearing_drag: float = 0.0
    turn_drop: float = 0.0
    xi3: float = 0.0


def _no_twin(level: Level, why: str) -> LevelError:
    """The error saying in one plain line why ``level`` has no ideal twin."""
    return LevelError(f"{level.name} has no ideal twin: {why}")


def _pulls(force: float, scale: float) -> float | None:
    """``force`` (N) if a cart can give it (``>= 0``, within :data:`FORCE_ROUNDING` of
    ``scale``), else ``None``."""
    if force >= 0.0:
        return force
    return 0.0 if force >= -FORCE_ROUNDING * scale else None


def _template(level: Level, drive: str) -> Level:
    """The shipped ideal preset the twin copies its solver, starter, recording and machine
    inertia from: ``library.twin(name)`` when it is shipped and has the twin's drive (the
    ideal machine of the same arrangement), else the drive's own preset (``ideal_floor``,
    ``ideal_fold``, ``ideal_open``)."""
    shipped = library.shipped_dir()
    name = library.twin(level.name)
    if name is not None and (shipped / f"{name}.toml").exists():
        lvl = io.load(shipped / f"{name}.toml")
        if kind_of(lvl.sim).style(lvl.sim) == drive:
            return lvl
    return io.load(shipped / f"{drive}.toml")


def _check_not_near_critical(level: Level) -> None:
    """Refuse a fountain too near critical for the ideal machines: ``k/q = cos(alpha0) (1 -
    Tbar_0)`` at the launch (``Tbar_0 = Tbar_E + k H``, ``Tbar_E`` 0 for a floor, else the
    source's end tension) below
    :data:`~chainfountain.sim.kinds.ideal.checks.IDEAL_MIN_KQ`. The level
    checks apply that bound to the full machine, where it was measured; it is applied to
    every twin, because near critical the simulated chain's back force grows as the machine
    slows, and the checks let an ideal floor pass at any ``k/q``. Measured from rest, 30 s,
    with the twins of ``apparatus_floor`` at other speeds (0.5-m drop, 2-cm links): at 2.3
    and 2.33 m/s (``k/q`` 0.036, 0.048) the chain stopped 1.5 and 3.0 s after the starter
    let go; at 2.36, 2.4, 2.45 and 2.5 m/s (0.060-0.108) it ran 1.6, 0.7, 2.5-5 (wandering)
    and 0.5 % low; at 2.6 m/s (0.137) 1.9 % low, steady. The floor twin of
    ``apparatus_fountain_d_kmax`` (0.019) stopped 2.3 s after the hand-over."""
    a, g = level.sim.apparatus, level.sim.gravity
    v, H = a.speed, a.drop
    TE = 0.0 if a.variant == "floor" else a.end_tension
    kq = (1.0 - (TE + g * H / (v * v))) * math.cos(a.launch_angle)
    if kq < IDEAL_MIN_KQ:
        raise _no_twin(level, f"at {v:.3g} m/s its fountain is too near critical for the "
                       f"ideal machine (k/q = {kq:.3f}, below {IDEAL_MIN_KQ}), where the "
                       "simulated chain holds the machine back until it stops")


def _floor_machine(level: Level) -> _Machine:
    """The idealized beaker with a real floor that selects the source's speed."""
    sim = level.sim
    a, g, lam = sim.apparatus, sim.gravity, sim.chain.linear_density
    v, H = a.speed, a.drop
    if a.end != "absorbing":
        raise _no_twin(level, f"its floor is {a.end!r}: the chain piles on it, and the "
                       "paper's real floor takes the chain without pull (apparatus.end = "
                       "'absorbing')")
    if a.floor_depth > 0.0:
        raise _no_twin(level, f"its floor lies {a.floor_depth:.3g} m below the fountain's end, "
                       "and the ideal floor machine's floor is at the end (apparatus."
                       "floor_depth = 0)")
    # Tbar_0 = 1/2 + Tbar_uc + xi2 k H = k H  =>  F_uc = lambda (g H (1 - xi2) - v^2/2)
    F_uc = _pulls(lam * (g * H * (1.0 - a.xi2) - 0.5 * v * v), lam * g * H)
    if F_uc is None:
        v_max = math.sqrt(2.0 * g * H * (1.0 - a.xi2))
        raise _no_twin(level, f"the paper's ideal rollers run a floor machine with a "
                       f"{H:g} m drop and xi2 = {a.xi2:g} at most at {v_max:.3g} m/s (with no "
                       f"upper cart), slower than its {v:.3g} m/s")
    return _Machine("ideal_floor", F_uc)


def _fold_machine(level: Level, template: Level) -> _Machine:
    """The full machine for the source's fountain (``Tbar_E = apparatus.end_tension``),
    with the template's bearing drag where its carts can carry it, else loss-free."""
    sim = level.sim
    a, g, lam = sim.apparatus, sim.gravity, sim.chain.linear_density
    v, H, TE = a.speed, a.drop, a.end_tension
    k, lv2, scale = g / (v * v), lam * v * v, lam * g * H
    design = settings_for(TE, k, H, a.xi2, a.xi3)  # the paper's two-step design
    F_lc = _pulls(design.T_lc * lv2, scale)
    if F_lc is None:
        raise _no_twin(level, f"at {v:.3g} m/s its fountain ends with Tbar_E = {TE:g}, but the "
                       f"paper's put-down alone pulls 1/2 - xi3*k*H = {0.5 - a.xi3 * k * H:.3g}, "
                       f"so its lower cart would have to hold the chain back (Tbar_lc = "
                       f"{design.T_lc:.3g})")
    F_bal = balanced_cart_force(F_lc, a.xi2, a.xi3, lam, H, g)
    F_uc = _pulls(F_bal, scale)
    if F_uc is None:
        raise _no_twin(level, f"at {v:.3g} m/s its fountain starts with Tbar_0 = "
                       f"{TE + k * H:.3g}, but the paper's pick-up and lift alone pull "
                       f"1/2 + xi2*k*H = {0.5 + a.xi2 * k * H:.3g}, so its upper cart would "
                       f"have to push (Tbar_uc = {F_bal / lv2:.3g})")
    c = float(template.sim.feed.bearing_drag)
    if c > 0.0:
        F_lc_c, F_uc_c = F_lc + 0.5 * c * v, F_uc - 0.5 * c * v
        taut = ideal_fold_TE_bar(v, a.xi3, F_lc_c, lam, H, g, c) >= 0.0
        if F_uc_c >= 0.0 and taut:
            # F_uc from the selection v = (F_lc + lambda g H (1 - xi2 - xi3) - F_uc)/c itself
            F_uc_c = balanced_cart_force(F_lc_c, a.xi2, a.xi3, lam, H, g) - c * v
            return _Machine("ideal_fold", F_uc_c, F_lc_c, bearing_drag=c, xi3=a.xi3)
    return _Machine("ideal_fold", F_uc, F_lc, bearing_drag=0.0, xi3=a.xi3)


def _open_machine(level: Level) -> _Machine:
    """The open arrangement whose turn gives the source's end tension and whose upper cart
    selects the source's speed."""
    sim = level.sim
    a, g, lam = sim.apparatus, sim.gravity, sim.chain.linear_density
    v, H, TE = a.speed, a.drop, a.end_tension
    d = TE * v * v / g  # Tbar_E = k d
    F_uc = _pulls(lam * (g * (H * (1.0 - a.xi2) + d) - 0.5 * v * v), lam * g * H)
    if F_uc is None:
        d_max = 0.5 * v * v / g - H * (1.0 - a.xi2)
        raise _no_twin(level, f"at {v:.3g} m/s with Tbar_E = {TE:g} (a turn of {d:.3g} m) the "
                       f"paper's pick-up and lift hold the chain back harder than the fall "
                       f"pulls it on, so its upper cart would have to push (it would need a "
                       f"turn of {d_max:.3g} m, Tbar_E = {g * d_max / (v * v):.3g})")
    return _Machine("ideal_open", F_uc, turn_drop=d)


def _feed(level: Level, template: Level, m: _Machine) -> FeedConfig:
    """The twin's ``[feed]``: the source's speed, launch, drop and offsets, the machine
    ``m``, the template's table, guide, floor width, inertia and starter."""
    a, t = level.sim.apparatus, template.sim.feed
    return FeedConfig(
        speed=a.speed, launch_angle=a.launch_angle, drop=a.drop,
        chain_length=t.chain_length, end_tension=0.0, floor="absorbing",
        floor_width=t.floor_width, guide_links=t.guide_links, drive=m.drive, xi2=a.xi2,
        cart_force=m.cart_force, xi3=m.xi3, lower_cart_force=m.lower_cart_force,
        bearing_drag=m.bearing_drag, turn_drop=m.turn_drop, machine_mass=t.machine_mass,
        starter=t.starter,
    )


def _description(level: Level, m: _Machine) -> str:
    """Three plain sentences: the same machine with the paper's ideal rollers, what its
    carts do by the paper's laws, and how it starts."""
    a = level.sim.apparatus
    offsets = f"xi2 = {a.xi2:.3g}" + (f", xi3 = {a.xi3:.3g}" if m.drive == "ideal_fold" else "")
    carts = f"an upper cart of {1e3 * m.cart_force:.3g} mN"
    if m.drive == "ideal_fold":
        carts += (f" and a lower cart of {1e3 * m.lower_cart_force:.3g} mN"
                  if m.lower_cart_force > 0.0 else " and no lower cart")
    if m.drive == "ideal_open":
        carts += f" and a loss-free turn of {100 * m.turn_drop:.3g} cm"
    select = "selects" if m.drive == "ideal_floor" else "select"
    if m.drive == "ideal_fold" and m.bearing_drag == 0.0 and a.end_tension == 0.0:
        how = ("bring the chain up to that speed, where its lower strand just goes slack, "
               "and keep any faster one, as its rollers are loss-free")
    elif m.drive == "ideal_fold" and m.bearing_drag == 0.0:
        how = ("keep that speed: its rollers are loss-free and its carts balanced, so it "
               "keeps the speed it runs at")
    elif m.bearing_drag > 0.0:
        how = (f"select that speed against its bearings' small drag ({m.bearing_drag:g} N s/m), "
               "which brings it back after a push")
    else:
        how = f"{select} that speed"
    return (f"The machine of {level.name} with the paper's ideal rollers: the same "
            f"{a.drop:g} m drop, {offsets} and launch angle, and the same {a.speed:.3g} m/s. "
            f"By the paper's laws {carts} {how}. A starter fires the chain from a short stub "
            "and hands it to the laws once the fountain has formed.")


def ideal_twin(level: Level) -> Level | None:
    """The ideal machine that runs the same fountain as the contact machine ``level``.

    For a contact apparatus level (``kind = "apparatus"``, variants ``'floor'``,
    ``'fold'``, the limit case included, and ``'open'``): a ``kind = "feed"`` level with
    ``feed.drive`` ``"ideal_floor"``, ``"ideal_fold"`` or ``"ideal_open"``, the source's
    drop ``H``, launch angle, offsets ``xi2`` (and ``xi3``), chain and gravity, started at
    the source's speed ``apparatus.speed``, with the carts the paper's laws need to select
    that speed (or, loss-free, to keep it) with the source's end tension: ``Tbar_0 = 1/2 +
    Tbar_uc + xi2 k H``, ``Tbar_E = 1/2 + Tbar_lc - xi3 k H`` and the steady ``Tbar_uc =
    Tbar_lc + k H (1 - xi2 - xi3)`` (the module's docstring gives each arrangement). The
    solver, initial state (a stub), starter, recording, machine inertia and bearing drag
    come from the shipped ideal preset of the same arrangement (``library.twin(name)``,
    else ``ideal_floor``/``ideal_fold``/``ideal_open``). Named ``"<name> (ideal twin)"``.

    ``None`` for a level with no ideal counterpart (a beaker, a fed level, a scene).
    Raises :class:`~chainfountain.level.model.LevelError` (one plain line) when the paper's
    machine cannot run the source's fountain at its geometry: a cart would have to push,
    the fountain would be too near critical, or the arrangement has no ideal form (a
    solid floor, a floor below the fountain's end); and when the twin fails the level
    checks.
    """
    sim = level.sim
    if kind_of(sim) is not APPARATUS:
        return None
    a = sim.apparatus
    drive = DRIVE_OF_VARIANT[a.variant]
    if a.speed**2 <= sim.gravity * a.drop:
        raise _no_twin(level, f"{a.speed:.3g} m/s makes no fountain over its {a.drop:g} m drop "
                       f"(the paper needs v > sqrt(g H) = {math.sqrt(sim.gravity * a.drop):.3g}"
                       " m/s)")
    template = _template(level, drive)
    if drive == "ideal_floor":
        m = _floor_machine(level)
    elif drive == "ideal_fold":
        m = _fold_machine(level, template)
    else:
        m = _open_machine(level)
    _check_not_near_critical(level)
    t = template.sim
    name = f"{level.name}{TWIN_SUFFIX}"
    twin_sim = SimConfig(
        kind="feed", name=name, gravity=sim.gravity, chain=copy.deepcopy(sim.chain),
        feed=_feed(level, template, m), solver=copy.deepcopy(t.solver),
        initial=copy.deepcopy(t.initial), recording=copy.deepcopy(t.recording),
    )
    meta = Meta(name=name, title=f"{level.meta.shown_title}: ideal rollers",
                description=_description(level, m))
    twin = Level(meta=meta, sim=twin_sim)
    try:
        io.check_consistency(twin, name)
    except LevelError as exc:
        raise _no_twin(level, f"the ideal machine fails the level checks ({exc})") from None
    return twin


def contact_twin(level: Level) -> Level | None:
    """The shipped contact machine showing an ideal level's arrangement, or ``None``.

    For an ideal level (``kind = "feed"``, ``feed.drive`` other than ``"motor"``) whose name
    is a shipped ideal preset's (``ideal_floor``, ``ideal_fold``, ...): the first shipped
    contact preset that :data:`~chainfountain.level.library.TWINS` pairs with it, loaded
    from the package. Its geometry and speed are its own (the shipped ideal presets stand
    at 1 m, the contact presets at 0.5 m), so it is the same arrangement, not the same
    fountain. A like-for-like contact machine of an ideal level is not known in general:
    this model's contact rollers pick the chain up and put it down with other forces than
    the paper's (``docs/apparatus.md``, "Where the model's laws differ from the paper"),
    so their carts for a given fountain are measured, not derived. Hence ``None`` for any
    other ideal level, a twin made by :func:`ideal_twin` included (the caller that made it
    holds its source), and for every level that is not an ideal machine.
    """
    sim = level.sim
    if kind_of(sim) is not IDEAL:
        return None
    shipped = library.shipped_dir()
    if not (shipped / f"{level.name}.toml").exists() or level.name in library.TWINS:
        return None
    name = library.twin(level.name)
    if name is None or not (shipped / f"{name}.toml").exists():
        return None
    return io.load(shipped / f"{name}.toml")
