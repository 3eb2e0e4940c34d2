"""Robot profiles: what a real robot's driver calls things and what the robot can do.

A profile (YAML in ``amiro/data/robots/`` or any file) names the driver's topics and frames,
the base type (a differential base never moves sideways), the velocity and acceleration
limits commands are clamped to, where the laser sits on the base, and the head's range.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path
from typing import Literal

from pydantic import Field, model_validator

from amiro.core import names
from amiro.core.config import ConfigError, Section, load

BaseType = Literal["differential", "omnidirectional"]


class Limits(Section):
    max_linear: float = Field(gt=0, description="m/s; for an omni base, on the norm of vx, vy")
    max_angular: float = Field(gt=0, description="rad/s")
    max_linear_accel: float = Field(gt=0, description="m/s^2")
    max_angular_accel: float = Field(gt=0, description="rad/s^2")


class Mount(Section):
    """Where the driver's laser frame sits in the base frame (planar)."""

    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0
    upside_down: bool = False  # mounted flipped: beam angles run clockwise

    @property
    def is_identity(self) -> bool:
        return self.x == 0.0 and self.y == 0.0 and self.yaw == 0.0 and not self.upside_down


class Frames(Section):
    """The driver's frame names; amiro renames them to REP-105's on the way in."""

    odom: str = "odom"
    base: str = "base_footprint"
    laser: str = "laser"
    camera: str = "camera"


class Topics(Section):
    """The driver's topic names; None where the robot has no such topic."""

    scan: str = names.SCAN
    odom: str = names.ODOM
    cmd_vel: str = names.CMD_VEL
    joint_states: str | None = names.JOINT_STATES
    head_cmd: str | None = Field(default=None, description="sensor_msgs/JointState targets")
    speech: str | None = Field(default=None, description="std_msgs/String text to say")
    image: str | None = None
    depth: str | None = None
    camera_info: str | None = None


class Head(Section):
    """The pan-tilt head: the driver's joint names and their ranges (rad)."""

    yaw_joint: str = names.HEAD_YAW
    pitch_joint: str = names.HEAD_PITCH
    yaw_limits: tuple[float, float]
    pitch_limits: tuple[float, float]
    speed: float = Field(default=0.2, gt=0, le=1, description="NAOqi: fraction of max speed")

    @model_validator(mode="after")
    def _ordered(self) -> Head:
        for name, (low, high) in (("yaw", self.yaw_limits), ("pitch", self.pitch_limits)):
            if low > high:
                raise ValueError(f"{name}_limits: lower bound above upper bound")
        return self


class Naoqi(Section):
    """What a NAOqi robot needs beyond ROS: its TTS language names and start-up posture."""

    languages: dict[str, str] = Field(
        default_factory=lambda: {"en": "English", "fr": "French"},
        description="amiro language code -> ALTextToSpeech language name",
    )
    default_language: str = "English"
    posture_on_start: str | None = Field(default="Stand", description="ALRobotPosture name")
    posture_speed: float = Field(default=0.5, gt=0, le=1)
    wake_up: bool = True


class RobotProfile(Section):
    name: str
    description: str = ""
    base: BaseType
    limits: Limits
    cmd_rate_hz: float = Field(default=20.0, gt=0, description="velocity commands sent per s")
    cmd_timeout_s: float = Field(default=0.5, gt=0, description="stop without fresh /cmd_vel")
    frames: Frames = Field(default_factory=Frames)
    laser_mount: Mount = Field(default_factory=Mount)
    topics: Topics = Field(default_factory=Topics)
    head: Head | None = None
    naoqi: Naoqi | None = None


def shipped_profiles() -> dict[str, Path]:
    """The profiles amiro ships, by name."""
    folder = Path(str(resources.files("amiro").joinpath("data/robots")))
    return {p.stem: p for p in sorted(folder.glob("*.yaml"))}


def load_profile(name_or_path: str | Path) -> RobotProfile:
    """A shipped profile by name (``pepper``) or a profile YAML file."""
    shipped = shipped_profiles()
    if str(name_or_path) in shipped:
        return load(RobotProfile, shipped[str(name_or_path)])
    path = Path(name_or_path)
    if path.suffix in (".yaml", ".yml") or path.exists():
        return load(RobotProfile, path)
    raise ConfigError(
        f"unknown robot profile '{name_or_path}' (shipped: {', '.join(shipped)}; or a YAML file)"
    )
