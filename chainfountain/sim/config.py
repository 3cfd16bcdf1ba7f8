"""Configuration dataclasses of the physics core (SI units: m, kg, s, N, rad).

Every numeric field is declared with :func:`chainfountain.fields.param`
(unit, one-line doc, allowed range, ``live`` flag), so a generic level loader
can read, validate and document them. The classes are plain nested dataclasses
of numbers, strings, bools and tuples; :class:`SimConfig` is the top level.

Two kinds are simulated: ``kind = "feed"`` (a motor-driven beaker feeding the
chain at a set speed and launch angle, with an absorbing or solid floor ``H``
below the launch point) and ``kind = "apparatus"`` (the paper's pulley
apparatus, section "Generating Steady-State Chain Fountains": a roller unfolds
the resting chain, a guide channel lifts it ``xi2*H`` to the fountain start, it
flies, and either lands on a floor or is caught by an end channel and folded
back to rest by a second roller; see :class:`ApparatusConfig`). A third kind,
``kind = "scene"``, is a free chain with pins, a floor and probes
(:mod:`chainfountain.sim.scene_config`). ``rollers`` are
kinematic building blocks of feed levels; ``carts`` are free carts on a feed
level and the roller carts of an apparatus level.

The defaults come from the convergence study in ``docs/convergence.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from chainfountain.fields import param
from chainfountain.sim.scene_config import SceneConfig

KINDS: tuple[str, ...] = ("feed", "apparatus", "scene", "beaker")
"""Level kinds the simulator can build."""


@dataclass
class ChainConfig:
    """The chain: rigid rod links joined by pivots with a rotary spring-damper.

    The spring ``c`` and damper ``d`` between consecutive links are the joint
    resistance of the paper's angular momentum balance (section "Equations of
    Motion"): ``Qbar = -J*alpha'' - c/(lambda*v^2)*alpha' - d/(lambda*v)*alpha''``.
    """

    link_length: float = param(
        0.02, unit="m", doc="Length of one rigid link (pivot to pivot)", min=1e-3, max=0.2
    )
    linear_density: float = param(
        0.05, unit="kg/m", doc="Mass per length of the chain (lambda)", min=1e-4, max=10.0,
        min_inclusive=False,
    )
    bending_stiffness: float = param(
        0.0, unit="N*m/rad", doc="Rotary spring c between consecutive links (0 = free pivot)",
        min=0.0, max=10.0, live=True,
    )
    bending_damping: float = param(
        0.0, unit="N*m*s/rad", doc="Rotary damper d between consecutive links (0 = none)",
        min=0.0, max=1.0, live=True,
    )
    friction: float = param(
        0.6, unit="1", doc="Coulomb friction coefficient of links against floor, rollers, carts",
        min=0.0, max=5.0, live=True,
    )
    link_radius: float = param(
        0.002, unit="m", doc="Radius of the link capsules (contacts and drawing)",
        min=1e-4, max=0.05,
    )
    self_collision: bool = param(
        False, unit="", doc="Let links collide with each other (costly; off for fountains)"
    )
    bend_limit: float = param(
        0.0, unit="rad", doc="Largest bend between two neighbouring links, as a real ball chain "
        "has (a rotary limit joint; beaker and scene levels); a joint bent further at the start "
        "is free until it straightens. 0: free pivots", min=0.0, max=3.0,
    )


@dataclass
class BeakerConfig:
    """The beaker (``kind = "beaker"``, :mod:`chainfountain.sim.beaker`): a chain piled in
    a pot rises over the rim and falls to an absorbing floor (the Mould effect). Frame: the
    exit rim's top is the origin, the pot at ``x < 0``."""

    pot_width: float = param(
        0.3, unit="m", doc="Inner width of the pot (the pile's rows run across it)",
        min=0.05, max=2.0,
    )
    pot_depth: float = param(
        0.3, unit="m", doc="Depth of the pot from the rim to its bottom", min=0.05, max=2.0,
    )
    pile_rows: int = param(
        4, unit="1", doc="Rows of the pile in the solver (a new row is laid under the pile "
        "as the top is drawn off, with refill)", min=1, max=40,
    )
    pile_depth: float = param(
        0.04, unit="m", doc="Depth of the pile's top row below the rim (where the chain is "
        "picked up)", min=0.0, max=2.0,
    )
    drop: float = param(
        1.0, unit="m", doc="Drop from the rim to the absorbing floor", min=0.05, max=20.0,
        min_inclusive=False,
    )
    hang: float = param(
        0.6, unit="m", doc="Chain hanging over the rim at the start (it pulls the rest out)",
        min=0.02, max=20.0,
    )
    refill: bool = param(
        True, unit="", doc="Keep the pile's top at pile_depth: the pile rises on a plate as "
        "it is drawn off and a row is laid under it for each row taken (runs as long as you "
        "watch); false: the pile empties and the run ends",
    )
    duration: float = param(
        30.0, unit="s", doc="Length of a headless run", min=0.01, max=1e5,
        min_inclusive=False,
    )


