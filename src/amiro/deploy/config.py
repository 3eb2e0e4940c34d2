"""Configuration of one deployment process (``amiro node NAME --config FILE``).

A process has a role: ``sim`` (the robot: simulator, or a real robot's adapter), ``edge``
(navigation, perception, activity, behaviour engine) or ``cloud`` (smart environment,
notifications' ledger, watchdog; with ``serve_services: [/amiro/dialogue/understand]`` also
the dialogue, with ``web:`` also the dashboard).  Unset topic lists take the role's defaults
below.
"""

from __future__ import annotations

from pathlib import Path
from typing import Literal

from pydantic import Field, model_validator

from amiro.core import names
from amiro.core.config import Section
from amiro.ros2.context import RosSection
from amiro.web.config import WebConfig

Role = Literal["sim", "edge", "cloud"]

DEFAULT_PUBLISH: dict[str, tuple[str, ...]] = {
    "sim": (
        names.SCAN,
        names.ODOM,
        names.TF,
        names.TF_STATIC,
        names.MAP,
        names.JOINT_STATES,
        names.GROUND_TRUTH,
        names.OBSERVATIONS,  # the simulated head camera's frame
        names.SKELETONS,
        names.CAMERA_INFO,
        names.HEARD,
        names.HEARTBEAT,
    ),
    "edge": (
        names.CMD_VEL,
        names.TF,  # map -> odom from localisation
        names.HEAD_CMD,
        names.SAY,
        names.DISPLAY,
        names.EVENTS,
        names.ACK,
        names.HEARTBEAT,
        names.PEOPLE,  # the people perception tracks, for the cloud's dashboard
    ),
    "cloud": (names.NOTIFICATIONS, names.SENSORS),
}
DEFAULT_SUBSCRIBE: dict[str, tuple[str, ...]] = {
    # an operator's stop over ROS 2 reaches the robot adapter and, on the edge, the mux
    "sim": (names.CMD_VEL, names.HEAD_CMD, names.SAY, names.EMERGENCY_STOP),
    "edge": (
        names.SCAN,
        names.ODOM,  # AMCL, the default localisation, needs odometry as well as the scan
        names.GROUND_TRUTH,
        # perception and activity: the camera's frame and intrinsics, head joints, skeletons
        names.OBSERVATIONS,
        names.CAMERA_INFO,
        names.JOINT_STATES,
        names.SKELETONS,
        names.HEARD,
        names.NOTIFICATIONS,
        names.EMERGENCY_STOP,
    ),
    "cloud": (names.EVENTS, names.ACK, names.HEARTBEAT, names.PEOPLE),
}

# An edge driving a real robot: the robot adapter (``robot.adapter: ros2`` in its system
# config) carries the driver's topics (scan, odometry, camera, joints, velocity, head,
# speech) with the profile's names and limits, so the bridge leaves them alone.  /tf is not
# exported either: it would re-send the driver's own odom frame beside map -> odom.
ROBOT_EDGE_PUBLISH = (
    names.DISPLAY,
    names.EVENTS,
    names.ACK,
    names.HEARTBEAT,
    names.PEOPLE,
)
ROBOT_EDGE_SUBSCRIBE = (names.HEARD, names.NOTIFICATIONS, names.EMERGENCY_STOP)


# What a sim process with a rendered camera exports besides its defaults (the robot port's).
CAMERA_TOPICS = (names.IMAGE, names.DEPTH, names.CAMERA_INFO)


class SimCameraSection(Section):
    """``camera:`` of a sim process: render the head camera's images at this rate and size."""

    rate_hz: float = Field(default=2.0, gt=0.0, le=30.0, description="frames per sim second")
    width: int = Field(default=320, ge=32, le=1920, description="pixels")
    height: int = Field(default=240, ge=24, le=1080, description="pixels")


