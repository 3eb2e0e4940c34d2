"""The topics a deployment can carry over ROS 2: name, bus type, ROS type and QoS.

Contract names (CONTRACTS.md section 5) use standard types; amiro's own topics travel as
JSON in ``std_msgs/String``.  A robot profile may remap the ROS-side name of any of them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from amiro.core import names
from amiro.core.config import ConfigError
from amiro.core.messages import (
    Acknowledgement,
    AudioStamped,
    BehaviorEvent,
    CameraInfo,
    Image,
    JointState,
    LaserScan,
    Notification,
    OccupancyGrid,
    Odometry,
    People,
    Pose2D,
    PoseStamped,
    SensorReading,
    Skeleton,
    SpeechHeard,
    SpeechRequest,
    String,
    TransformStamped,
    Twist,
)
from amiro.ros2.convert import STANDARD_CODECS, Codec, json_codec


@dataclass(frozen=True)
class Route:
    topic: str
    codec: Codec[Any]
    latched: bool = False  # transient-local durability: late joiners get the last message
    depth: int = 10


def _standard(bus_type: type) -> Codec[Any]:
    return next(c for c in STANDARD_CODECS if c.bus_type is bus_type)


ROUTES: dict[str, Route] = {
    r.topic: r
    for r in (
        # CONTRACTS.md section 5
        Route(names.SCAN, _standard(LaserScan)),
        Route(names.ODOM, _standard(Odometry)),
        Route(names.CMD_VEL, _standard(Twist)),
        Route(names.MAP, _standard(OccupancyGrid), latched=True, depth=1),
        Route(names.TF, _standard(TransformStamped), depth=100),
        Route(names.TF_STATIC, _standard(TransformStamped), latched=True, depth=100),
        Route(names.GOAL_POSE, _standard(PoseStamped)),
        Route(names.SAY, _standard(SpeechRequest)),
        Route(names.EVENTS, _standard(BehaviorEvent), depth=1000),
        # amiro's robot-side topics
        Route(names.JOINT_STATES, _standard(JointState)),
        Route(names.HEAD_CMD, _standard(JointState)),
        Route(names.DISPLAY, _standard(String)),
        Route(names.EMERGENCY_STOP, _standard(String)),
        Route(names.POSTURE, _standard(String)),
        Route(names.IMAGE, _standard(Image), depth=2),
        Route(names.DEPTH, _standard(Image), depth=2),
        Route(names.CAMERA_INFO, _standard(CameraInfo), depth=2),
        Route(names.HEARD, json_codec(SpeechHeard), depth=50),
        Route(names.AUDIO, _standard(AudioStamped), depth=100),  # the microphone's chunks
        Route(names.GROUND_TRUTH, _standard(Pose2D), depth=1),
        Route(names.LOCALIZATION, _standard(Pose2D), depth=1),
        Route(names.SKELETONS, _standard(Skeleton), depth=200),  # a person's history at once
        Route(names.PEOPLE, json_codec(People), depth=1),  # the edge's tracks, for the dashboard
        # smart environment and deployment health
        Route(names.SENSORS, json_codec(SensorReading), depth=100),
        Route(names.NOTIFICATIONS, json_codec(Notification), depth=100),
        Route(names.ACK, json_codec(Acknowledgement), depth=100),
    )
}


def add_route(r: Route) -> None:
    """Carry a topic whose message type lives in a layer above the transport (a split
    deployment's heartbeats, the simulated camera's frames)."""
    ROUTES[r.topic] = r


def route(topic: str) -> Route:
    found = ROUTES.get(topic)
    if found is None:
        raise ConfigError(f"no ROS 2 route for topic {topic} (known: {', '.join(sorted(ROUTES))})")
    return found