@dataclass
class FeedConfig:
    """The motor-driven beaker: chain leaves a straight guide at speed ``v`` and angle ``alpha0``.

    With an absorbing floor the end tension is zero and the paper's inverted
    catenary is fully determined: ``Tbar_0 = k*H``, ``q = k/(cos(alpha0)*(1 - k*H))``
    (Eq. for ``Tbar_0 - Tbar_E = k*H`` with ``Tbar_E = 0``).
    """

    speed: float = param(
        5.0, unit="m/s", doc="Feed speed v of the chain leaving the guide", min=0.0, max=30.0,
        live=True,
    )
    launch_angle: float = param(
        math.radians(75.0), unit="rad", doc="Launch angle alpha0 of the guide above horizontal",
        min=math.radians(5.0), max=math.radians(89.0),
    )
    drop: float = param(
        1.0, unit="m", doc="Height H of the floor below the launch point", min=0.05, max=20.0,
        min_inclusive=False,
    )
    chain_length: float = param(
        0.0, unit="m", doc="Total chain length to feed; 0 = infinite feed. With an ideal "
        "machine (feed.drive other than 'motor') the chain on its upper table: the run ends "
        "when it is all picked up",
        min=0.0, max=1e4,
    )
    end_tension: float = param(
        0.0, unit="1", doc="Scaled pull Tbar_E = T_E/(lambda*v^2) of the absorbing floor on the "
        "chain end (0 = the end is free); the paper's floor reaction force", min=0.0, max=0.99,
        live=True,
    )
    floor: str = param(
        "absorbing", unit="", doc="Floor under the fountain: 'absorbing' removes landing links, "
        "'solid' is a static segment links land and pile on",
        choices=("absorbing", "solid"),
    )
    floor_width: float = param(
        6.0, unit="m", doc="Length of the floor, centred on the launch point (a solid floor "
        "must reach past the landing point)",
        min=0.1, max=100.0,
    )
    guide_links: int = param(
        2, unit="1", doc="Kinematic links kept inside the guide (upstream of the launch point)",
        min=1, max=20,
    )
    drive: str = param(
        "motor", unit="", doc="What moves the chain: 'motor', the guide runs at feed.speed; "
        "'ideal_floor', 'ideal_fold' or 'ideal_open', one of the paper's machines with ideal "
        "parts, its laws alone setting the speed from feed.speed at the start (see "
        "docs/apparatus.md#the-ideal-machines)",
        choices=("motor", "ideal_floor", "ideal_fold", "ideal_open"),
    )
    xi2: float = param(
        0.0, unit="1", doc="The ideal machines: height the chain is lifted "
        "before the start, as a fraction xi2 of H (the paper's lowered beaker)", min=0.0,
        max=1.0, min_inclusive=True, max_inclusive=False, live=True,
    )
    cart_force: float = param(
        0.0, unit="N", doc="The ideal machines: force F_uc of the upper "
        "cart holding the chain back", min=0.0, max=100.0, live=True,
    )
    xi3: float = param(
        0.0, unit="1", doc="Drive 'ideal_fold': height the chain is lifted after landing "
        "before it is put down, as a fraction xi3 of H (the paper's raised bottom)", min=0.0,
        max=1.0, min_inclusive=True, max_inclusive=False, live=True,
    )
    lower_cart_force: float = param(
        0.0, unit="N", doc="Drive 'ideal_fold': force F_lc of the lower cart pulling the "
        "chain on at the put-down (the paper's Tbar_lc*lambda*v^2)", min=0.0, max=100.0,
        live=True,
    )
    bearing_drag: float = param(
        0.0, unit="N*s/m", doc="Drive 'ideal_fold': viscous drag c of the rollers' bearings, "
        "c*v/2 at each roller; above 0 the machine selects a speed and returns to it after a "
        "push. 0: the paper's loss-free machine (see docs/apparatus.md#the-ideal-machines)",
        min=0.0, max=100.0, live=True,
    )
    turn_drop: float = param(
        0.0, unit="m", doc="Drive 'ideal_open': height d of the loss-free turn from the "
        "fountain's end down to the plate the chain slides away on; the chain in the turn "
        "pulls the end with its weight lambda*g*d (Tbar_E = k*d)", min=0.0, max=20.0,
        live=True,
    )
    machine_mass: float = param(
        0.05, unit="kg", doc="The ideal machines: inertia of the carts "
        "and the guided strands (sets how fast the speed changes, not where it goes; "
        "'ideal_open' adds the chain sliding on its plate)",
        min=0.001, max=100.0,
    )
    starter: float = param(
        0.0, unit="s", doc="The ideal machines from a stub (initial.mode = 'stub'): how long the "
        "guide runs on as a motor at feed.speed after the chain has landed, before the machine's "
        "laws take over. 0: no starter (see docs/apparatus.md#the-ideal-machines)",
        min=0.0, max=60.0,
    )


