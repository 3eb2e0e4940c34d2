"""Codecs: every route survives bus -> ROS 2 -> bus, through rclpy and through rosbags CDR."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from amiro.core.messages import (
    BehaviorEvent,
    Header,
    JointState,
    LaserScan,
    MapMetaData,
    OccupancyGrid,
    Odometry,
    Pose,
    Pose2D,
    Quaternion,
    SpeechRequest,
    String,
    TransformStamped,
    Twist,
    Vector3,
)
from amiro.ros2.convert import bus_say, ros_time, seconds
from amiro.ros2.routes import ROUTES, route
from amiro.ros2.types import RclpyTypes, RosbagsTypes

SCAN = LaserScan(
    Header(12.25, "laser"), -1.5, 1.5, 0.01, 0.0, 0.1, 0.05, 8.0, np.linspace(0.1, 7.9, 301)
)
ODOM = Odometry(
    Header(3.5, "odom"),
    "base_footprint",
    Pose2D(1.0, -2.0, 0.7).to_pose(),
    Twist.planar(0.3, 0.1, -0.2),
)
GRID = OccupancyGrid(
    Header(0.0, "map"),
    MapMetaData(0.05, 4, 3, Pose()),
    np.array([[0, 100, -1, 0], [0, 0, 0, 100], [-1, -1, 0, 0]], dtype=np.int8),
)
SAMPLES: dict[str, Any] = {
    "/scan": SCAN,
    "/odom": ODOM,
    "/map": GRID,
    "/cmd_vel": Twist.planar(0.2, 0.0, 0.5),
    "/tf": TransformStamped(
        Header(1.0, "odom"), "base_footprint", Vector3(1, 2, 0), Quaternion.from_yaw(0.3)
    ),
    "/joint_states": JointState(Header(2.0, ""), ("HeadYaw", "HeadPitch"), (0.1, -0.2)),
    "/amiro/say": SpeechRequest(
        "Drink some water", lang="fr", act="hydration_reminder", addressee="maria"
    ),
    "/amiro/events": BehaviorEvent(
        4.5, "task_started", "hydration#1", "search", {"task_type": "Search"}
    ),
    "/amiro/display": String("hello"),
    "/amiro/sim/ground_truth": Pose2D(1.5, 2.5, -0.4),
}


def _same(a: Any, b: Any) -> None:
    if isinstance(a, LaserScan):
        assert b.header == a.header and b.range_max == pytest.approx(a.range_max)
        assert np.allclose(b.ranges, a.ranges, atol=1e-5)
    elif isinstance(a, OccupancyGrid):
        assert (b.info.width, b.info.height) == (a.info.width, a.info.height)
        assert b.info.resolution == pytest.approx(a.info.resolution)  # float32 on the wire
        assert np.array_equal(b.data, a.data)
    elif isinstance(a, Pose2D):
        assert (b.x, b.y, b.theta) == pytest.approx((a.x, a.y, a.theta))
    elif isinstance(a, TransformStamped):
        assert b.header == a.header and b.child_frame_id == a.child_frame_id
        assert b.rotation.yaw == pytest.approx(0.3)
    else:
        assert b == a


@pytest.mark.parametrize("topic", sorted(SAMPLES))
def test_roundtrip_through_rosbags_cdr(topic: str) -> None:
    types = RosbagsTypes()
    codec = route(topic).codec
    raw = types.store.serialize_cdr(codec.encode(types, SAMPLES[topic], 9.0), codec.ros_type)
    _same(SAMPLES[topic], codec.decode(types.store.deserialize_cdr(raw, codec.ros_type)))


@pytest.mark.parametrize("topic", sorted(SAMPLES))
def test_roundtrip_through_rclpy_messages(topic: str) -> None:
    types = RclpyTypes()
    codec = route(topic).codec
    _same(SAMPLES[topic], codec.decode(codec.encode(types, SAMPLES[topic], 9.0)))


def test_contract_names_use_standard_types() -> None:
    expected = {
        "/scan": "sensor_msgs/msg/LaserScan",
        "/odom": "nav_msgs/msg/Odometry",
        "/cmd_vel": "geometry_msgs/msg/Twist",
        "/map": "nav_msgs/msg/OccupancyGrid",
        "/tf": "tf2_msgs/msg/TFMessage",
        "/goal_pose": "geometry_msgs/msg/PoseStamped",
        "/amiro/say": "std_msgs/msg/String",
        "/amiro/events": "std_msgs/msg/String",
    }
    assert {t: ROUTES[t].codec.ros_type for t in expected} == expected
    assert ROUTES["/map"].latched and not ROUTES["/scan"].latched


def test_time_and_plain_text_say() -> None:
    types = RosbagsTypes()
    stamp = ros_time(types, 12.75)
    assert (stamp.sec, stamp.nanosec) == (12, 750_000_000) and seconds(stamp) == 12.75
    assert bus_say(types.make("std_msgs/msg/String", data="Hello")) == SpeechRequest("Hello")


def test_malformed_json_is_rejected_with_value_error() -> None:
    types = RosbagsTypes()
    codec = route("/amiro/notifications").codec
    with pytest.raises(ValueError):
        codec.decode(types.make("std_msgs/msg/String", data='{"id": 3}'))
    with pytest.raises(ValueError):
        route("/amiro/events").codec.decode(types.make("std_msgs/msg/String", data="[1]"))
