"""The simulated home as a robot adapter: the simulator's nodes offer the robot port in-process."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Self

from amiro.core.runtime import Runtime
from amiro.sim.simulator import Simulation, build_sim


@dataclass
class SimAdapter:
    """The :class:`~amiro.robot.adapter.RobotAdapter` of the simulated home."""

    simulated: ClassVar[bool] = True
    simulation: Simulation

    @classmethod
    def build(cls, runtime: Runtime, config: Any) -> Self:
        """The simulator built from ``config.sim``."""
        return cls(build_sim(runtime, config.sim))

    def stats(self) -> dict[str, Any]:
        return {"collisions": self.simulation.robot.collisions}

    def close(self) -> None:
        """Nothing to release: the simulator lives in the runtime."""