@dataclass
class SolverConfig:
    """Integrator and constraint solver settings (pymunk / Chipmunk2D).

    Each step ``dt`` is made of ``substeps`` pymunk steps of ``dt/substeps``; the feed's
    bookkeeping, the recorder and the divergence watchdog run once per ``dt``. Too few
    iterations leave a long strand's tension wrong: a chain of 100 (300) links hanging
    at rest needs 6 (10) iterations at a 62.5-us pymunk step, and 5 read its tension
    42 % low (``tests/sim/test_measure.py``)."""

    dt: float = param(
        2.5e-4, unit="s", doc="Time step of the simulation's bookkeeping and samples (the "
        "pymunk step is dt/substeps)", min=1e-6, max=0.02, min_inclusive=False
    )
    substeps: int = param(
        1, unit="1", doc="pymunk steps per time step dt (a scene's default: 8)", min=1,
        max=64,
    )
    iterations: int = param(
        25, unit="1", doc="Constraint solver iterations per pymunk step (a scene's default: "
        "2)", min=1, max=1000, live=True
    )
    joint_error_bias: float = param(
        1e-10, unit="1", doc="Fraction of pivot-joint error left uncorrected after 1 s "
        "(tiny = stiff joints)", min=0.0, max=1.0, live=True,
    )
    collision_slop: float = param(
        1e-4, unit="m", doc="Allowed contact overlap", min=0.0, max=0.01, live=True
    )
    accuracy: float = param(
        0.0, unit="1", doc="Relative accuracy wanted (e.g. 0.005) of a fed fountain on an "
        "absorbing floor or a beaker: above 0, the cheapest link_length, dt and iterations "
        "within it are chosen at load; 0: the level's own. A fed file that sets none of them "
        "gets 0.01 (0.02 an ideal machine) (docs/accuracy.md)", min=0.0, max=0.1,
    )
    wave_damping: float = param(
        1e-3, unit="1", doc="Damping D of link-scale bending waves: a rotary damper "
        "D*lambda*v*L**2 at each joint between moving links (v the level's speed, L the link "
        "length), besides chain.bending_damping (see "
        "docs/convergence.md#choices-that-matter-and-defaults)", min=0.0, max=1.0,
    )


@dataclass
class InitialConfig:
    """How the chain starts (kind 'feed'). An 'apparatus' level lays its chain along its
    own path, moving at ``apparatus.speed``, and accepts only these defaults."""

    mode: str = param(
        "catenary", unit="", doc="'catenary': laid along the predicted fountain moving at v; "
        "'stub': a short straight stub at the guide", choices=("stub", "catenary"),
    )
    stub_length: float = param(
        0.1, unit="m", doc="Free length of the initial stub (mode 'stub')", min=0.0, max=10.0
    )
    jitter: float = param(
        1e-3, unit="rad", doc="Random angle perturbation per link at start (rad)",
        min=0.0, max=0.5,
    )
    seed: int = param(
        0, unit="1", doc="Random seed of the initial perturbation; in apparatus and beaker levels "
        "a seed above 0 nudges every moving body by 1e-12 of its velocity, which picks another "
        "of the run's chaotic outcomes. 0: no nudge", min=0,
    )


