"""The robot's coordinate frames on ``/tf`` and ``/tf_static`` (REP-105), for ROS 2 viewers.

rviz2 and Foxglove place every message by its ``frame_id`` through the transform tree::

    map -> odom -> base_footprint -> base_link -> laser
                                              -> camera_link -> camera (optical)

The simulator already publishes ``odom -> base_footprint`` from its odometry on ``/tf``.
:class:`RobotFramesNode` (robot process) adds the fixed mounts once on ``/tf_static`` and the
head camera, which turns with the head joints, on ``/tf``; :class:`MapOdomNode` (wherever
localisation runs) publishes ``map -> odom`` as ROS amcl does.  Each bus message is one
``TransformStamped``; the bridge sends it as a ``tf2_msgs/TFMessage``.
"""

from __future__ import annotations

import math

from scipy.spatial.transform import Rotation

from amiro.core import names
from amiro.core.messages import (
    Header,
    JointState,
    Odometry,
    Pose2D,
    Quaternion,
    TransformStamped,
    Vector3,
)
from amiro.core.node import Node
from amiro.navigation.poses import between, compose
from amiro.robot.camera import CameraParams
from amiro.sim.simulator import Simulation

MAP, ODOM_FRAME, BASE_FOOTPRINT, BASE_LINK = "map", "odom", "base_footprint", "base_link"
CAMERA_LINK = "camera_link"
# camera_link (x forward, z up) -> optical frame (z forward, x right, y down), REP-103
OPTICAL = Quaternion(-0.5, 0.5, -0.5, 0.5)
ORIGIN = Pose2D(0.0, 0.0, 0.0)


def transform(
    stamp: float,
    parent: str,
    child: str,
    translation: Vector3 | None = None,
    rotation: Quaternion | None = None,
) -> TransformStamped:
    return TransformStamped(
        Header(stamp, parent), child, translation or Vector3(), rotation or Quaternion()
    )


def planar(stamp: float, parent: str, child: str, pose: Pose2D) -> TransformStamped:
    return transform(stamp, parent, child, Vector3(pose.x, pose.y), Quaternion.from_yaw(pose.theta))


def static_frames(stamp: float, laser_frame: str, camera: CameraParams) -> list[TransformStamped]:
    """The mounts that never move: the sim's lidar scans in the plane at the base's centre."""
    return [
        transform(stamp, BASE_FOOTPRINT, BASE_LINK),
        transform(stamp, BASE_LINK, laser_frame),
        transform(stamp, CAMERA_LINK, camera.frame_id, rotation=OPTICAL),
    ]


def head_camera(stamp: float, camera: CameraParams, yaw: float, pitch: float) -> TransformStamped:
    """``base_link -> camera_link``: the head turns about the base's vertical axis, the
    camera sits ``forward`` of it at ``height``, as :meth:`amiro.sim.camera.Camera.position`."""
    x, y, z, w = Rotation.from_euler("ZY", [yaw, pitch]).as_quat()
    ahead = Rotation.from_euler("Z", yaw).apply([camera.forward, 0.0, camera.height])
    return transform(
        stamp,
        BASE_LINK,
        CAMERA_LINK,
        Vector3(*(float(v) for v in ahead)),
        Quaternion(float(x), float(y), float(z), float(w)),
    )


def map_to_odom(stamp: float, map_pose: Pose2D, odom_pose: Pose2D) -> TransformStamped:
    """The correction that takes odometry onto the map: ``map_pose ⊕ odom_pose⁻¹``."""
    return planar(stamp, MAP, ODOM_FRAME, compose(map_pose, between(odom_pose, ORIGIN)))


class _Throttle:
    """At most one message per ``period`` of sim time: viewers need 10 Hz, not physics rate."""

    def __init__(self, period: float) -> None:
        self.period = period
        self.last = -math.inf

    def due(self, now: float) -> bool:
        if now - self.last < self.period - 1e-9:
            return False
        self.last = now
        return True


class RobotFramesNode(Node):
    """Robot process: static mounts once on ``/tf_static``, the head camera on ``/tf``."""

    def __init__(
        self,
        laser_frame: str,
        camera: CameraParams,
        period: float = 0.1,
        name: str = "robot_frames",
    ) -> None:
        super().__init__(name)
        self.laser_frame = laser_frame
        self.camera = camera
        self.period = period

    def on_start(self) -> None:
        statics = self.create_publisher(names.TF_STATIC, TransformStamped)
        for tf in static_frames(self.now(), self.laser_frame, self.camera):
            statics.publish(tf)
        self.pub_tf = self.create_publisher(names.TF, TransformStamped)
        self._throttle = _Throttle(self.period)
        self.create_subscription(names.JOINT_STATES, JointState, self._on_joints, depth=1)

    def _on_joints(self, msg: JointState) -> None:
        joints = dict(zip(msg.name, msg.position, strict=False))
        if (
            names.HEAD_YAW in joints
            and names.HEAD_PITCH in joints
            and self._throttle.due(msg.header.stamp)
        ):
            self.pub_tf.publish(
                head_camera(
                    msg.header.stamp, self.camera, joints[names.HEAD_YAW], joints[names.HEAD_PITCH]
                )
            )


def robot_frames(sim: Simulation) -> RobotFramesNode:
    """The frames node for the simulated Pepper, from the sim's own lidar and camera."""
    return RobotFramesNode(sim.robot.lidar.params.frame_id, sim.residents.camera.params)


class MapOdomNode(Node):
    """Localisation's ``map -> odom`` on ``/tf`` from the poses on ``pose_topic`` and the
    latest odometry, at most once per ``period``."""

    def __init__(self, pose_topic: str, period: float = 0.1, name: str = "map_odom_tf") -> None:
        super().__init__(name)
        self.pose_topic = pose_topic
        self.period = period
        self._odom: Pose2D | None = None

    def on_start(self) -> None:
        self._odom = None
        self._throttle = _Throttle(self.period)
        self.pub_tf = self.create_publisher(names.TF, TransformStamped)
        self.create_subscription(names.ODOM, Odometry, self._on_odom, depth=1)
        self.create_subscription(self.pose_topic, Pose2D, self._on_pose, depth=1)

    def _on_odom(self, msg: Odometry) -> None:
        self._odom = msg.pose.to_pose2d()

    def _on_pose(self, pose: Pose2D) -> None:
        if self._odom is not None and self._throttle.due(self.now()):
            self.pub_tf.publish(map_to_odom(self.now(), pose, self._odom))
