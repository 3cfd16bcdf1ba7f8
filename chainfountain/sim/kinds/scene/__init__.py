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


KIND = Kind(
    config=SceneConfig, name="scene", table="scene", title="a scene",
    check=lambda cfg, where: check_scene(cfg, where, MAX_LINKS),
    default_duration=lambda cfg: float(cfg.scene.duration), reach=reach,
    seed_field="scene.seed", unseeded=_unseeded, style=lambda cfg: "scene", fountain=False,
)
