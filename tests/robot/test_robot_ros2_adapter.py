"""The ROS 2 robot adapter against a fake robot: a plain rclpy participant on loopback that
publishes the driver's topics and records what amiro commands."""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

from amiro.core.clock import SimClock
from amiro.core.messages import (
    Header,
    Image,
    JointState,
    LaserScan,
    Odometry,
    SpeechRequest,
    String,
    Twist,
)
from amiro.core.runtime import Runtime
from amiro.robot.profile import load_profile
from amiro.robot.ros2_adapter import Ros2RobotNode
from amiro.ros2.context import RosContext


class FakeRobot:
    """What a ROS 2 driver looks like from outside: sensors out, commands in."""

    def __init__(self, ros: RosContext, scan: str, odom_child: str = "base_link") -> None:
        self.ros = ros
        self.odom_child = odom_child
        self.scan_pub = ros.publisher("sensor_msgs/msg/LaserScan", scan)
        self.odom_pub = ros.publisher("nav_msgs/msg/Odometry", "/odom")
        self.joints_pub = ros.publisher("sensor_msgs/msg/JointState", "/joint_states")
        self.cmd: list[tuple[float, float, float]] = []
        self.head: list[tuple[list[str], list[float]]] = []
        self.speech: list[str] = []
        ros.subscribe("geometry_msgs/msg/Twist", "/cmd_vel", self._on_cmd)
        ros.subscribe("std_msgs/msg/String", "/speech", lambda m: self.speech.append(m.data))
        ros.subscribe("sensor_msgs/msg/JointState", "/head/joint_command", self._on_head)

    def _on_cmd(self, msg: Any) -> None:
        self.cmd.append((msg.linear.x, msg.linear.y, msg.angular.z))

    def _on_head(self, msg: Any) -> None:
        self.head.append((list(msg.name), list(msg.position)))

    def publish_sensors(self, ranges: list[float], frame: str) -> None:
        t = self.ros.types
        header = t.make("std_msgs/msg/Header", frame_id=frame)
        n = len(ranges)
        self.scan_pub.publish(
            t.make(
                "sensor_msgs/msg/LaserScan",
                header=header,
                angle_min=-2.0944,
                angle_max=2.0944,
                angle_increment=2 * 2.0944 / (n - 1),
                range_min=0.1,
                range_max=3.0,
                ranges=t.float32_seq(ranges),
            )
        )
        odom = t.make("nav_msgs/msg/Odometry", child_frame_id=self.odom_child)
        odom.header.frame_id = "odom"
        odom.pose.pose.position.x = 1.5
        self.odom_pub.publish(odom)
        joints = t.make("sensor_msgs/msg/JointState", name=["HeadYaw", "HeadPitch"])
        joints.position = t.float64_seq([0.1, -0.2])
        self.joints_pub.publish(joints)


@pytest.fixture
def pair(robot_domain: int) -> Iterator[tuple[RosContext, RosContext]]:
    amiro, robot = (
        RosContext("amiro_robot_test", robot_domain),
        RosContext("fake_robot", robot_domain),
    )
    yield amiro, robot
    amiro.close()
    robot.close()


def _run(runtime: Runtime, robot: RosContext, seconds: float, each: Any = None) -> None:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if each is not None:
            each()
        runtime.spin_for(0.02)
        robot.spin(0.0)


def _connected(amiro: RosContext, robot: RosContext) -> None:
    assert not amiro.wait_for_nodes(["fake_robot"], 10.0)
    assert not robot.wait_for_nodes(["amiro_robot_test"], 10.0)


