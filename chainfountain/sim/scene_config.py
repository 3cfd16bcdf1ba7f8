"""Configuration of a scene level (``kind = "scene"``): one free chain laid out in the
world, pins that hold points of it and let go at set times, an optional solid floor (a
scale: the force on it is recorded), walls (tables, sides), and probes that say what to
record.

The falling-chain experiments with closed forms are scenes: the folded chain falling
with one end fixed (Calkin and March 1989) and the chain dropped onto a scale (Hamm and
Geminard 2010); ``closed_form`` names the one a run is compared with
(:mod:`chainfountain.theory.falling`). Points are numbered along the chain from its
start, ``0 .. N`` for ``N`` links; a negative number counts from the end (``-1`` is the
last point), as in Python.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from chainfountain.fields import REQUIRED, param

LAYOUTS: tuple[str, ...] = ("straight", "folded", "polyline")
"""How the chain is laid out at the start."""
PROBE_KINDS: tuple[str, ...] = ("point", "tension", "pin_force", "floor_force", "energy")
"""What a probe records (:class:`ProbeConfig`)."""
CLOSED_FORMS: tuple[str, ...] = ("none", "folded_fall", "scale")
"""Closed forms a scene can be compared with (:mod:`chainfountain.theory.falling`)."""
MAX_POINT = 20_000
"""Largest point number a pin or probe may name (the chain's link limit)."""


def point_number(point: int, n: int) -> int:
    """``point`` of a chain of ``n`` links as a number in ``0 .. n`` (negative: from the end)."""
    return point + n + 1 if point < 0 else point


@dataclass
class VertexConfig:
    """A corner of the polyline the chain is laid along (layout 'polyline')."""

    x: float = param(0.0, unit="m", doc="Corner x", min=-100.0, max=100.0)
    y: float = param(0.0, unit="m", doc="Corner y (up)", min=-100.0, max=100.0)


@dataclass
class WallConfig:
    """A static segment the links land on, slide along and bounce off: a table top, a
    wall, the side of a pot."""

    x0: float = param(0.0, unit="m", doc="One end of the wall (x)", min=-100.0, max=100.0)
    y0: float = param(0.0, unit="m", doc="One end of the wall (y)", min=-100.0, max=100.0)
    x1: float = param(0.0, unit="m", doc="The other end (x)", min=-100.0, max=100.0)
    y1: float = param(0.0, unit="m", doc="The other end (y)", min=-100.0, max=100.0)
    thickness: float = param(0.01, unit="m", doc="Thickness of the wall (its surface lies "
                             "half of it from the line x0,y0 - x1,y1)", min=1e-4, max=1.0)


@dataclass
class PinConfig:
    """A point of the chain held in place from the start."""

    point: int = param(
        REQUIRED, unit="1", doc="Point held: 0 .. N along the chain (N links), or counted "
        "from the end when negative (-1 = the last point)", min=-MAX_POINT - 1, max=MAX_POINT,
    )
    release: float = param(
        0.0, unit="s", doc="Time at which the pin lets go (0 = held for the whole run)",
        min=0.0, max=3600.0,
    )


@dataclass
class ProbeConfig:
    """Something recorded at every sample (``recording.sample_interval``) into
    ``probe_<name>.csv``; ``summary.json`` gives each column's statistics."""

    name: str = param(REQUIRED, unit="", doc="Name of the probe (letters, digits, '_' and "
                      "'-'; names its file probe_<name>.csv)")
    kind: str = param(
        REQUIRED, unit="", doc="'point': position and velocity (x, y, vx, vy); 'tension': tension "
        "at an interior point (N, + = pull; no pin beyond it); 'pin_force': the pin's force (N); "
        "'floor_force': the chain's force on the floor (fx, fy); 'energy': kinetic, potential, "
        "total (J)",
        choices=PROBE_KINDS,
    )
    point: int = param(
        0, unit="1", doc="Point probed (kinds 'point', 'tension', 'pin_force'): 0 .. N, or "
        "from the end when negative", min=-MAX_POINT - 1, max=MAX_POINT,
    )


@dataclass
class SceneConfig:
    """A free chain and what holds, catches and measures it (kind 'scene')."""

    layout: str = param(
        "straight", unit="", doc="'straight': a line from (x, y) at angle; 'folded': two arms "
        "joined by a U of fold_links links, the first leaving (x, y) at angle; 'polyline': along "
        "[[scene.vertices]], as many whole links as fit",
        choices=LAYOUTS,
    )
    length: float = param(
        1.0, unit="m", doc="Length of the chain (layouts 'straight' and 'folded'; rounded to "
        "whole links)", min=0.0, max=400.0, min_inclusive=False,
    )
    x: float = param(0.0, unit="m", doc="Start of the chain, point 0 (x)", min=-100.0,
                     max=100.0)
    y: float = param(0.0, unit="m", doc="Start of the chain, point 0 (y, up)", min=-100.0,
                     max=100.0)
    angle: float = param(
        -math.pi / 2, unit="rad", doc="Direction of the chain (of its first arm when folded) "
        "from point 0, from the +x axis, counter-clockwise (-pi/2 = straight down)",
        min=-2 * math.pi, max=2 * math.pi,
    )
    fold_links: int = param(
        2, unit="1", doc="Links in the U that joins the arms (layout 'folded'; 2 makes a "
        "fold about 1.4 link lengths wide)", min=1, max=1000,
    )
    tilt: float = param(
        1e-3, unit="rad", doc="Both arms lean this far from angle toward the U's side "
        "(layout 'folded'; a slight lean decides which way a vertical fold goes)",
        min=0.0, max=0.5,
    )
    jitter: float = param(
        0.0, unit="rad", doc="Random angle added to each link ('straight' and 'folded'; "
        "normal, this standard deviation): a pile of falling links is chaotic, so compare "
        "means over seeds", min=0.0, max=0.5,
    )
    seed: int = param(0, unit="1", doc="Random seed of the jitter", min=0)
    velocity_x: float = param(0.0, unit="m/s", doc="Initial velocity of every link (x)",
                              min=-100.0, max=100.0)
    velocity_y: float = param(0.0, unit="m/s", doc="Initial velocity of every link (y)",
                              min=-100.0, max=100.0)
    floor: str = param(
        "none", unit="", doc="'solid': a floor at floor_y the links land and pile on (a "
        "scale: probe kind 'floor_force' reads it); 'none': no floor", choices=("none", "solid"),
    )
    floor_y: float = param(0.0, unit="m", doc="Height of the floor's top surface (floor "
                           "'solid')", min=-100.0, max=100.0)
    duration: float = param(
        1.0, unit="s", doc="Simulated seconds of a run (chainfountain run --duration "
        "overrides)", min=0.0, max=3600.0, min_inclusive=False,
    )
    closed_form: str = param(
        "none", unit="", doc="Closed form the run is compared with: 'folded_fall' (layout "
        "'folded', point 0 pinned; Calkin and March), 'scale' (layout 'straight' onto a solid "
        "floor, no pins; Hamm and Geminard) or 'none'", choices=CLOSED_FORMS,
    )
    vertices: tuple[VertexConfig, ...] = ()
    walls: tuple[WallConfig, ...] = ()
    pins: tuple[PinConfig, ...] = ()
    probes: tuple[ProbeConfig, ...] = ()
