"""The level kinds behind one registry (as dm_control's suite): each kind one package
declaring its :class:`~chainfountain.sim.kinds.base.Kind`.

=============  ==============================================  =====================
kind           what                                            level file
=============  ==============================================  =====================
``feed``       a motor-fed fountain                            ``kind = "feed"``
``ideal``      the paper's ideal machines                      ``kind = "feed"``, an
                                                               ideal ``feed.drive``
``apparatus``  the pulley apparatus                            ``kind = "apparatus"``
``beaker``     a chain rising from a beaker                    ``kind = "beaker"``
``scene``      a chain laid out by hand, headless              ``kind = "scene"``
=============  ==============================================  =====================

A new kind is a new package here and one line in :data:`REGISTRY`; nothing else asks
which kind a level is.
"""

from __future__ import annotations

from chainfountain.sim.config import SimConfig
from chainfountain.sim.kinds import apparatus, beaker, feed, ideal, scene
from chainfountain.sim.kinds.base import Kind
from chainfountain.sim.watchdog import Limits

REGISTRY: dict[str, Kind] = {k.name: k for k in (feed.KIND, ideal.KIND, apparatus.KIND,
                                                 beaker.KIND, scene.KIND)}
"""Every kind by its name."""


def kind_of(config: SimConfig) -> Kind:
    """The kind of a level's configuration: its ``kind`` table, and for a fed level its
    drive (a motor's feed or an ideal machine)."""
    if config.kind == "feed" and config.feed.drive != "motor":
        return REGISTRY["ideal"]
    try:
        return REGISTRY[config.kind]
    except KeyError:
        raise ValueError(f"unsupported level kind {config.kind!r} (supported: "
                         + ", ".join(repr(k) for k in sorted({k.table for k in
                                                              REGISTRY.values()})) + ")") from None


def limits_for(cfg: SimConfig) -> Limits:
    """The limits of a level: its chain speed and a scene of its size (its kind's
    :attr:`~chainfountain.sim.kinds.base.Kind.reach`: a feed's drop and whole chain, an
    apparatus's tables and run, a beaker's drop and pot) plus the height ``v**2/g`` the
    chain can climb."""
    g = float(cfg.gravity)
    v, size = kind_of(cfg).reach(cfg)
    return Limits.for_level(v, size + v * v / max(g, 1e-9), g)


__all__ = ["REGISTRY", "Kind", "kind_of", "limits_for"]
