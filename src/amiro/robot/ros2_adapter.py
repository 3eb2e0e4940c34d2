"""Any ROS 2 robot as amiro's robot: the driver's topics in, clamped commands out.

:class:`Ros2RobotNode` subscribes to the driver's topics named by a :class:`RobotProfile`
(``/laser`` on Pepper, ``/scan`` elsewhere), converts frames and publishes amiro's robot port
on the bus; it sends ``/cmd_vel`` at the profile's rate through a :class:`VelocityLimiter`
(zero once commands stop coming, and on shutdown), head targets within the joint ranges,
and speech text.  Stamps become the runtime clock's at receipt: amiro's nodes compare them
with their own clock, which need not be the robot's.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Collection
from dataclasses import dataclass
from typing import Any

from amiro.core import names
from amiro.core.messages import (
    CameraInfo,
    Header,
    Image,
    JointState,
    LaserScan,
    Odometry,
    SpeechRequest,
    String,
    TransformStamped,
    Twist,
    Vector3,
)
from amiro.core.node import Node
from amiro.core.safety import estop_engaged
from amiro.robot.frames import odometry_in_rep105, scan_in_base
from amiro.robot.limits import VelocityLimiter, clamp_head
from amiro.robot.profile import RobotProfile
from amiro.ros2.context import RosContext
from amiro.ros2.convert import (
    STRING,
    bus_camera_info,
    bus_image,
    bus_joints,
    bus_odometry,
    bus_scan,
    ros_joints,
    ros_twist,
)

# What an adapter can hand to another one (e.g. speech and head to NAOqi on a Pepper).
CHANNELS = ("base", "head", "say")


@dataclass
class AdapterStats:
    scans: int = 0
    odom: int = 0
    images: int = 0
    commands: int = 0  # velocity commands sent to the robot
    head_commands: int = 0
    said: int = 0
    errors: int = 0  # driver messages that could not be converted


class Ros2RobotNode(Node):
    """The robot port over a ROS 2 driver, for one :class:`RobotProfile`."""

    def __init__(
        self,
        ros: RosContext,
        profile: RobotProfile,
        skip: Collection[str] = (),
        pump_period: float = 0.01,
        name: str = "robot",
    ) -> None:
        super().__init__(name)
        unknown = set(skip) - set(CHANNELS)
        if unknown:
            raise ValueError(f"unknown robot channels {sorted(unknown)} (known: {CHANNELS})")
        self.ros = ros
        self.profile = profile
        self.skip = frozenset(skip)
        self.pump_period = pump_period
        self.limiter = VelocityLimiter(profile.base, profile.limits)
        self.stats = AdapterStats()
        self.estop = False
        self._wanted = Twist()
        self._wanted_at = -math.inf
        t = profile.topics
        self.cmd_pub = ros.publisher("geometry_msgs/msg/Twist", t.cmd_vel)
        self.head_pub = (
            ros.publisher("sensor_msgs/msg/JointState", t.head_cmd)
            if t.head_cmd and profile.head is not None and "head" not in self.skip
            else None
        )
        self.speech_pub = (
            ros.publisher(STRING, t.speech) if t.speech and "say" not in self.skip else None
        )
        self._inbound(t.scan, "sensor_msgs/msg/LaserScan", self._on_scan, depth=1)
        self._inbound(t.odom, "nav_msgs/msg/Odometry", self._on_odom, depth=1)
        if t.joint_states:
            self._inbound(t.joint_states, "sensor_msgs/msg/JointState", self._on_joints)
        for topic, port in ((t.image, names.IMAGE), (t.depth, names.DEPTH)):
            if topic:
                self._inbound(topic, "sensor_msgs/msg/Image", self._image_to(port), depth=1)
        if t.camera_info:
            self._inbound(t.camera_info, "sensor_msgs/msg/CameraInfo", self._on_info, depth=1)

    # --- driver -> bus ------------------------------------------------------------------
    def _inbound(
        self, topic: str, ros_type: str, handler: Callable[[Any], None], depth: int = 10
    ) -> None:
        def guarded(msg: Any) -> None:
            if not self.running:
                return
            try:
                handler(msg)
            except (ValueError, TypeError, AttributeError, IndexError) as exc:
                self.stats.errors += 1
                self.log.warning("bad %s from the robot dropped: %s", topic, exc)

        self.ros.subscribe(ros_type, topic, guarded, depth)

    def _on_scan(self, msg: Any) -> None:
        scan = scan_in_base(bus_scan(msg), self.profile.laser_mount, self.now())
        self.stats.scans += 1
        self.pub_scan.publish(scan)

    def _on_odom(self, msg: Any) -> None:
        odom = odometry_in_rep105(bus_odometry(msg), self.now())
        self.stats.odom += 1
        self.pub_odom.publish(odom)
        p = odom.pose.position
        self.pub_tf.publish(
            TransformStamped(
                odom.header, odom.child_frame_id, Vector3(p.x, p.y, 0.0), odom.pose.orientation
            )
        )

    def _on_joints(self, msg: Any) -> None:
        joints = bus_joints(msg)
        head = self.profile.head
        joint_names = (
            {head.yaw_joint: names.HEAD_YAW, head.pitch_joint: names.HEAD_PITCH} if head else {}
        )
        renamed = tuple(joint_names.get(n, n) for n in joints.name)
        self.pub_joints.publish(JointState(Header(self.now(), ""), renamed, joints.position))

    def _image_to(self, port: str) -> Callable[[Any], None]:
        def publish(msg: Any) -> None:
            img = bus_image(msg)
            self.stats.images += 1
            header = Header(self.now(), "camera")
            self.pubs_image[port].publish(
                Image(header, img.height, img.width, img.encoding, img.data)
            )

        return publish

    def _on_info(self, msg: Any) -> None:
        info = bus_camera_info(msg)
        self.pub_info.publish(
            CameraInfo(Header(self.now(), "camera"), info.width, info.height, info.k)
        )

    # --- bus -> driver ------------------------------------------------------------------
    def on_start(self) -> None:
        self.limiter.reset()
        self._wanted, self._wanted_at = Twist(), -math.inf
        self.pub_scan = self.create_publisher(names.SCAN, LaserScan)
        self.pub_odom = self.create_publisher(names.ODOM, Odometry)
        self.pub_tf = self.create_publisher(names.TF, TransformStamped)
        self.pub_joints = self.create_publisher(names.JOINT_STATES, JointState)
        self.pubs_image = {p: self.create_publisher(p, Image) for p in (names.IMAGE, names.DEPTH)}
        self.pub_info = self.create_publisher(names.CAMERA_INFO, CameraInfo)
        self.create_subscription(names.EMERGENCY_STOP, String, self._on_estop)
        if "base" not in self.skip:
            self.create_subscription(names.CMD_VEL, Twist, self._on_cmd_vel, depth=1)
            self.create_timer(1.0 / self.profile.cmd_rate_hz, self._send_command)
        if self.head_pub is not None:
            self.create_subscription(names.HEAD_CMD, JointState, self._on_head)
        if self.speech_pub is not None:
            self.create_subscription(names.SAY, SpeechRequest, self._on_say)
        self.create_timer(self.pump_period, self.pump)

    def on_stop(self) -> None:
        if "base" not in self.skip:
            self.cmd_pub.publish(ros_twist(self.ros.types, Twist()))  # leave the base still

    def pump(self) -> None:
        """Deliver what the driver sent since the last call."""
        self.ros.spin(0.0)

    def _on_cmd_vel(self, msg: Twist) -> None:
        self._wanted, self._wanted_at = msg, self.now()

    def _on_estop(self, msg: String) -> None:
        self.estop = estop_engaged(msg.data)
        if self.estop and "base" not in self.skip:
            self.limiter.reset()
            self.cmd_pub.publish(ros_twist(self.ros.types, Twist()))

    def _send_command(self) -> None:
        if self.estop:
            self.limiter.reset()
            command = self.limiter.current
        else:
            fresh = self.now() - self._wanted_at <= self.profile.cmd_timeout_s
            target = self.limiter.target(self._wanted if fresh else Twist())
            command = self.limiter.step(target, 1.0 / self.profile.cmd_rate_hz)
        self.cmd_pub.publish(ros_twist(self.ros.types, command.to_twist()))
        self.stats.commands += 1

    def _on_head(self, msg: JointState) -> None:
        head = self.profile.head
        assert head is not None and self.head_pub is not None
        targets = clamp_head(head, dict(zip(msg.name, msg.position, strict=False)))
        if not targets:
            return
        joint_names = {names.HEAD_YAW: head.yaw_joint, names.HEAD_PITCH: head.pitch_joint}
        out = JointState(
            Header(self.now(), ""), tuple(joint_names[j] for j in targets), tuple(targets.values())
        )
        self.head_pub.publish(ros_joints(self.ros.types, out, self.now()))
        self.stats.head_commands += 1

    def _on_say(self, msg: SpeechRequest) -> None:
        assert self.speech_pub is not None
        if msg.say and msg.text.strip():
            self.speech_pub.publish(self.ros.types.make(STRING, data=msg.text))
            self.stats.said += 1