@dataclass
class RecordingConfig:
    """Measurement sampling and averaging."""

    sample_interval: float = param(
        0.01, unit="s", doc="Time between recorded samples", min=1e-4, max=10.0,
        min_inclusive=False,
    )
    window: float = param(
        2.0, unit="s", doc="Averaging window at the end of a run; a run is steady only "
        "if it stays in the steady band for at least this long", min=0.01, max=1e4
    )
    steady_tolerance: float = param(
        0.01, unit="1", doc="Relative band for steady-state detection (vertex height, speed)",
        min=0.0, max=1.0, min_inclusive=False,
    )
    smoothing: float = param(
        0.25, unit="s", doc="Moving-average span applied before steady-state detection",
        min=0.0, max=100.0,
    )


@dataclass
class RollerConfig:
    """A kinematic roller (circle) spinning at a set angular speed (apparatus building block)."""

    x: float = param(0.0, unit="m", doc="Centre x relative to the launch point", min=-100.0,
                     max=100.0)
    y: float = param(0.0, unit="m", doc="Centre y relative to the launch point", min=-100.0,
                     max=100.0)
    radius: float = param(0.03, unit="m", doc="Roller radius", min=1e-3, max=2.0)
    angular_speed: float = param(
        0.0, unit="rad/s", doc="Spin rate, counter-clockwise positive", min=-1000.0,
        max=1000.0, live=True,
    )
    friction: float = param(1.0, unit="1", doc="Friction coefficient", min=0.0, max=5.0)


@dataclass
class CartConfig:
    """A dynamic cart on a straight inclined track (GrooveJoint), apparatus building block."""

    x: float = param(0.0, unit="m", doc="Start position x of the cart centre (launch frame)",
                     min=-100.0, max=100.0)
    y: float = param(0.0, unit="m", doc="Start position y of the cart centre (launch frame)",
                     min=-100.0, max=100.0)
    incline: float = param(
        0.0, unit="rad", doc="Track angle beta above horizontal (+x uphill for beta > 0)",
        min=-math.pi / 2, max=math.pi / 2,
    )
    track_length: float = param(2.0, unit="m", doc="Track length, centred on the start", min=0.01,
                                max=100.0)
    mass: float = param(0.1, unit="kg", doc="Cart mass", min=1e-6, max=1000.0,
                        min_inclusive=False, live=True)
    width: float = param(0.05, unit="m", doc="Cart box width", min=1e-3, max=10.0)
    height: float = param(0.02, unit="m", doc="Cart box height", min=1e-3, max=10.0)


