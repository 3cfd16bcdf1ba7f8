"""Cross-field checks of a scene level (``kind = "scene"``): its chain can be laid out,
every pin and probe names a point it has, every setting has an effect, and the closed
form it names fits the scene."""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np

from chainfountain.errors import fail
from chainfountain.sim.config import InitialConfig, RecordingConfig, SimConfig, SolverConfig
from chainfountain.sim.scene_config import SceneConfig, point_number
from chainfountain.sim.scene_layout import chain_points, fold_arms, link_count

MAX_PROBES = 50
"""Most probes a scene may have."""
MAX_WALLS = 100
"""Most walls a scene may have."""
PROBE_NAME = re.compile(r"[A-Za-z0-9_-]{1,40}")
"""A probe's name: it names a file."""
HANGING = 0.02
"""A closed form's chain must hang within this angle (rad) of the vertical."""
_NOT_FOR_SCENES = {
    "solver.wave_damping": "damps a fountain's bending waves",
    "recording.window": "averages a fountain's steady state",
    "recording.steady_tolerance": "detects a fountain's steady state",
    "recording.smoothing": "smooths a fountain's steady-state detection",
}
"""Settings of fountain levels that have no effect in a scene, and what they do."""


def check_scene(sim: SimConfig, where: str, max_links: int) -> None:
    """All checks of a scene level; the first problem raises (one line)."""
    _check_unused(sim, where)
    sc = sim.scene
    L = sim.chain.link_length
    _check_layout(sc, L, where, max_links)
    pts = chain_points(sc, L)
    n = len(pts) - 1
    if n < 2:  # a polyline too short (the other layouts' lengths are checked above)
        fail(where, "scene.vertices", f"the polyline is {_length(sc):.4g} m long, room for "
              f"{n} link(s) of {L:g} m; allowed: room for at least 2 links")
    if sc.floor == "solid":
        low = int(np.argmin(pts[:, 1]))
        if pts[low, 1] - sim.chain.link_radius < sc.floor_y:
            fail(where, "scene.floor_y", f"{sc.floor_y:g} m puts point {low} (at y = "
                  f"{pts[low, 1]:.4g} m) into the floor; allowed: at most "
                  f"{pts[low, 1] - sim.chain.link_radius:.4g} m (below the chain by its "
                  "link_radius)")
    _check_walls(sc, pts, sim.chain.link_radius, where)
    _check_pins(sc, n, where)
    _check_probes(sc, n, where)
    _check_closed_form(sc, n, where)


def _length(sc: SceneConfig) -> float:
    v = np.array([(p.x, p.y) for p in sc.vertices], dtype=float)
    return float(np.hypot(*np.diff(v, axis=0).T).sum()) if len(v) > 1 else 0.0


def _check_unused(sim: SimConfig, where: str) -> None:
    """Fountain settings are left at their defaults: they have no effect in a scene."""
    if sim.initial != InitialConfig():
        changed = next(f.name for f in dataclasses.fields(InitialConfig)
                       if getattr(sim.initial, f.name) != getattr(InitialConfig(), f.name))
        fail(where, f"initial.{changed}", f"{getattr(sim.initial, changed)!r} has no effect "
              "in a 'scene' level (its chain starts as scene.layout lays it); allowed: no "
              "[initial] table")
    for name in ("rollers", "carts"):
        if getattr(sim, name):
            fail(where, name, f"{len(getattr(sim, name))} given; allowed: none in a 'scene' "
                  "level (its chain is free, held only by scene.pins)")
    defaults = {"solver": SolverConfig(), "recording": RecordingConfig()}
    for path, what in _NOT_FOR_SCENES.items():
        table, field = path.split(".")
        value, default = getattr(getattr(sim, table), field), getattr(defaults[table], field)
        if value != default:
            fail(where, path, f"{value!r} has no effect in a 'scene' level (it {what}); "
                  f"allowed: {default!r} or leave it out")