class NodeConfig(Section):
    role: Role
    ros: RosSection = Field(default_factory=RosSection)
    clock: Literal["follow", "wall"] = Field(
        default="follow",
        description="edge/cloud: follow the robot process's /clock (the simulator's time), "
        "or run on wall time (a real robot's driver publishes no /clock)",
    )
    scenario: Literal["hydration"] | None = Field(
        default="hydration", description="the household and triggers to load"
    )
    system: Path | None = Field(
        default=None, description="SystemConfig YAML (amiro node: relative to the node's file)"
    )
    speed: float | None = Field(default=1.0, gt=0, description="sim: sim seconds per real second")
    wait_for: tuple[str, ...] = Field(
        default=(), description="sim: ROS node names to wait for before time starts"
    )
    wait_timeout_s: float = Field(default=30.0, gt=0)
    publish: tuple[str, ...] | None = None
    subscribe: tuple[str, ...] | None = None
    publish_also: tuple[str, ...] = Field(
        default=(), description="topics exported besides ``publish`` (or the role's defaults)"
    )
    subscribe_also: tuple[str, ...] = Field(
        default=(), description="topics imported besides ``subscribe`` (or the defaults)"
    )
    remap: dict[str, str] = Field(default_factory=dict)
    hear_audio: bool = Field(
        default=False,
        description="sim: voice the residents' replies onto /amiro/audio (the robot's "
        "microphone) instead of sending their text on /amiro/speech/heard; edge or cloud: "
        "recognise /amiro/audio here (dialogue.asr, loaded at start) and publish the "
        "transcripts on /amiro/speech/heard",
    )
    serve_actions: tuple[str, ...] = Field(
        default=(), description="actions whose server runs here, offered over ROS 2"
    )
    call_actions: tuple[str, ...] = Field(
        default=(), description="actions served by another process, sent from here"
    )
    serve_services: tuple[str, ...] = Field(
        default=(), description="services answered here, offered over ROS 2"
    )
    call_services: tuple[str, ...] = Field(
        default=(), description="services answered by another process, called from here"
    )
    action_timeout_s: float = Field(
        default=3.0, gt=0, description="a remote goal unheard of this long (sim s) aborts"
    )
    heartbeat_s: float = Field(default=1.0, gt=0)
    hri: bool = Field(
        default=False,
        description="edge: also publish the people perception tracks on ROS4HRI (REP-155): "
        "/humans/... topics and person_<id> / body_<id> frames on /tf",
    )
    watch: dict[str, float] = Field(
        default_factory=dict, description="cloud: process name -> heartbeat timeout (s)"
    )
    web: WebConfig | None = Field(
        default=None,
        description="cloud: serve the dashboard (needs call_actions: [/amiro/behavior/run])",
    )
    camera: SimCameraSection | None = Field(
        default=None,
        description="sim: publish rendered RGB, depth and CameraInfo as a real robot's camera "
        "would (``amiro sim --ros2`` turns it on)",
    )
    ledger_path: Path | None = Field(
        default=None,
        description="cloud: keep the pending notifications and their checkpoints in this JSON "
        "file, so a restarted cloud re-sends them (relative: to the directory of the "
        "process's --events file, the launcher's log dir; else the working directory)",
    )
    stop_after_acks: int | None = Field(default=None, ge=1)
    duration_s: float | None = Field(default=None, gt=0)

    @model_validator(mode="after")
    def _sim_owns_time(self) -> NodeConfig:
        if self.role == "sim" and self.clock == "wall":
            raise ValueError("clock: wall is for edge and cloud; the sim role owns simulated time")
        return self

    def topics_out(self, robot: bool = False) -> tuple[str, ...]:
        """``robot``: an edge whose robot adapter carries the driver's topics itself."""
        defaults = ROBOT_EDGE_PUBLISH if robot else DEFAULT_PUBLISH[self.role]
        base = defaults if self.publish is None else self.publish
        rendered = CAMERA_TOPICS if self.role == "sim" and self.camera is not None else ()
        topics = _merged(base, (*self.publish_also, *rendered))
        if not self.hear_audio:
            return topics
        if self.role == "sim":  # the replies go out as audio, not as text
            return _merged(tuple(t for t in topics if t != names.HEARD), (names.AUDIO,))
        return _merged(topics, (names.HEARD,)) if self.role == "cloud" else topics

    def topics_in(self, robot: bool = False) -> tuple[str, ...]:
        defaults = ROBOT_EDGE_SUBSCRIBE if robot else DEFAULT_SUBSCRIBE[self.role]
        base = defaults if self.subscribe is None else self.subscribe
        topics = _merged(base, self.subscribe_also)
        if not self.hear_audio or self.role == "sim":
            return topics
        # heard here: the audio comes in, the transcripts are this process's own, and the
        # language listened for is the one the robot last spoke (/amiro/say, the edge's)
        said = () if names.SAY in self.topics_out(robot) else (names.SAY,)
        return _merged(tuple(t for t in topics if t != names.HEARD), (names.AUDIO, *said))

    def ros_node_name(self, process: str) -> str:
        return self.ros.node_name or f"amiro_{process}"

    def with_ledger_base(self, base: Path) -> NodeConfig:
        """This config with a relative ``ledger_path`` taken from ``base``."""
        if self.ledger_path is None or self.ledger_path.is_absolute():
            return self
        return self.model_copy(update={"ledger_path": base / self.ledger_path})


def _merged(base: tuple[str, ...], extra: tuple[str, ...]) -> tuple[str, ...]:
    return tuple(dict.fromkeys((*base, *extra)))
