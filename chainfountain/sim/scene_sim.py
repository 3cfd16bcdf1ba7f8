"""A scene level running: its chain laid out, pinned, given its start velocity, over its
floor; pins let go at their times; probes read at every sample.

:class:`SceneSimulation` is to a ``kind = "scene"`` level what
:class:`chainfountain.sim.world.Simulation` is to a fountain: it only steps and reads.
"""

from __future__ import annotations

import numpy as np

from chainfountain.sim.config import SimConfig
from chainfountain.sim.scene import ChainScene, Pin
from chainfountain.sim.scene_config import ProbeConfig, point_number
from chainfountain.sim.scene_layout import chain_points

COLUMNS: dict[str, tuple[str, ...]] = {
    "point": ("x", "y", "vx", "vy"),
    "tension": ("T",),
    "pin_force": ("F",),
    "floor_force": ("fx", "fy"),
    "energy": ("kinetic", "potential", "total"),
}
"""The columns each probe kind records (after the time ``t``), in SI units."""
FLOOR_MARGIN = 1.0
"""The floor reaches this far (m) beyond the chain's length on each side of its start."""


class SceneSimulation:
    """A scene level, built from its configuration and ready to step."""

    def __init__(self, config: SimConfig) -> None:
        sc = config.scene
        self.config = config
        pts = chain_points(sc, config.chain.link_length)
        collide = sc.floor == "solid" or bool(sc.walls) or config.chain.self_collision
        self.scene = ChainScene(pts, gravity=config.gravity, solver=config.solver,
                                collide=collide, chain=config.chain)
        self.n = self.scene.n
        if sc.velocity_x or sc.velocity_y:
            self.scene.set_velocity(sc.velocity_x, sc.velocity_y)
        if sc.floor == "solid":
            reach = self.n * self.scene.L + FLOOR_MARGIN
            x0 = float(pts[:, 0].mean())
            self.scene.add_floor(sc.floor_y, x0 - reach, x0 + reach,
                                 friction=config.chain.friction)
        for w in sc.walls:
            self.scene.add_wall((w.x0, w.y0), (w.x1, w.y1), 0.5 * w.thickness,
                                friction=config.chain.friction)
        self.pins: list[tuple[Pin, float]] = [
            (self.scene.pin(point_number(p.point, self.n)), p.release) for p in sc.pins]
        self._pin_at = {pin.point: i for i, (pin, _) in enumerate(self.pins)}
        self._forces = (np.zeros(len(self.pins)), np.zeros(2))

    @property
    def time(self) -> float:
        return self.scene.time

    @property
    def dt(self) -> float:
        return self.scene.solver.dt

    def step(self) -> None:
        """One time step; pins whose release time has come let go first."""
        t = self.scene.time
        for pin, release in self.pins:
            if 0.0 < release <= t + 0.5 * self.dt and not pin.released:
                self.scene.release(pin)
        self.scene.step()

    def end_sample(self) -> None:
        """Close a sample interval: the mean forces :meth:`read` gives are over the time
        since the last call."""
        self._forces = self.scene.take_means()

    def read(self, probe: ProbeConfig) -> tuple[float, ...]:
        """The probe's values now (:data:`COLUMNS`); forces are the means over the last
        sample interval (:meth:`end_sample`)."""
        return _READERS[probe.kind](self, probe)

    def _point(self, probe: ProbeConfig) -> tuple[float, ...]:
        p = point_number(probe.point, self.n)
        (x, y), (vx, vy) = self.scene.points()[p], self.scene.point_velocity(p)
        return float(x), float(y), float(vx), float(vy)

    def _tension(self, probe: ProbeConfig) -> tuple[float, ...]:
        return (float(self.scene.tensions()[point_number(probe.point, self.n) - 1]),)

    def _pin_force(self, probe: ProbeConfig) -> tuple[float, ...]:
        return (float(self._forces[0][self._pin_at[point_number(probe.point, self.n)]]),)

    def _floor_force(self, probe: ProbeConfig) -> tuple[float, ...]:
        fx, fy = self._forces[1]
        return float(fx), float(fy)

    def _energy(self, probe: ProbeConfig) -> tuple[float, ...]:
        sc = self.scene
        kinetic = sc.kinetic_energy()
        mass = sc.chain.mass
        potential = float(sum(mass * sc.g * lk.body.position.y for lk in sc.chain.links))
        return kinetic, potential, kinetic + potential

    def finite(self) -> bool:
        """Whether every link end is a finite number (the run has not blown up)."""
        return bool(np.isfinite(self.scene.points()).all())


_READERS = {"point": SceneSimulation._point, "tension": SceneSimulation._tension,
            "pin_force": SceneSimulation._pin_force, "floor_force": SceneSimulation._floor_force,
            "energy": SceneSimulation._energy}
"""What each probe kind reads (:data:`~chainfountain.sim.probe_log.COLUMNS`)."""
