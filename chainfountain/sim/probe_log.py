"""The probes' time series of a scene run, in arrays of a fixed size (a bounded buffer)."""

from __future__ import annotations

import numpy as np

from chainfountain.sim.scene_config import ProbeConfig
from chainfountain.sim.scene_sim import COLUMNS, SceneSimulation


class ProbeLog:
    """Up to ``capacity`` samples of every probe: the time and the probe's columns
    (:data:`chainfountain.sim.scene_sim.COLUMNS`); samples beyond are not kept."""

    def __init__(self, probes: tuple[ProbeConfig, ...], capacity: int) -> None:
        self.probes = probes
        self.capacity = int(capacity)
        self.t = np.empty(self.capacity)
        self._data = [np.empty((self.capacity, len(COLUMNS[p.kind]))) for p in probes]
        self.n = 0

    def sample(self, sim: SceneSimulation) -> None:
        """Read every probe now (call :meth:`SceneSimulation.end_sample` first)."""
        if self.n >= self.capacity:
            return
        self.t[self.n] = sim.time
        for probe, data in zip(self.probes, self._data, strict=True):
            data[self.n] = sim.read(probe)
        self.n += 1

    def columns(self, index: int) -> dict[str, np.ndarray]:
        """Probe ``index``'s series by column name, ``t`` first."""
        probe = self.probes[index]
        data = self._data[index][: self.n]
        return {"t": self.t[: self.n], **{c: data[:, k] for k, c in
                                          enumerate(COLUMNS[probe.kind])}}

    def by_name(self, name: str) -> dict[str, np.ndarray]:
        """:meth:`columns` of the probe called ``name``."""
        for i, p in enumerate(self.probes):
            if p.name == name:
                return self.columns(i)
        raise KeyError(name)
