"""Suite-wide options.

``--perturb N`` (N > 0) nudges every simulation (fountain or scene level) right after it
is built: each dynamic body's velocity changes by about 1e-12 of itself (seeded by ``N``;
of 1 mm/s at rest), far below anything physical, as a different machine or library build
would change the last bits of a trajectory. Running the suite with ``--perturb 1``,
``2``, ... and comparing the verdicts shows that no test depends on one trajectory of a
chaotic run (``benchmarks/`` has no part in it; see the README, "Tests").

The ``level`` fixture finds a shipped level by name (``level("beaker")``), the one way
the tests find a level (:mod:`tests.shipped`).
"""

from __future__ import annotations

import zlib
from collections.abc import Callable
from typing import TYPE_CHECKING

import pytest

if TYPE_CHECKING:
    from chainfountain.level.model import Level


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--perturb", type=int, default=0, metavar="N",
                     help="nudge every simulation's start by ~1e-12 (seed N; 0: off)")


@pytest.fixture(autouse=True, scope="session")
def _perturb_starts(request: pytest.FixtureRequest):
    seed = request.config.getoption("--perturb")
    if not seed:
        yield
        return
    from chainfountain.sim.world import Simulation

    build = Simulation._build

    def nudged(self: Simulation) -> None:
        build(self)
        # the same configuration gets the same nudge (runs stay deterministic)
        self.nudge((seed, zlib.crc32(repr(self.config).encode())))

    from chainfountain.sim.bodies import nudge_bodies
    from chainfountain.sim.scene_sim import SceneSimulation

    make_scene = SceneSimulation.__init__

    def nudged_scene(self: SceneSimulation, config) -> None:
        make_scene(self, config)
        nudge_bodies(self.scene.space, (seed, zlib.crc32(repr(config).encode())))

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(Simulation, "_build", nudged)
        mp.setattr(SceneSimulation, "__init__", nudged_scene)
        yield


@pytest.fixture(scope="session")
def level() -> Callable[[str], Level]:
    """``level("beaker")``: the shipped level of that name, parsed afresh
    (:func:`tests.shipped.level`; session-scoped, so module-scoped runs can take it)."""
    from tests import shipped

    return shipped.level