def _check_layout(sc: SceneConfig, L: float, where: str, max_links: int) -> None:
    polyline = sc.layout == "polyline"
    if polyline:
        for field in ("length", "x", "y", "angle", "fold_links", "tilt", "jitter", "seed"):
            value, default = getattr(sc, field), getattr(SceneConfig(), field)
            if value != default:
                fail(where, f"scene.{field}", f"{value!r} has no effect with layout "
                      "'polyline' (the chain lies along scene.vertices); allowed: "
                      f"{default!r} or leave it out")
        if len(sc.vertices) < 2:
            fail(where, "scene.vertices", f"{len(sc.vertices)} given; allowed: at least 2 "
                  "corners with layout 'polyline' ([[scene.vertices]] x, y)")
        if _length(sc) > max_links * L:
            fail(where, "scene.vertices", f"the polyline is {_length(sc):.4g} m long, more "
                  f"than {max_links} links of {L:g} m; allowed: at most "
                  f"{max_links * L:g} m")
        for i in range(1, len(sc.vertices)):
            a, b = sc.vertices[i - 1], sc.vertices[i]
            if (a.x, a.y) == (b.x, b.y):
                fail(where, f"scene.vertices[{i}]", f"({b.x:g}, {b.y:g}) repeats the corner "
                      "before it; allowed: a corner apart from the one before")
        return
    if sc.vertices:
        fail(where, "scene.vertices", f"{len(sc.vertices)} given; allowed: none with "
              f"layout {sc.layout!r} (only with 'polyline')")
    n = link_count(sc, L)
    if n < 2:
        fail(where, "scene.length", f"{sc.length:g} m is {n} link(s) of {L:g} m; allowed: "
              f"at least {2 * L:g} m (2 links)")
    if n > max_links:
        fail(where, "scene.length", f"{sc.length:g} m is {n} links of {L:g} m; allowed: at "
              f"most {max_links * L:g} m ({max_links} links)")
    if sc.layout == "folded":
        arm, _ = fold_arms(n, sc.fold_links)
        if arm < 1:
            fail(where, "scene.fold_links", f"{sc.fold_links} leaves no arm in a chain of "
                  f"{n} links; allowed: at most {n - 2}")
    else:
        for field in ("fold_links", "tilt"):
            value, default = getattr(sc, field), getattr(SceneConfig(), field)
            if value != default:
                fail(where, f"scene.{field}", f"{value!r} has no effect with layout "
                      f"{sc.layout!r} (only with 'folded'); allowed: {default!r} or leave "
                      "it out")
    if sc.jitter == 0.0 and sc.seed != 0:
        fail(where, "scene.seed", f"{sc.seed} has no effect without scene.jitter; allowed: "
              "0, or set scene.jitter")


def _point_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distances of points ``p`` (k, 2) from the segments ``a``-``b`` (each (k, 2) or (2,))."""
    d = b - a
    dd = np.maximum(np.sum(d * d, axis=-1), 1e-300)
    s = np.clip(np.sum((p - a) * d, axis=-1) / dd, 0.0, 1.0)
    return np.hypot(*(a + s[..., None] * d - p).T)


def _crosses(a: np.ndarray, b: np.ndarray, c: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Whether segments ``a``-``b`` (each row) cross the segment ``c``-``e``."""
    def side(p, q, r):
        return np.sign((q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1])
                       - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0]))
    return (side(a, b, c) * side(a, b, e) < 0) & (side(c, e, a) * side(c, e, b) < 0)


def _check_walls(sc: SceneConfig, pts: np.ndarray, radius: float, where: str) -> None:
    """No wall is a point, and the chain starts clear of every wall."""
    if len(sc.walls) > MAX_WALLS:
        fail(where, "scene.walls", f"{len(sc.walls)} given; allowed: at most {MAX_WALLS}")
    a, b = pts[:-1], pts[1:]
    for i, w in enumerate(sc.walls):
        c, e = np.array([w.x0, w.y0]), np.array([w.x1, w.y1])
        if (w.x0, w.y0) == (w.x1, w.y1):
            fail(where, f"scene.walls[{i}]", f"both ends at ({w.x0:g}, {w.y0:g}); allowed: "
                  "two different ends")
        gap = np.minimum(_point_segment(pts, c, e),
                         np.minimum(_point_segment(c[None], a, b), _point_segment(e[None], a, b))
                         .min(initial=np.inf))
        clear = radius + 0.5 * w.thickness
        crossing = _crosses(a, b, c, e)
        if crossing.any() or gap.min() < clear:
            k = int(np.argmax(crossing)) if crossing.any() else int(np.argmin(gap))
            fail(where, f"scene.walls[{i}]", f"({w.x0:g}, {w.y0:g}) - ({w.x1:g}, {w.y1:g}) "
                  f"runs through the chain at its start (near point {k}); allowed: a wall at "
                  f"least {clear:g} m (link_radius + thickness/2) from the chain")


def _point(value: int, n: int, where: str, field: str) -> int:
    if not -(n + 1) <= value <= n:
        fail(where, field, f"{value} is not a point of this chain of {n} links; allowed: "
              f"0 .. {n}, or -{n + 1} .. -1 counted from the end")
    return point_number(value, n)


