"""Adding a real robot's adapters to a runtime, from a :class:`RobotConfig`.

The simulator is built by :func:`amiro.sim.simulator.build_sim`; this builds the others.
Connections (the rclpy participant, the NAOqi session) stay open until :meth:`RealRobot.close`,
called after the runtime has stopped, so the adapters' last commands (stop the base) go out.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar

from amiro.core.config import ConfigError
from amiro.core.runtime import Runtime
from amiro.robot.config import RobotConfig
from amiro.robot.naoqi_adapter import NaoqiRobotNode
from amiro.robot.naoqi_session import NaoqiSession
from amiro.robot.profile import RobotProfile, load_profile
from amiro.robot.ros2_adapter import Ros2RobotNode


@dataclass
class RealRobot:
    """The :class:`~amiro.robot.adapter.RobotAdapter` of a real robot: its ROS 2 driver's
    topics, and NAOqi for the channels configured to go there."""

    simulated: ClassVar[bool] = False
    profile: RobotProfile
    ros2: Ros2RobotNode | None = None
    naoqi: NaoqiRobotNode | None = None
    _closers: list[Any] = field(default_factory=list)

    @classmethod
    def build(cls, runtime: Runtime, config: Any) -> RealRobot:
        """The adapters ``config.robot`` asks for."""
        return build_robot(runtime, config.robot)

    def stats(self) -> dict[str, Any]:
        out: dict[str, Any] = {}
        if self.ros2 is not None:
            s = self.ros2.stats
            out.update(scans=s.scans, odom=s.odom, images=s.images, commands=s.commands)
            out.update(clamped=self.ros2.limiter.clamped, errors=s.errors)
        if self.naoqi is not None:
            out.update(naoqi_calls=self.naoqi.naoqi.calls, naoqi_errors=self.naoqi.naoqi.errors)
        return out

    def close(self) -> None:
        for closer in reversed(self._closers):
            closer.close()
        self._closers.clear()


def build_robot(runtime: Runtime, cfg: RobotConfig) -> RealRobot:
    """The adapters ``cfg`` asks for, added to ``runtime`` (not for ``adapter: sim``)."""
    if cfg.adapter == "sim":
        raise ConfigError("robot.adapter sim is the simulator: build it with build_sim")
    profile = load_profile(cfg.profile)
    robot = RealRobot(profile)
    channels = cfg.naoqi_channels()
    if channels:
        if profile.naoqi is None or profile.head is None:
            raise ConfigError(
                f"robot profile {profile.name} has no naoqi section: not a NAOqi robot"
            )
        assert cfg.naoqi is not None
        session = NaoqiSession(cfg.naoqi.url)
        robot._closers.append(session)
        robot.naoqi = runtime.add(NaoqiRobotNode(session, profile, channels))
    if cfg.adapter == "ros2":
        from amiro.ros2.context import RosContext

        ros = RosContext(
            cfg.ros.node_name or "amiro_robot", cfg.ros.domain_id, cfg.ros.localhost_only
        )
        robot._closers.append(ros)
        skip = [c for c in ("base", "head", "say") if c in channels]
        robot.ros2 = runtime.add(Ros2RobotNode(ros, profile, skip))
    return robot
