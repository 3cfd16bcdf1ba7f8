"""Where a scene's chain lies at the start: its link ends, ``(N + 1, 2)`` m, every
segment one link long (:class:`chainfountain.sim.scene.ChainScene` takes them as is)."""

from __future__ import annotations

import math

import numpy as np

from chainfountain.sim.scene_config import SceneConfig


def link_count(scene: SceneConfig, L: float) -> int:
    """Links of a 'straight' or 'folded' chain: its length in whole links (rounded)."""
    return int(round(scene.length / L))


def _walk(start: tuple[float, float], angles: np.ndarray, L: float) -> np.ndarray:
    steps = L * np.column_stack((np.cos(angles), np.sin(angles)))
    return np.vstack(([start], start + np.cumsum(steps, axis=0)))


def _jitter(scene: SceneConfig, n: int) -> np.ndarray:
    if scene.jitter == 0.0:
        return np.zeros(n)
    return scene.jitter * np.random.default_rng(scene.seed).standard_normal(n)


def straight(scene: SceneConfig, L: float) -> np.ndarray:
    """A line of :func:`link_count` links from ``(x, y)`` at ``angle``, each link turned by
    its jitter."""
    n = link_count(scene, L)
    return _walk((scene.x, scene.y), scene.angle + _jitter(scene, n), L)


def fold_arms(n: int, fold_links: int) -> tuple[int, int]:
    """Links in each arm and in the U of a folded chain of ``n`` links (the U takes what
    the two equal arms leave)."""
    arm = (n - fold_links) // 2
    return arm, n - 2 * arm


def folded(scene: SceneConfig, L: float) -> np.ndarray:
    """Two arms side by side joined at the far end by a U of ``fold_links`` links turning
    through 180 degrees: the first arm leaves ``(x, y)`` at ``angle``, the U turns to its
    left, the second arm comes back beside the first; both lean ``tilt`` toward the U's
    side. The last point (the free end) lies next to point 0."""
    n = link_count(scene, L)
    arm, u = fold_arms(n, scene.fold_links)
    a = scene.angle
    turn = [a + scene.tilt] * arm
    turn += [a + math.pi * (k + 0.5) / u for k in range(u)]
    turn += [a + math.pi + scene.tilt] * arm
    return _walk((scene.x, scene.y), np.array(turn) + _jitter(scene, n), L)


def along_polyline(vertices: np.ndarray, L: float) -> np.ndarray:
    """Points along the polyline ``vertices`` from its first corner, each exactly ``L``
    from the one before (it cuts the corners by chords), as many as fit."""
    pts = [vertices[0].astype(float)]
    seg, s_now = 0, 0.0
    while True:
        p = pts[-1]
        for j in range(seg, len(vertices) - 1):
            a, b = vertices[j], vertices[j + 1]
            d, f = b - a, a - p
            A = float(d @ d)
            if A == 0.0:
                continue
            B, C = 2.0 * float(f @ d), float(f @ f) - L * L
            disc = B * B - 4.0 * A * C
            if disc < 0.0:
                continue
            s = (-B + math.sqrt(disc)) / (2.0 * A)  # where the path leaves the circle
            if (s > s_now if j == seg else s >= 0.0) and s <= 1.0:
                pts.append(a + s * d)
                seg, s_now = j, s
                break
        else:
            return np.array(pts)


def chain_points(scene: SceneConfig, L: float) -> np.ndarray:
    """The scene's chain at the start, by its layout."""
    if scene.layout == "straight":
        return straight(scene, L)
    if scene.layout == "folded":
        return folded(scene, L)
    corners = np.array([(v.x, v.y) for v in scene.vertices], dtype=float)
    return along_polyline(corners, L)
