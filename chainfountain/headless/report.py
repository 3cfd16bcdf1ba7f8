"""The typed run summary, what ``summary.json`` holds: one name per quantity.

A :class:`RunSummary` is the run's common figures (the level, the time run, the steps and
links), the fountain's figures over the steady window (:class:`FountainFigures`) or a
scene's (:class:`SceneFigures`), and the optional sections the level's kind adds (the
theory comparison, the apparatus, beaker and open-arrangement reports, the machine line,
the error bars and model), each under its own key. :meth:`RunSummary.to_json` gives the
object ``summary.json`` stores (the parts flattened into one level, NaN and infinities as
``null``) and :meth:`RunSummary.from_json` reads it back::

    s = RunSummary.load("runs/wide_low/summary.json")
    s.fountain.h, s.theory.rel_error.h, s.sections.get("beaker")

The names: ``h`` the vertex height above the launch point, ``vertex_x`` its x, ``l`` the
landing x, ``H`` the drop to the floor, ``v`` the chain speed, ``q`` the catenary's
parameter, ``k = g/v^2``, ``T0_bar`` and ``TE_bar`` the scaled tensions at the launch and
the end (the paper's symbols), the same in the theory and in its errors. ``docs/cli.md``
lists every field; :data:`OLD_NAMES` maps the names of earlier versions to these.
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

OLD_NAMES: dict[str, str | None] = {
    "speed_mean": "v",
    "q_fit": "q",
    "vertex[0]": "vertex_x",
    "vertex[1]": "h",
    "start[0]": None,
    "start[1]": None,
    "end[0]": "l",
    "end[1]": None,
    "theory.vertex[0]": "theory.vertex_x",
    "theory.vertex[1]": "theory.h",
    "theory.rel_error.speed": "theory.rel_error.v",
    "analysis_failed.error model": "analysis_failed.error_model report",
}
"""Flattened ``summary.json`` keys of versions before the typed summary (``.`` between
keys, ``[i]`` for a list's items) and what they are now: a renamed key, or ``None`` for one
dropped because it repeated another (``vertex[1]`` is ``h``, ``end`` is ``(l, -H)``,
``start`` the launch point, always ``(0, 0)``). ``research/summary_snapshot.py`` applies
it to compare an old snapshot with a new one."""


def finite(x: Any) -> float | None:
    """JSON-safe float: NaN and infinities (and ``None``) become ``None``."""
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def json_safe(obj: Any) -> Any:
    """Nested dicts and lists with every number a float, NaN and infinities as ``null``
    (for the kinds' reports and ``converge.json``)."""
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [json_safe(v) for v in obj]
    if isinstance(obj, bool) or obj is None or isinstance(obj, str):
        return obj
    return finite(obj)


def _plain(obj: Any) -> Any:
    """A part's value as JSON: typed parts by their :meth:`to_json`, floats' NaN and
    infinities as ``null``, everything else as it is."""
    if hasattr(obj, "to_json"):
        return obj.to_json()
    if isinstance(obj, dict):
        return {k: _plain(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_plain(v) for v in obj]
    return finite(obj) if isinstance(obj, float) else obj


class _Part:
    """A flat dataclass written as a dict of its fields and read back from one."""

    def to_json(self) -> dict[str, Any]:
        return {f.name: _plain(getattr(self, f.name)) for f in dataclasses.fields(self)}

    @classmethod
    def from_json(cls, d: dict[str, Any]) -> Any:
        """The part from its fields in ``d`` (others ignored; a missing one ``None`` or
        its default)."""
        return cls(**{f.name: d[f.name] if f.name in d else (
            None if f.default is dataclasses.MISSING else f.default)
            for f in dataclasses.fields(cls)})


@dataclass
class RelErrors(_Part):
    """Relative errors against the paper: ``measured / predicted - 1``."""

    h: float | None
    vertex_x: float | None
    l: float | None  # noqa: E741 - the paper's symbol
    q: float | None
    v: float | None


@dataclass
class AbsErrors(_Part):
    """Absolute errors of the scaled tensions: ``measured - predicted``; ``tension_rms`` the
    RMS over the free chain of the time-averaged ``Tbar`` against the paper's ``Tbar(y)``."""

    T0_bar: float | None
    TE_bar: float | None
    tension_rms: float | None


THEORY_EXTRAS = ("joints", "catenary", "why_none", "at_speed")
""":class:`Theory`'s fields written only when they hold something (a stiff chain's, a
machine's that selects its speed)."""


@dataclass
class Theory(_Part):
    """The section ``theory``: the theory's fountain for this run and the window's errors
    against it. ``theory`` says which: ``"catenary"`` (the paper's,
    :class:`~chainfountain.sim.reference.LaunchReference`) or, for a motor-fed chain with
    joint springs or dampers, ``"stiff"`` (the steady stiff fountain,
    :class:`~chainfountain.sim.stiff_reference.StiffReference`; its ``q`` is ``None``),
    with the joints (``c``, ``d`` and their scaled ``e``, ``delta``) and the catenary's
    figures and the window's errors against them beside it (``catenary``). Where the stiff
    chain has no steady fountain the figures are ``None`` and ``why_none`` says so."""

    h: float | None
    vertex_x: float | None
    l: float | None  # noqa: E741 - the paper's symbol
    q: float | None
    k: float | None
    v: float | None
    T0_bar: float | None
    TE_bar: float | None
    rel_error: RelErrors
    abs_error: AbsErrors
    theory: str = "catenary"
    joints: dict[str, Any] | None = None
    """A stiff chain's ``c`` (N*m/rad), ``d`` (N*m*s/rad), ``e`` (m^2), ``delta`` (m^3), the
    damper's decay ``damper_decay`` and whether the fountain ``settles``
    (:func:`chainfountain.theory.stiff.damper_decay`)."""
    catenary: dict[str, Any] | None = None
    """A stiff chain's catenary: ``h``, ``vertex_x``, ``l``, ``q``, ``T0_bar`` and
    ``rel_error`` (``h``, ``vertex_x``, ``l``) of the window against them."""
    why_none: str | None = None
    """Why a stiff chain's figures are ``None``: "no steady stiff fountain at ..."."""
    at_speed: dict[str, Any] | None = None
    """A machine that selects its speed (an ideal machine with ``summary.json``
    ``machine = "selects"``): the paper's fountain at the window's own speed, with the
    end tension the machine's lower half supplies there
    (:meth:`~chainfountain.sim.reference.LaunchReference.at_speed`): ``v``, ``h``,
    ``vertex_x``, ``l``, ``TE_bar`` and ``rel_error`` (``h``, ``vertex_x``, ``l``) of the
    window against them. The figures above compare the window with the fountain at the
    speed the laws select, so they carry the speed's error too (the vertex moves by
    several times the speed's relative error); the error model bounds these."""

    def to_json(self) -> dict[str, Any]:
        d = super().to_json()
        return {k: v for k, v in d.items() if v is not None or k not in THEORY_EXTRAS}

    @classmethod
    def from_json(cls, d: dict[str, Any]) -> Theory:
        base = {k: d.get(k) for k in ("h", "vertex_x", "l", "q", "k", "v", "T0_bar", "TE_bar")}
        return cls(**base, rel_error=RelErrors.from_json(d.get("rel_error") or {}),
                   abs_error=AbsErrors.from_json(d.get("abs_error") or {}),
                   theory=d.get("theory") or "catenary",
                   **{k: d.get(k) for k in THEORY_EXTRAS})

    @property
    def stiff(self) -> bool:
        """Whether the theory is the stiff chain's."""
        return self.theory == "stiff"


@dataclass
class FountainFigures(_Part):
    """A fountain's figures over the run's averaging window (``window``, from
    ``steady_since_s`` when the run became steady), positions from the launch point."""

    steady: bool
    links_free: int | None = None
    steady_since_s: float | None = None
    window: list[float | None] | None = None
    """``[t0, t1]`` (s): the averaging window."""
    samples: int | None = None
    v: float | None = None
    """Mean chain speed (m/s)."""
    speed_cv: float | None = None
    """Largest deviation of a link position's mean speed from the mean, over the mean."""
    speed_spread: float | None = None
    """Mean over samples of (max - min)/mean link speed."""
    max_stretch: float | None = None
    vertex_x: float | None = None
    h: float | None = None
    """Vertex height above the launch point (m)."""
    l: float | None = None  # noqa: E741 - the paper's symbol
    """Landing x (m): where the end link, extended, meets the floor's height."""
    H: float | None = None
    """Drop from the launch point to the floor (m)."""
    q: float | None = None
    """Catenary parameter (1/m) fitted to the time-averaged shape."""
    k: float | None = None
    """``g/v^2`` (1/m) at the measured speed."""
    T0_bar: float | None = None
    TE_bar: float | None = None
    tension_rms: float | None = None


@dataclass
class SceneFigures(_Part):
    """A scene's figures: its steps, sampling and each probe's statistics."""

    pymunk_step: float
    sample_interval_s: float
    samples: int
    seed: int | None
    jitter: float
    probes: dict[str, Any]


@dataclass
class Ended(_Part):
    """``ended_early``: when and why a run stopped before its duration (``cause``: the
    :attr:`~chainfountain.headless.stepping.Ending.cause`)."""

    t_s: float | None
    cause: str | None
    reason: str
    signal_number: int | None = None
    last_mouth_entry_s: float | None = None
    """A guided fold's: when the fountain last landed in the end guide's mouth."""

    def to_json(self) -> dict[str, Any]:
        d = super().to_json()
        return {k: v for k, v in d.items()
                if v is not None or k not in ("signal_number", "last_mouth_entry_s")}


@dataclass
class Remeasured:
    """What a section builder returns when its report measures a headline figure better
    than the window does (the apparatus's ``TE_bar`` at the fountain's end height):
    ``section`` is stored, ``figures`` replace those of :class:`FountainFigures`."""

    section: Any
    figures: dict[str, float | None]


SECTION_TYPES: dict[str, Any] = {"theory": Theory}
"""Sections read back as typed objects by :meth:`RunSummary.from_json` (the others stay
the dicts ``summary.json`` has)."""

_CORE = ("level", "kind", "duration_s", "requested_duration_s", "steps", "links",
         "link_length", "dt", "wall_s", "realtime_factor")
_TAIL = ("ended_early", "analysis_failed", "outputs", "write_failed")


@dataclass
class RunSummary:
    """A headless run's summary (``summary.json``)."""

    level: str
    kind: str
    duration_s: float | None
    """Simulated seconds run."""
    requested_duration_s: float | None
    steps: int
    links: int
    link_length: float
    dt: float
    wall_s: float | None
    realtime_factor: float | None
    fountain: FountainFigures | None = None
    """A fountain's window figures (every kind but the scene)."""
    scene: SceneFigures | None = None
    sections: dict[str, Any] = field(default_factory=dict)
    """The kind's sections by name (``theory``, ``machine``, ``open``, ``beaker``,
    ``apparatus``, ``error_bars``, ``error_model``, a scene's ``closed_form``): typed
    objects or dicts, in the order written."""
    ended_early: Ended | None = None
    analysis_failed: dict[str, str] = field(default_factory=dict)
    """Analyses that failed (name: reason); their figures are null."""
    outputs: list[str] = field(default_factory=list)
    write_failed: dict[str, str] = field(default_factory=dict)
    """Files that could not be written (name: why)."""

    @property
    def theory(self) -> Theory | None:
        """The section ``theory``, typed (``None`` without a prediction)."""
        th = self.sections.get("theory")
        return Theory.from_json(th) if isinstance(th, dict) else th

    @property
    def steady(self) -> bool:
        """Whether the fountain became steady (a scene: never asked)."""
        return bool(self.fountain is not None and self.fountain.steady)

    def to_json(self) -> dict[str, Any]:
        """The ``summary.json`` object: the common figures, the fountain's or scene's,
        the sections, then how the run ended and what was written."""
        out: dict[str, Any] = {k: _plain(getattr(self, k)) for k in _CORE}
        for part in (self.fountain, self.scene):
            if part is not None:
                out.update(part.to_json())
        out.update({k: _plain(v) for k, v in self.sections.items()})
        out.update({k: _plain(getattr(self, k)) for k in _TAIL})
        return out

    def write(self, path: Path) -> None:
        """Write :meth:`to_json` to ``path`` (not atomically; see
        :func:`chainfountain.headless.files.write_summary`)."""
        Path(path).write_text(json.dumps(self.to_json(), indent=2) + "\n")

    @classmethod
    def from_json(cls, d: dict[str, Any]) -> RunSummary:
        """A summary from its ``summary.json`` object."""
        scene = d.get("kind") == "scene"
        fountain = None if scene else FountainFigures.from_json(
            {"steady": bool(d.get("steady")), **d})
        parts = {f.name for f in dataclasses.fields(FountainFigures if not scene
                                                   else SceneFigures)}
        known = set(_CORE) | set(_TAIL) | parts
        sections = {k: (SECTION_TYPES[k].from_json(v) if k in SECTION_TYPES
                        and isinstance(v, dict) else v)
                    for k, v in d.items() if k not in known}
        ended = d.get("ended_early")
        return cls(
            **{k: d.get(k) for k in _CORE},
            fountain=fountain,
            scene=SceneFigures.from_json(d) if scene else None,
            sections=sections,
            ended_early=Ended.from_json(ended) if ended else None,
            analysis_failed=dict(d.get("analysis_failed") or {}),
            outputs=list(d.get("outputs") or []),
            write_failed=dict(d.get("write_failed") or {}))

    @classmethod
    def load(cls, path: str | Path) -> RunSummary:
        """A summary from a ``summary.json`` file."""
        return cls.from_json(json.loads(Path(path).read_text()))
