"""A scene (``kind = "scene"``): a chain laid out by hand, pinned, released and measured
against closed forms (:mod:`chainfountain.sim.scene_sim`); it runs headless only."""

from __future__ import annotations

from chainfountain.sim.config import SimConfig
from chainfountain.sim.kinds.base import Kind
from chainfountain.sim.kinds.scene.checks import check_scene
from chainfountain.sim.kinds.sizing import MAX_LINKS
from chainfountain.sim.scene_config import SceneConfig


def reach(cfg: SimConfig) -> tuple[float, float]:
    """A scene's speed and size come from its layout (its own limits)."""
    return 0.0, 0.0


def _unseeded(cfg: SimConfig) -> str | None:
    if cfg.scene.jitter > 0:
        return None
    return "its scene.jitter is 0: no random angles to seed"


SOLVER_DEFAULTS = {"substeps": 8, "iterations": 2}
"""A scene's ``[solver]`` when its file gives none: 8 pymunk steps of 31 us a 250-us step,
2 iterations each (the shipped scenes' table). With the fed fountains' 1 x 25 a folded
chain that falls whips its free end too slowly: 2 m of 2-cm links -0.5 / -1.8 / -12 % at
25 / 50 / 75 % of the fall, 0.6 m of 5-mm links -1.0 / -9.8 / -30 %; with these
-0.2 / -0.3 / -1.0 % and -0.3 / -0.7 / -2.4 %, at the same cost (real-time factor 0.19
against 0.20, 0.15 against 0.18)."""


KIND = Kind(
    config=SceneConfig, name="scene", table="scene", title="a scene",
    check=lambda cfg, where: check_scene(cfg, where, MAX_LINKS),
    default_duration=lambda cfg: float(cfg.scene.duration), reach=reach,
    seed_field="scene.seed", unseeded=_unseeded, style=lambda cfg: "scene", fountain=False,
    solver_defaults=SOLVER_DEFAULTS,
)