@dataclass
class ApparatusConfig:
    """The paper's pulley apparatus (section "Generating Steady-State Chain Fountains").

    Frame as for the feed: the fountain start (exit of the upper guide channel)
    is the origin, ``y`` up, the fountain flies in ``+x``; its end is ``drop``
    (the paper's ``H``) below the start. Upstream: the chain rests on a rough
    upper table; a roller (alpha = 0: the chain wraps around its back and
    leaves on top, along the roller's motion) rolls on it and unfolds it, the
    chain slides over a frictionless plate to a frictionless two-sided guide
    channel that lifts it ``xi2*H`` to the start at ``launch_angle``.
    Downstream, by ``variant``:

    - ``"floor"`` (idealized beaker, real floor): the chain ends at the fountain
      end height; with ``end = "absorbing"`` (default) links vanish there (free
      end, ``Tbar_E = 0``) and the speed selects itself,
      ``v**2 = (g*H*(1 - xi2) - F_uc/lambda)/p``; with ``floor_depth = d`` the
      absorbing floor lies ``d`` below the fountain end, whose tension is then
      ``lambda*g*d`` (``Tbar_E = g*d/v**2``), and ``H`` becomes ``H + d`` in the
      speed's drive; ``end = "solid"`` is a static floor the chain piles on (it
      pushes back in the simulation);
    - ``"fold"`` (full arrangement): an end channel catches the chain at the
      fountain end, turns it and lifts it ``xi3*H`` onto a plate; a second
      roller folds it back to rest on a lower table;
    - ``"open"`` (non-stationary): the end channel turns the chain horizontal
      and it slides away on a frictionless plate (more and more chain moves).

    Carts: ``carts[0]`` pulls the upper roller back against its motion,
    ``carts[1]`` (fold only) pushes the lower roller forward, each with the
    force ``mass*g*sin(incline)`` of a cart on an inclined track tied to the
    roller's carriage by an ideal rope (its mass is added to the carriage).
    Their ``x``, ``y`` and ``track_length`` only place the drawing.
    """

    variant: str = param(
        "floor", unit="", doc="'floor': real floor at the fountain end; 'fold': end channel and "
        "folding roller; 'open': end channel, chain slides away (non-stationary)",
        choices=("floor", "fold", "open"),
    )
    drop: float = param(
        0.5, unit="m", doc="Height H of the fountain start above the fountain end", min=0.05,
        max=20.0, min_inclusive=False,
    )
    launch_angle: float = param(
        math.radians(60.0), unit="rad", doc="Launch angle alpha0 of the upper channel exit",
        min=math.radians(5.0), max=math.radians(85.0),
    )
    speed: float = param(
        3.0, unit="m/s", doc="Launch speed v0: the chain starts moving along its path at v0",
        min=0.1, max=30.0,
    )
    end_tension: float = param(
        0.0, unit="1", doc="Scaled end tension Tbar_E that sets the initial fountain's "
        "layout and the end channel's aim", min=0.0, max=0.99,
    )
    xi2: float = param(
        0.5, unit="1", doc="Upper table ('beaker') xi2*H below the fountain start", min=0.0,
        max=5.0,
    )
    xi3: float = param(
        0.5, unit="1", doc="Lower table ('bottom') xi3*H above the fountain end (fold)", min=0.0,
        max=5.0,
    )
    duration: float = param(
        6.0, unit="s", doc="Run time the tables and plates are sized for (rollers move at "
        "about v0/2)", min=0.1, max=600.0,
    )
    roller_radius: float = param(0.03, unit="m", doc="Radius r of both rollers (of the pick-up "
                                 "roller alone when apparatus.fold_roller_radius is set)",
                                 min=0.005, max=0.5)
    roller_mass: float = param(0.02, unit="kg", doc="Mass of each roller", min=1e-4, max=10.0)
    carriage_mass: float = param(
        0.02, unit="kg", doc="Mass of each roller carriage (cart mass is added)", min=1e-4,
        max=10.0,
    )
    table_friction: float = param(
        5.0, unit="1", doc="Friction of the tables (rough, so the resting chain stays put)",
        min=0.0, max=20.0,
    )
    channel_radius: float = param(
        0.15, unit="m", doc="Bend radius of the guide channels (reduced if the rise is short)",
        min=0.02, max=5.0,
    )
    floor_width: float = param(4.0, unit="m", doc="Length of the floor ('floor' variant)",
                               min=0.1, max=100.0)
    end: str = param(
        "absorbing", unit="", doc="Floor of the 'floor' variant: 'absorbing' removes a link when "
        "its centre reaches the floor (a free end, Tbar_E = 0); 'solid', a static floor the "
        "chain piles on",
        choices=("absorbing", "solid"),
    )
    floor_depth: float = param(
        0.0, unit="m", doc="'floor' with end = 'absorbing' only: depth d of the absorbing floor "
        "below the fountain end; the hanging strand gives Tbar_E = g*d/v**2. 0: the floor at the "
        "fountain end", min=0.0, max=10.0,
    )
    plate: str = param(
        "groove", unit="", doc="Upper plate (roller to channel): 'groove', a frictionless groove "
        "joint holds each link centre on the plate line; 'contact', a frictionless static "
        "segment the strand slides on",
        choices=("groove", "contact"),
    )
    end_pull: float = param(
        0.0, unit="N", doc="'open' only: constant horizontal force pulling the chain's downstream "
        "end away (a light weight over an ideal pulley), so the chain enters the end channel taut",
        min=0.0, max=100.0,
    )
    rest_links: int = param(
        20, unit="1", doc="Resting links kept in the solver behind the folding roller / on "
        "the floor (older ones leave the solver), and ahead of the pick-up roller unless "
        "pickup_rest_links is set", min=5, max=10000,
    )
    pickup_rest_links: int = param(
        0, unit="1", doc="Resting links kept in the solver ahead of the pick-up roller (the rest "
        "enter as the roller comes). 0: as rest_links", min=0, max=10000,
    )
    plate_links: int = param(
        0, unit="1", doc="Treadmill (needs plate = 'groove'): the upper plate strand (in 'fold' "
        "the lower too) is kept at about this many links, so the rollers stay put and runs may "
        "last any time. 0: the real geometry (see docs/apparatus.md#tables-plates-and-treadmills)",
        min=0, max=1000,
    )
    fold_clearance: float = param(
        0.0, unit="m", doc="'fold' with plate = 'groove' only: gap between the lower plate's "
        "groove line and the chain centre line on the folding roller's top; 0 (the presets' "
        "build) clamps the roller (see docs/apparatus.md#the-fold-depends-on-the-time-step)",
        min=0.0, max=0.005,
    )
    fold_roller: str = param(
        "contact", unit="", doc="'fold' with plate = 'groove': how the folding roller puts the "
        "chain down: 'contact' grips it by friction; 'gripped' welds each joint to the rim and "
        "pins it to the table (see docs/apparatus.md#the-gripped-folding-roller)",
        choices=("contact", "gripped"),
    )
    fold_roller_radius: float = param(
        0.0, unit="m", doc="'fold': radius of the folding roller; 0: apparatus.roller_radius "
        "(both rollers alike)", min=0.0, max=0.5,
    )
    bearing_drag: float = param(
        0.0, unit="N*s/m", doc="Declared loss of a real apparatus: viscous drag c of each "
        "roller unit (bearings and cart rolling resistance), a force -c*u on its carriage "
        "moving at u (about v/2). 0: loss-free bearings", min=0.0, max=10.0, live=True,
    )
    fold_brake: float = param(
        0.0, unit="N*s/m", doc="'fold': a brake c on the folding roller's carriage, a force -c*u "
        "at its speed u (not in the paper); with it the lower cart selects the speed. 0: none "
        "(see docs/apparatus.md#a-brake-that-selects-the-speed)",
        min=0.0, max=10.0, live=True,
    )
    end_follow: float = param(
        0.0, unit="1/s", doc="'fold' with plate = 'groove': the end guide slides toward where the "
        "fountain lands at this rate times the landing's offset (at most 5 cm/s and 30 cm; not "
        "in the paper). 0: fixed (see docs/apparatus.md#an-end-guide-that-follows-the-landing)",
        min=0.0, max=20.0,
    )
    swing_damper: float = param(
        0.0, unit="N*s/m", doc="'fold': a dashpot c between the two roller carriages, a force "
        "-c*(u_up - u_lo); idle in a steady run, it damps the landing swing (not in the paper). "
        "0: none (see docs/apparatus.md#the-landing-swing)",
        min=0.0, max=10.0, live=True,
    )
    starter: float = param(
        0.0, unit="s", doc="From rest (initial.mode = 'stub'): how long a starter motor in the "
        "upper guide runs the chain at apparatus.speed after it has landed (or, in 'fold', been "
        "laid on the lower table). 0: none (see docs/apparatus.md#starting-from-rest)",
        min=0.0, max=60.0,
    )
    upper_guide: str = param(
        "walls", unit="", doc="Upper guide channel (plate end to fountain start): 'walls', a "
        "frictionless two-sided channel of static segments; 'joints' (needs plate = 'groove'), "
        "frictionless joints hold each link centre on the centre line (see "
        "docs/apparatus.md#guides)",
        choices=("walls", "joints"),
    )
    start_region: str = param(
        "checked", unit="", doc="From rest (initial.mode = 'stub'): 'checked' refuses a gripped "
        "fold or floor machine set outside the region where it was measured to form and hold "
        "(docs/apparatus.md#where-the-machines-start-from-rest); 'unchecked' runs it anyway, "
        "for a study of that region itself (research/contact_region)",
        choices=("checked", "unchecked"),
    )


@dataclass
class SimConfig:
    """A complete simulation setup (one level)."""

    kind: str = param("feed", unit="", doc="Level kind", choices=KINDS)
    name: str = param("", unit="", doc="Short name of the level")
    gravity: float = param(9.81, unit="m/s^2", doc="Gravitational acceleration g", min=0.01,
                           max=1000.0)
    chain: ChainConfig = field(default_factory=ChainConfig)
    feed: FeedConfig = field(default_factory=FeedConfig)
    apparatus: ApparatusConfig = field(default_factory=ApparatusConfig)
    beaker: BeakerConfig = field(default_factory=BeakerConfig)
    scene: SceneConfig = field(default_factory=SceneConfig)
    solver: SolverConfig = field(default_factory=SolverConfig)
    initial: InitialConfig = field(default_factory=InitialConfig)
    recording: RecordingConfig = field(default_factory=RecordingConfig)
    rollers: tuple[RollerConfig, ...] = ()
    carts: tuple[CartConfig, ...] = ()
