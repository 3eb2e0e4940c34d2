"""Which robot amiro drives: ``robot: {adapter: sim|ros2|naoqi, profile: ..., ...}``.

``sim`` is the simulated home (the default).  ``ros2`` drives a robot through its ROS 2
driver, named by the profile.  ``naoqi`` drives Pepper through NAOqi alone.  A ``ros2``
robot may also hand some channels to NAOqi (``naoqi.handles``): on Pepper, naoqi_driver2
for the laser, odometry and base, NAOqi for multilingual speech, the tablet, head, posture.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, model_validator

from amiro.core.config import Section
from amiro.core.registry import backend_name
from amiro.robot import adapter as _adapters  # noqa: F401 - registers the robot adapters
from amiro.ros2.context import RosSection

NaoqiChannel = Literal["say", "display", "head", "base", "posture", "odom"]
ALL_NAOQI: tuple[NaoqiChannel, ...] = ("say", "display", "head", "base", "posture", "odom")


class NaoqiConnection(Section):
    url: str = Field(default="tcp://127.0.0.1:9559", description="NAOqi's address")
    handles: tuple[NaoqiChannel, ...] | None = Field(
        default=None,
        description="channels driven over NAOqi; default: all for adapter naoqi, "
        "say/display/head/posture beside a ros2 adapter",
    )


class RobotConfig(Section):
    adapter: Annotated[str, backend_name("robot")] = Field(
        default="sim", description="a registered robot adapter (sim, ros2, naoqi)"
    )
    profile: str = Field(default="pepper", description="shipped profile name or YAML file")
    ros: RosSection = Field(default_factory=RosSection)
    naoqi: NaoqiConnection | None = None

    @model_validator(mode="after")
    def _consistent(self) -> RobotConfig:
        if self.adapter == "naoqi" and self.naoqi is None:
            raise ValueError("adapter naoqi needs naoqi.url")
        if self.adapter == "ros2" and "odom" in self.naoqi_channels():
            raise ValueError("odometry comes from the ROS 2 driver: drop odom from naoqi.handles")
        return self

    def naoqi_channels(self) -> tuple[NaoqiChannel, ...]:
        if self.naoqi is None:
            return ()
        if self.naoqi.handles is not None:
            return self.naoqi.handles
        return ALL_NAOQI if self.adapter == "naoqi" else ("say", "display", "head", "posture")