def test_pepper_driver_topics_become_amiro_ports_and_commands_are_clamped(
    pair: tuple[RosContext, RosContext],
) -> None:
    amiro, robot_ros = pair
    fake = FakeRobot(robot_ros, scan="/laser")
    profile = load_profile("pepper")
    runtime = Runtime(SimClock(speed=1.0))
    adapter = runtime.add(Ros2RobotNode(amiro, profile))
    scans: list[LaserScan] = []
    odoms: list[Odometry] = []
    joints: list[JointState] = []
    runtime.bus.subscribe("/scan", LaserScan, scans.append)
    runtime.bus.subscribe("/odom", Odometry, odoms.append)
    runtime.bus.subscribe("/joint_states", JointState, joints.append)
    runtime.start()
    _connected(amiro, robot_ros)
    ranges = [1.0] * 15 + [-1.0] * 8 + [2.0] * 15 + [-1.0] * 8 + [1.5] * 15  # Pepper's layout
    cmd = runtime.bus.publisher("/cmd_vel", Twist)

    def drive() -> None:
        fake.publish_sensors(ranges, frame="base_footprint")
        cmd.publish(Twist.planar(1.0, 1.0, 3.0))  # far beyond Pepper's limits

    _run(runtime, robot_ros, 1.5, drive)
    runtime.bus.publisher("/amiro/say", SpeechRequest).publish(SpeechRequest("Hello Maria"))
    runtime.bus.publisher("/amiro/say", SpeechRequest).publish(SpeechRequest("shh", say=False))
    _run(runtime, robot_ros, 1.5)  # no more /cmd_vel: the adapter brings the base to rest
    runtime.stop()
    robot_ros.spin(0.5)

    assert scans and scans[-1].header.frame_id == "laser" and len(scans[-1].ranges) == 61
    assert np.isnan(scans[-1].ranges[20]) and scans[-1].ranges[0] == pytest.approx(1.0)
    assert odoms and (odoms[-1].header.frame_id, odoms[-1].child_frame_id) == (
        "odom",
        "base_footprint",
    )
    assert odoms[-1].pose.position.x == pytest.approx(1.5)
    assert joints and joints[-1].name == ("HeadYaw", "HeadPitch")
    lim = profile.limits
    speeds = [math.hypot(vx, vy) for vx, vy, _ in fake.cmd]
    assert max(speeds) == pytest.approx(lim.max_linear, rel=1e-3)  # clamped, reached
    assert max(abs(w) for _, _, w in fake.cmd) == pytest.approx(lim.max_angular, rel=1e-3)
    assert any(abs(vy) > 0.1 for _, vy, _ in fake.cmd)  # omnidirectional: lateral kept
    steps = [abs(b[0] - a[0]) for a, b in itertools.pairwise(fake.cmd)]
    assert max(steps) <= lim.max_linear_accel / profile.cmd_rate_hz + 1e-6
    assert fake.cmd[-1] == (0.0, 0.0, 0.0)  # at rest once commands stopped, and on stop
    assert fake.speech == ["Hello Maria"]
    assert adapter.stats.errors == 0


def test_a_differential_base_gets_no_lateral_velocity_and_the_head_is_clamped(
    pair: tuple[RosContext, RosContext],
) -> None:
    amiro, robot_ros = pair
    fake = FakeRobot(robot_ros, scan="/scan")
    runtime = Runtime(SimClock(speed=1.0))
    runtime.add(Ros2RobotNode(amiro, load_profile("generic_diff"), name="diff"))
    runtime.add(Ros2RobotNode(amiro, load_profile("generic_omni"), skip=("base",), name="omni"))
    images: list[Image] = []
    runtime.bus.subscribe("/camera/image_raw", Image, images.append)
    runtime.start()
    _connected(amiro, robot_ros)
    cmd = runtime.bus.publisher("/cmd_vel", Twist)
    head = runtime.bus.publisher("/amiro/head/cmd", JointState)
    raw = robot_ros.publisher("sensor_msgs/msg/Image", "/camera/color/image_raw")
    pixels = np.arange(2 * 3 * 3, dtype=np.uint8).reshape(2, 3, 3)
    bgr = robot_ros.types.make(
        "sensor_msgs/msg/Image", height=2, width=3, encoding="bgr8", step=9,
        data=robot_ros.types.uint8_seq(pixels[:, :, ::-1].tobytes()),
    )  # fmt: skip

    def drive() -> None:
        cmd.publish(Twist.planar(0.1, 0.5, 0.0))
        raw.publish(bgr)

    _run(runtime, robot_ros, 1.0, drive)
    head.publish(JointState(Header(), ("HeadYaw", "HeadPitch"), (2.5, 0.1)))
    runtime.bus.publisher("/amiro/emergency_stop", String).publish(String("stop"))
    _run(runtime, robot_ros, 0.5, drive)
    runtime.stop()

    assert fake.cmd and all(vy == 0.0 for _, vy, _ in fake.cmd)
    assert max(vx for vx, _, _ in fake.cmd) == pytest.approx(0.1)
    assert fake.cmd[-1] == (0.0, 0.0, 0.0)  # emergency stop holds the base
    assert fake.head == [(["head_pan_joint", "head_tilt_joint"], [1.57, pytest.approx(0.1)])]
    assert images and images[-1].encoding == "rgb8"
    assert np.array_equal(images[-1].data, pixels)
