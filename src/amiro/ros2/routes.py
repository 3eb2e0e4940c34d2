"""The topics a deployment can carry over ROS 2: name, bus type, ROS type and QoS.

Contract names (CONTRACTS.md section 5) use standard types; amiro's own topics travel as
JSON in ``std_msgs/String``.  A robot profile may remap the ROS-side name of any of them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from amiro.core.config import ConfigError
from amiro.core.messages import (
    Acknowledgement,
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
from amiro.ros2.boundary import (
    HEARTBEAT_TOPIC,
    OBSERVATIONS_TOPIC,
    SKELETONS_TOPIC,
    CameraObservations,
    Heartbeat,
)
from amiro.ros2.convert import STANDARD_CODECS, Codec, json_codec
from amiro.ros2.people import PEOPLE_TOPIC


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
        Route("/scan", _standard(LaserScan)),
        Route("/odom", _standard(Odometry)),
        Route("/cmd_vel", _standard(Twist)),
        Route("/map", _standard(OccupancyGrid), latched=True, depth=1),
        Route("/tf", _standard(TransformStamped), depth=100),
        Route("/tf_static", _standard(TransformStamped), latched=True, depth=100),
        Route("/goal_pose", _standard(PoseStamped)),
        Route("/amiro/say", _standard(SpeechRequest)),
        Route("/amiro/events", _standard(BehaviorEvent), depth=1000),
        # amiro's robot-side topics
        Route("/joint_states", _standard(JointState)),
        Route("/amiro/head/cmd", _standard(JointState)),
        Route("/amiro/display", _standard(String)),
        Route("/amiro/emergency_stop", _standard(String)),
        Route("/amiro/posture", _standard(String)),
        Route("/camera/image_raw", _standard(Image), depth=2),
        Route("/camera/depth/image_raw", _standard(Image), depth=2),
        Route("/camera/camera_info", _standard(CameraInfo), depth=2),
        Route("/amiro/speech/heard", json_codec(SpeechHeard), depth=50),
        Route("/amiro/sim/ground_truth", _standard(Pose2D), depth=1),
        Route("/amiro/localization/pose", _standard(Pose2D), depth=1),
        Route(OBSERVATIONS_TOPIC, json_codec(CameraObservations), depth=1),
        Route(SKELETONS_TOPIC, _standard(Skeleton), depth=200),  # a person's history at once
        Route(PEOPLE_TOPIC, json_codec(People), depth=1),  # the edge's tracks, for the dashboard
        # smart environment and deployment health
        Route("/amiro/env/sensors", json_codec(SensorReading), depth=100),
        Route("/amiro/notifications", json_codec(Notification), depth=100),
        Route("/amiro/notifications/ack", json_codec(Acknowledgement), depth=100),
        Route(HEARTBEAT_TOPIC, json_codec(Heartbeat), depth=50),
    )
}


def route(topic: str) -> Route:
    found = ROUTES.get(topic)
    if found is None:
        raise ConfigError(f"no ROS 2 route for topic {topic} (known: {', '.join(sorted(ROUTES))})")
    return found