def _check_pins(sc: SceneConfig, n: int, where: str) -> None:
    seen: dict[int, int] = {}
    for i, pin in enumerate(sc.pins):
        p = _point(pin.point, n, where, f"scene.pins[{i}].point")
        if p in seen:
            fail(where, f"scene.pins[{i}].point", f"{pin.point} is point {p}, pinned by "
                  f"scene.pins[{seen[p]}] already; allowed: one pin per point")
        seen[p] = i


def _check_probes(sc: SceneConfig, n: int, where: str) -> None:
    if len(sc.probes) > MAX_PROBES:
        fail(where, "scene.probes", f"{len(sc.probes)} given; allowed: at most {MAX_PROBES}")
    pinned = {point_number(p.point, n) for p in sc.pins}
    names: set[str] = set()
    for i, probe in enumerate(sc.probes):
        at = f"scene.probes[{i}]"
        if not PROBE_NAME.fullmatch(probe.name):
            fail(where, f"{at}.name", f"{probe.name!r} is not allowed; allowed: 1 to 40 "
                  "letters, digits, '_' or '-' (it names the file probe_<name>.csv)")
        if probe.name in names:
            fail(where, f"{at}.name", f"{probe.name!r} names another probe already; "
                  "allowed: a name of its own")
        names.add(probe.name)
        if probe.kind in ("floor_force", "energy"):
            if probe.point != 0:
                fail(where, f"{at}.point", f"{probe.point} has no effect on a "
                      f"{probe.kind!r} probe; allowed: 0 or leave it out")
            if probe.kind == "floor_force" and sc.floor != "solid":
                fail(where, f"{at}.kind", "'floor_force' needs a floor; allowed: with "
                      "scene.floor = 'solid'")
            continue
        p = _point(probe.point, n, where, f"{at}.point")
        if probe.kind == "tension" and not 0 < p < n:
            fail(where, f"{at}.point", f"{probe.point} is an end of the chain (tension 0); "
                  f"allowed: an interior point, 1 .. {n - 1}")
        if probe.kind == "tension" and any(q > p for q in pinned):
            # the tension is the momentum balance of the links from the last point to p:
            # a pin among them would add a force it does not see
            last = max(pinned)
            allowed = (f"a point beyond the last pin, {last + 1} .. {n - 1}" if last + 1 <= n - 1
                       else f"none while point {last}, the chain's end, is pinned: no interior "
                       "point lies beyond it; read that pin's force with a 'pin_force' probe, "
                       "or pin another point")
            fail(where, f"{at}.point", f"{probe.point} has a pinned point beyond it (toward "
                  f"point {n}), which the tension's momentum balance cannot see; allowed: "
                  + allowed)
        if probe.kind == "pin_force" and p not in pinned:
            fail(where, f"{at}.point", f"{probe.point} is not pinned; allowed: a point of "
                  "scene.pins (" + (", ".join(str(x) for x in sorted(pinned)) or "none") + ")")


def _check_closed_form(sc: SceneConfig, n: int, where: str) -> None:
    form = sc.closed_form
    if form == "none":
        return
    at = "scene.closed_form"
    if abs(sc.velocity_x) + abs(sc.velocity_y) > 0:
        fail(where, at, f"{form!r} starts from rest; allowed: scene.velocity_x = "
              "scene.velocity_y = 0, or closed_form = 'none'")
    if form == "folded_fall":
        pins = [(point_number(p.point, n), p.release) for p in sc.pins]
        if sc.layout != "folded" or pins != [(0, 0.0)] or sc.floor != "none" or \
                sc.walls or abs(sc.angle + math.pi / 2) > HANGING:
            fail(where, at, "'folded_fall' is a folded chain hanging from its pinned point "
                  "0, the other end let go; allowed: with layout 'folded', angle -pi/2 "
                  f"(within {HANGING} rad), one pin at point 0 held all along, no floor, "
                  "no walls")
    if form == "scale":
        if sc.layout != "straight" or sc.pins or sc.floor != "solid" or sc.walls or \
                abs(abs(sc.angle) - math.pi / 2) > HANGING:
            fail(where, at, "'scale' is a straight chain hanging vertically just above a "
                  "solid floor, let go at the start; allowed: with layout 'straight', angle "
                  f"pi/2 or -pi/2 (within {HANGING} rad), no pins, floor 'solid', no walls")
