"""What the window's readout shows: the measured numbers, the paper's fountain through
them, the live plots' history and whether the fountain is steady. No pygame here."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from chainfountain.app.error_bars import error_bars_line
from chainfountain.sim import placement
from chainfountain.sim.apparatus.laws import braked_fold_speed, floor_speeds
from chainfountain.sim.machine_rules import keeps_any_speed
from chainfountain.sim.measure import steady_time
from chainfountain.sim.recorder import Recorder
from chainfountain.sim.stiff_reference import StiffReference, headline
from chainfountain.sim.world import Simulation

HISTORY_SECONDS = 120.0
"""How much measured history the plots keep (older samples are dropped)."""


@dataclass
class Readout:
    """What the readout panel and the overlays show (all floats, launch frame, SI)."""

    t: float = 0.0
    v: float = math.nan
    k: float = math.nan
    q: float = math.nan
    h: float = math.nan
    l: float = math.nan  # noqa: E741 - the paper's symbol
    H: float = math.nan
    T0_bar: float = math.nan
    TE_bar: float = math.nan
    T0_theory: float = math.nan
    TE_theory: float = math.nan
    steady: bool = False
    measured: bool = False
    """True once the values come from the running chain (else from the feed settings)."""
    note: str = ""
    machine: str = ""
    """An ideal machine's prediction by the paper's laws (speed, end tensions), or ''."""
    bars: str = ""
    """The expert view's line of discretisation error bars
    (:func:`~chainfountain.app.error_bars.error_bars_line`), or ''."""
    curve: np.ndarray | None = None
    """Theory curve, launch frame, ``(n, 2)``."""
    vertex: tuple[float, float] | None = None
    """Theory vertex, launch frame."""
    measured_vertex: tuple[float, float] | None = None
    paper_h: float = math.nan
    """The theory's vertex height for the level's settings (a fed fountain's launch speed
    and angle, or the speed an ideal machine's laws select); nan where they fix none."""
    theory: str = "catenary"
    """Which theory the curve, ``paper_h`` and the theory tensions are: ``"catenary"``
    (the paper's, through the measured ends once measured) or ``"stiff"`` (the steady
    stiff fountain of the chain's joints, :mod:`chainfountain.sim.stiff_reference`)."""
    theory_label: str = "paper"
    """What the window calls the theory: ``"paper"`` or ``"stiff-chain theory"``."""
    joints: str = ""
    """A stiff chain's joints (``c = ..., d = ...``), else ''."""
    theory_note: str = ""
    settle_note: str = ""
    """Why a stiff chain will not settle on its theory's fountain ('' when it will)."""
    """Why a stiff chain has no theory curve ("no steady stiff fountain at c = ..., d =
    ..."), else ''."""
    tension_theory_y: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """A stiff chain's theory tension profile: heights along the curve (launch frame)..."""
    tension_theory: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """... and the scaled tensions there (empty: the catenary's ``1 - k/q + k*y``)."""
    origin: str = "launch"
    """What the heights and the launch pull are measured from: the launch point, or a
    beaker's pick-up ('pick-up'; its readout has no end pulls: the pile and the floor are
    not the paper's machine)."""
    tension_y: np.ndarray = field(default_factory=lambda: np.zeros(0))
    tension_bar: np.ndarray = field(default_factory=lambda: np.zeros(0))


class History:
    """Time series for the live plots (appended per recorder sample, trimmed to a span)."""

    def __init__(self, span: float = HISTORY_SECONDS) -> None:
        self.span = span
        self.t: list[float] = []
        self.speed: list[float] = []
        self.T0: list[float] = []
        self.TE: list[float] = []
        self.vertex_y: list[float] = []
        self.landing_x: list[float] = []
        self.speed_in: list[float] = []
        """Apparatus: chain speed at the pick-up (twice the roller speed; nan otherwise)."""
        self.speed_out: list[float] = []
        """Apparatus with a fold: chain speed at the folding roller (nan otherwise)."""
        self.reaction: list[float] = []
        """The open arrangement (apparatus 'open', ``feed.drive = "ideal_open"``): the
        lower plate's reaction force, N (nan otherwise)."""

    def _lists(self) -> tuple[list[float], ...]:
        return (self.t, self.speed, self.T0, self.TE, self.vertex_y, self.landing_x,
                self.speed_in, self.speed_out, self.reaction)

    def clear(self) -> None:
        for lst in self._lists():
            lst.clear()

    def append(self, t: float, speed: float, T0: float, TE: float, vy: float, lx: float,
               speed_in: float = math.nan, speed_out: float = math.nan,
               reaction: float = math.nan) -> None:
        for lst, x in zip(self._lists(),
                          (t, speed, T0, TE, vy, lx, speed_in, speed_out, reaction),
                          strict=True):
            lst.append(x)
        if len(self.t) > 64 and self.t[-1] - self.t[0] > 1.1 * self.span:
            cut = int(np.searchsorted(np.asarray(self.t), self.t[-1] - self.span))
            for lst in self._lists():
                del lst[:cut]

    def arrays(self) -> dict[str, np.ndarray]:
        return {
            "t": np.asarray(self.t), "speed": np.asarray(self.speed),
            "T0": np.asarray(self.T0), "TE": np.asarray(self.TE),
            "vertex_y": np.asarray(self.vertex_y), "landing_x": np.asarray(self.landing_x),
            "speed_in": np.asarray(self.speed_in), "speed_out": np.asarray(self.speed_out),
            "reaction": np.asarray(self.reaction),
        }


AVG_SPAN = 0.25
"""Seconds of history the readout's speed and shape are averaged over: short enough to
follow a slider."""
TENSION_SPAN = 1.0
"""Seconds of history its end tensions are averaged over: a contact machine's tensions
scatter from sample to sample (the gripped folds' ``Tbar_E`` by 0.28 ``lambda v^2``, sd of
10-ms samples over 9-25 s from rest); 0.25-s means of it scatter by 0.05-0.06, 1-s means
by 0.02-0.03 (``Tbar_0``: 0.11-0.13, 0.02, 0.01), so the printed ones flicker less."""


def _mean(a: np.ndarray) -> float:
    """Mean of the finite values of ``a``; nan (without numpy's warning) if none."""
    a = a[np.isfinite(a)]
    return float(a.mean()) if len(a) else math.nan


def compute_readout(sim: Simulation, recorder: Recorder, history: History,
                    asked_accuracy: float = 0.0, was_steady: bool = False) -> Readout:
    """The numbers and theory overlay the readout shows, from the recorded history
    (``asked_accuracy``: the level's ``solver.accuracy`` where the window runs the
    settings of a coarser one, :mod:`chainfountain.app.interactive`; ``was_steady``: the
    last readout said steady, which it keeps within :data:`STEADY_HYSTERESIS` times the
    tolerance)."""
    from chainfountain.theory import Fountain

    cfg = sim.config
    H = sim.drop
    g = float(cfg.gravity)
    r = Readout(t=sim.time, H=H, origin="pick-up" if sim.beaker is not None else "launch")
    hist = history.arrays()
    t = hist["t"]
    avg_span = AVG_SPAN
    ox, oy = 0.0, 0.0  # the launch point: the origin, or a beaker's pick-up
    landed = sim.ends.absorbed > 0 or placement.floor(sim)[3] != "absorbing"
    if len(t) >= 3 and sim.n_free >= 8 and landed:
        sel = t >= t[-1] - avg_span
        v = _mean(hist["speed"][sel])
        h = _mean(hist["vertex_y"][sel])
        lx = _mean(hist["landing_x"][sel])
        tsel = t >= t[-1] - TENSION_SPAN
        r.T0_bar = _mean(hist["T0"][tsel])
        r.TE_bar = _mean(hist["TE"][tsel])
        r.measured = True
        r.measured_vertex = (float(recorder.samples[-1].vertex_x)
                             if recorder.samples else math.nan, h)
        f = None
        if sim.beaker is not None:
            # the paper's curve through the measured ends: from where the chain leaves the
            # pile, over the measured top, to where it reaches the floor
            ox, oy = sim.beaker.pickup
            h, lx, H = h - oy, lx - ox, H + oy
            v = sim.beaker.speed
        if isinstance(sim.reference, StiffReference) or sim.reference_note:
            r.v, r.h, r.l = v, h, lx  # a stiff chain: compared with its own theory below
        elif not v * v > g * H:
            # no fountain can reach the floor (k*H >= 1): nothing to compare, and tensions
            # scaled by lambda*v^2 of a chain this slow mean nothing to a reader
            moves = ("the floor takes the chain at" if sim.beaker is not None  # its speed
                     else "the chain moves at")
            r.note = (f"no fountain: {moves} {v:.2f} m/s, slower than the "
                      f"sqrt(g*H) = {math.sqrt(g * H):.2f} m/s a fountain over this drop needs")
            r.T0_bar = r.TE_bar = math.nan
        elif not h > 0.0:
            r.note = "no fountain: the chain does not rise above the launch point"
        else:
            try:
                f = Fountain.from_geometry(l=lx, h=h, H=H, v=v, g=g)
            except (ValueError, ArithmeticError, RuntimeError):
                r.note = ("no inverted catenary fits the measured ends (the chain is not "
                          "a steady fountain)")
    else:
        f = None
        ref = sim.reference
        if ref is not None:
            try:
                f = Fountain.from_launch(v=ref.v, alpha0=ref.alpha0, H=H, TE_bar=0.0, g=g)
                r.note = ("prediction from the feed settings (the chain has not "
                          "reached the floor yet)" if len(t) else
                          "prediction from the feed settings (no measurement yet)")
            except (ValueError, ArithmeticError):
                f = None
        if f is None:
            r.note = "no fountain predicted for this feed"
    if sim.reference_note and sim.beaker is None:
        f = None  # a stiff chain without a steady fountain: no theory, and it says why
        r.note = r.theory_note = headline(sim.reference_note)
    stiff = sim.reference if isinstance(sim.reference, StiffReference) else None
    if stiff is not None:
        f = None
        _stiff_overlay(r, stiff, g)
    if f is not None:
        sx, sy = f.start
        r.v, r.k, r.q, r.h, r.l = f.v, f.k, f.q, f.h, f.l
        r.T0_theory, r.TE_theory = f.T0_bar, f.TE_bar
        xs, ys = f.curve(160)
        sx, sy = sx - ox, sy - oy
        r.curve = np.column_stack((np.asarray(xs) - sx, np.asarray(ys) - sy))
        r.vertex = (-sx, -sy)
    elif r.measured:
        r.v = _mean(hist["speed"][t >= t[-1] - avg_span])
        r.k = g / r.v**2 if r.v > 0 else math.nan
    if not r.measured and len(t):
        # measured tensions and speed exist before the chain lands; show them
        sel = t >= t[-1] - avg_span
        r.T0_bar = _mean(hist["T0"][sel])
        r.TE_bar = _mean(hist["TE"][sel])
    # tension profile: average of the last few samples, launch end first
    profs = recorder.profiles[-8:]
    if profs and not sim.dragging:
        n = min(len(p.tension_bar) for p in profs)
        if n >= 2:
            r.tension_bar = np.mean([p.tension_bar[:n] for p in profs], axis=0)
            r.tension_y = np.mean([p.y[:n] for p in profs], axis=0)
    if sim.apparatus is not None and sim.apparatus.starting:
        # the starter sets the links' velocities: the momentum balance reads its drive
        r.note = "the starter motor is running the chain: pulls are read once it lets go"
        r.T0_bar = r.TE_bar = math.nan
    if sim.dragging:
        r.note = "a link is held: tension readings paused"
        r.T0_bar = r.TE_bar = math.nan
    if sim.theory_stale and sim.reference is None:
        r.note = "solving the stiff-chain theory for these joints ..."
    r.steady = is_steady(sim, hist, STEADY_HYSTERESIS if was_steady else 1.0)
    r.machine = machine_line(sim)
    r.bars = error_bars_line(sim, asked_accuracy)
    if sim.reference is not None:
        r.paper_h = float(sim.reference.h)
    return r


def _stiff_overlay(r: Readout, ref: StiffReference, g: float) -> None:
    """The stiff-chain theory's curve, vertex and tensions in ``r`` (the measured figures
    stay; before the chain lands, the theory's stand in for them)."""
    r.theory, r.theory_label = ref.theory, ref.label
    if not ref.settles:
        r.settle_note = "too little damping: this stiff chain does not settle"
    r.joints = f"c = {ref.c:.3g} N*m/rad, d = {ref.d:.3g} N*m*s/rad"
    r.curve = ref.curve(160)
    r.T0_theory, r.TE_theory = ref.T0_bar, ref.TE_bar
    r.tension_theory_y, r.tension_theory = ref.tension_curve()
    r.q = math.nan  # a stiff fountain has no catenary parameter
    if r.measured:
        if r.measured_vertex is not None and math.isfinite(r.measured_vertex[0]):
            r.vertex = r.measured_vertex
        r.k = g / r.v**2 if r.v > 0 else math.nan
        return
    r.vertex = ref.vertex
    r.v, r.k, r.h, r.l = ref.v, ref.k, ref.h, ref.landing_x


def machine_line(sim: Simulation) -> str:
    """What an ideal machine's laws predict (the paper's section "Generating Steady-State
    Chain Fountains"): the speed it selects, or that it keeps any, and its end tensions."""
    cfg = sim.config
    if sim.beaker is not None:
        return beaker_line(sim)
    if sim.apparatus is not None:
        return selection_line(sim)
    if sim.piston is None:  # not an ideal machine
        return ""
    ref = sim.reference
    if ref is None:
        return "paper's laws: no fountain at these settings"
    ends = f"Tbar_0 {ref.T0_bar:.3f}, Tbar_E {ref.TE_bar:.3f}"
    if keeps_any_speed(cfg):
        return f"paper's laws keep any v: {ends}"
    return f"paper's laws: v {ref.v:.3f} m/s, {ends}"


def selection_line(sim: Simulation) -> str:
    """A contact 'floor' machine: the speed its upper cart selects now by this model's
    pick-up law and by the paper's (:func:`~chainfountain.sim.apparatus.laws.floor_speeds`);
    a 'fold' machine with a brake on its folding roller: the speed its carts and brake
    select by the paper's laws (:func:`~chainfountain.sim.apparatus.laws.braked_fold_speed`);
    to read beside the measured speed. '' for the other arrangements."""
    if sim.apparatus is None:
        return ""
    a = sim.config.apparatus
    if a.variant == "fold" and a.fold_brake > 0.0:
        v = braked_fold_speed(sim.config)
        if not math.isfinite(v):
            return "the carts and the brake select no speed: the upper cart holds the chain back"
        return f"the carts and the brake select {v:.2f} m/s by the paper's laws"
    if a.variant != "floor":
        return ""
    model, paper = floor_speeds(sim.config)
    if not math.isfinite(model):
        return "the cart selects no speed: it holds the chain harder than the fall pulls it"
    by_paper = f"{paper:.2f} m/s" if math.isfinite(paper) else "none (cart too heavy)"
    return (f"the cart selects {model:.2f} m/s by this model's rollers, "
            f"{by_paper} by the paper's laws")


def beaker_line(sim: Simulation) -> str:
    """The pile's push by Biggins and Warner's relation (:mod:`chainfountain.theory.mould`):
    ``alpha = 1 - g*H/v**2`` from the speed and the drop below the pick-up."""
    from chainfountain.theory.mould import alpha_from_speed

    b = sim.beaker
    v = b.speed
    H = b.pickup[1] - b.floor_y
    if not (v > 0.0 and H > 0.0) or b.absorbed == 0:
        return "Biggins & Warner: the pile's push once the chain reaches the floor"
    if v * v <= sim.g * H:  # no fountain yet: the relation reads a negative push
        return ("Biggins & Warner: the pile's push once the floor takes the chain faster "
                f"than sqrt(gH) = {math.sqrt(sim.g * H):.2f} m/s")
    a = alpha_from_speed(v, H, 0.0, sim.g)
    return (f"Biggins & Warner: the pile pushes with alpha = 1 - gH/v^2 = {a:.2f} "
            f"(H {H:.2f} m below the pick-up)")


STEADY_HYSTERESIS = 2.0
"""Once the readout says steady it says so while the vertex and the speed stay within
this many times the level's tolerance: a contact machine whose speed holds flat while its
vertex wanders about the 1-% tolerance otherwise flickered between "steady" and "not
steady (yet)" every few seconds (``apparatus_floor_heavy`` in a real window: 6 of 8
samples steady over 62-81 s at 2.792-2.797 m/s)."""


def is_steady(sim: Simulation, hist: dict[str, np.ndarray], loosen: float = 1.0) -> bool:
    """Vertex height and mean speed (``hist``: :meth:`History.arrays`) stayed within the
    level's tolerance (times ``loosen``) for a window."""
    rc = sim.config.recording
    t = hist["t"]
    if len(t) < 10 or t[-1] - t[0] < rc.window or sim.dragging:
        return False
    sel = t >= t[-1] - 2.0 * rc.window
    for name in ("vertex_y", "speed"):
        s = hist[name][sel]
        if not np.all(np.isfinite(s)):
            return False
        ts = steady_time(t[sel], s, loosen * rc.steady_tolerance, rc.smoothing, rc.window)
        if ts is None or ts > t[-1] - rc.window + 1e-9:
            return False
    return True
