"""The robot adapter: the one interface behind which amiro drives any robot.

An adapter adds to the runtime the nodes that offer the robot port's topics (``core.names``:
scan, odometry, joint states, camera in; velocity, head, speech, display out) and keeps the
connections they need.  Three ship, chosen by name (``robot.adapter``) through the registry:
``sim`` (the simulated home, :mod:`amiro.sim.adapter`), ``ros2`` (any ROS 2 robot through its
driver) and ``naoqi`` (Pepper's channels over NAOqi beside a ROS 2 driver).  A new robot is
one class with this shape and one ``register("robot", name, "pkg.module:factory")`` call.
"""

from __future__ import annotations

from typing import Any, ClassVar, Protocol

from amiro.core import registry
from amiro.core.runtime import Runtime


class RobotAdapter(Protocol):
    """What the assembly needs from a robot besides its topics."""

    # True when time and the world are simulated (a scenario's report may read ground
    # truth; the runtime runs on a simulated clock); a real robot runs on wall time.
    simulated: ClassVar[bool]

    @classmethod
    def build(cls, runtime: Runtime, config: Any) -> RobotAdapter:
        """Build the adapter into ``runtime`` from the system config (its ``robot`` section,
        and ``sim`` for the simulator)."""
        ...

    def stats(self) -> dict[str, Any]:
        """Counters for reports and the dashboard (messages, commands, errors)."""
        ...

    def close(self) -> None:
        """Release connections, after the runtime stopped (the base's last stop goes out)."""
        ...


registry.register("robot", "sim", "amiro.sim.adapter:SimAdapter")
registry.register("robot", "ros2", "amiro.robot.build:RealRobot")
registry.register("robot", "naoqi", "amiro.robot.build:RealRobot")


def adapter_type(name: str) -> type[RobotAdapter]:
    """The adapter class registered as ``name`` (its module imported now)."""
    cls: type[RobotAdapter] = registry.resolve("robot", name)
    return cls
