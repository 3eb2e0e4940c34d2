"""What the robot process shares with the edge across processes, instead of being read directly.

In one process perception and activity read the :class:`~amiro.sim.simulator.Simulation`.
Split over ROS 2, the robot process publishes what a real robot's sensors would give them:
the head camera's frame on ``/amiro/sim/observations`` (the simulated camera renders no
pixels; its observations are the "image" the simulated detector and face backends read),
its intrinsics on ``/camera/camera_info``, the head joints on ``/joint_states`` (from the
robot node) and the skeleton camera's NTU frames on ``/amiro/sim/skeletons``.  The edge's
:class:`HeadSensorsFeed` offers them as the same :class:`~amiro.robot.camera.HeadCamera` and
skeleton source, so it runs the same perception and activity code as the embedded system.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass
from typing import TypeVar

import numpy as np

from amiro.activity.motion import FPS
from amiro.activity.skeleton import NUM_JOINTS, FloatArray
from amiro.core import names
from amiro.core.bus import Bus
from amiro.core.messages import CameraInfo, Header, JointState, Odometry, Pose2D, Skeleton
from amiro.core.node import Node
from amiro.navigation.poses import between, compose
from amiro.perception.stack import PoseSource
from amiro.robot.camera import Camera, CameraObservation, CameraParams
from amiro.ros2.convert import json_codec
from amiro.ros2.routes import Route, add_route
from amiro.sim.simulator import Simulation
from amiro.sim.skeletons import (
    HISTORY_S,
    SkeletonCamera,
    framing,
    from_level,
    in_image,
    last_frames,
    sensor_tilt,
    to_level,
)

# Kinect axes (x left, y up, z forward) at the head camera, its pitch undone.
SKELETON_FRAME = "camera_level"
SKELETON_HISTORY = 64  # frames kept per person on the edge: beyond any model window (30)
HISTORY = 40  # joint states and odometry kept on the edge: 2 s at the robot's 20 Hz
T = TypeVar("T")


@dataclass(frozen=True, slots=True)
class CameraObservations:
    """The simulated head camera's frame at ``stamp``: everyone it sees (see the module)."""

    stamp: float
    observations: tuple[CameraObservation, ...]


@dataclass(frozen=True, slots=True)
class Heartbeat:
    """A deployment process saying it is alive (``node`` is its process name)."""

    node: str
    stamp: float
    pid: int


class HeadSensorsPublisher(Node):
    """Robot side: at the camera rate, the camera's frame and intrinsics, and the skeleton
    frames made since the last tick of everyone in view.  A skeleton's ``body_id`` is the
    resident's place in the household (the simulated tracker's id); its stamp is the time of
    the view its joints are expressed in (this tick), which the edge needs to place them."""

    def __init__(
        self,
        sim: Simulation,
        skeletons: SkeletonCamera,
        rate_hz: float = 10.0,
        publish_info: bool = True,
    ):
        super().__init__("head_sensors")
        self.sim = sim
        self.publish_info = publish_info  # off when rendered images come with their own info
        self.skeletons = skeletons
        self.period = 1.0 / rate_hz
        self.body_ids = {name: i for i, name in enumerate(sim.household())}
        self.streamed: dict[str, int] = {}  # person -> number of their newest frame sent

    def on_start(self) -> None:
        self.pub_frame = self.create_publisher(names.OBSERVATIONS, CameraObservations)
        self.pub_info = self.create_publisher(names.CAMERA_INFO, CameraInfo)
        self.pub_skeleton = self.create_publisher(names.SKELETONS, Skeleton)
        self.create_timer(self.period, self._publish)

    def _publish(self) -> None:
        observations = self.sim.observe()
        self.pub_frame.publish(CameraObservations(self.now(), tuple(observations)))
        if self.publish_info:
            self.pub_info.publish(self.sim.camera_info())
        for person in (o.name for o in observations):
            fresh = self.skeletons.fresh(person, self.streamed.get(person, 0))
            if fresh is None:
                continue
            frames, self.streamed[person] = fresh
            header, body = Header(self.now(), SKELETON_FRAME), self.body_ids[person]
            for joints in frames:
                tracked = ~np.isnan(joints).any(axis=1)
                self.pub_skeleton.publish(
                    Skeleton(header, body, np.nan_to_num(joints, nan=0.0), tracked)
                )


class HeadSensorsFeed:
    """Edge side: the robot's head camera and skeleton stream from the bridged topics.

    Implements :class:`~amiro.robot.camera.HeadCamera` and the activity recogniser's
    skeleton source.  The camera's mount (height, forward) is the robot's description, from
    the configuration; the head joints are those nearest in time to the frame, and the
    robot's pose is the ``localization`` estimate carried back to the frame's time by
    odometry (messages arrive late across processes, while the robot moves).  Skeletons
    are kept in the map frame, placed as they were seen, and shown from the current view,
    as the simulator's skeleton camera does: the robot's own motion does not look like the
    person's.
    """

    def __init__(
        self,
        bus: Bus,
        mount: tuple[float, float],
        household: tuple[str, ...],
        localization: PoseSource,
        tilt_deg: float = 0.0,
    ):
        """``tilt_deg``: the skeleton sensor's uncorrected pitch (``sim.skeletons.pitch_deg``),
        applied to the levelled skeletons the robot sends, as its skeleton camera does."""
        self.mount = mount
        self.tilt_deg = tilt_deg
        self.camera = Camera(CameraParams(height=mount[0], forward=mount[1]))
        self.residents = household
        self.localization = localization
        self.frame = CameraObservations(0.0, ())
        self.info: CameraInfo | None = None
        self.joints: deque[tuple[float, tuple[float, float]]] = deque(maxlen=HISTORY)
        self.odometry: deque[tuple[float, Pose2D]] = deque(maxlen=HISTORY)
        self.bodies: dict[str, deque[FloatArray]] = {}
        self.received = {"frames": 0, "camera_info": 0, "joint_states": 0, "skeletons": 0}
        bus.subscribe(names.OBSERVATIONS, CameraObservations, self._on_frame, depth=1)
        bus.subscribe(names.CAMERA_INFO, CameraInfo, self._on_info, depth=1)
        bus.subscribe(names.JOINT_STATES, JointState, self._on_joints, depth=20)
        bus.subscribe(names.ODOM, Odometry, self._on_odometry, depth=20)
        # The first tick a person is in view carries the camera's history of them (HISTORY_S).
        burst = 2 * int(HISTORY_S * FPS)
        bus.subscribe(names.SKELETONS, Skeleton, self._on_skeleton, depth=burst)

    # --- the bus side -------------------------------------------------------------------
    def _on_frame(self, msg: CameraObservations) -> None:
        self.frame = msg
        self.received["frames"] += 1

    def _on_info(self, msg: CameraInfo) -> None:
        self.info = msg
        self.received["camera_info"] += 1

    def _on_joints(self, msg: JointState) -> None:
        joints = dict(zip(msg.name, msg.position, strict=False))
        if names.HEAD_YAW in joints and names.HEAD_PITCH in joints:
            self.joints.append(
                (msg.header.stamp, (joints[names.HEAD_YAW], joints[names.HEAD_PITCH]))
            )
            self.received["joint_states"] += 1

    def _on_odometry(self, msg: Odometry) -> None:
        self.odometry.append((msg.header.stamp, msg.pose.to_pose2d()))

    def _on_skeleton(self, msg: Skeleton) -> None:
        self.received["skeletons"] += 1
        stamp = msg.header.stamp
        pose, head = self._pose_at(stamp), nearest(self.joints, stamp)
        if not 0 <= msg.body_id < len(self.residents) or pose is None or head is None:
            return  # a body the household does not explain, or no view to place it from
        joints = np.where(msg.tracked[:, None], msg.joints, np.nan)
        person = self.residents[msg.body_id]
        placed = from_level(self.camera, joints, pose, head[0])
        self.bodies.setdefault(person, deque(maxlen=SKELETON_HISTORY)).append(placed)

    def _pose_at(self, stamp: float) -> Pose2D | None:
        """The localisation estimate, moved back by odometry to where the robot was at
        ``stamp`` (the estimate as it is, before any odometry)."""
        estimate = self.localization()
        then = nearest(self.odometry, stamp)
        if estimate is None or then is None:
            return estimate
        return compose(estimate, between(self.odometry[-1][1], then))

    # --- HeadCamera -----------------------------------------------------------------------
    def now(self) -> float:
        return self.frame.stamp

    def observe(self) -> list[CameraObservation]:
        return list(self.frame.observations)

    def head_joints(self) -> tuple[float, float] | None:
        return nearest(self.joints, self.frame.stamp)

    def camera_info(self) -> CameraInfo | None:
        return self.info

    def camera_mount(self) -> tuple[float, float]:
        return self.mount

    def robot_pose(self) -> Pose2D | None:
        """Where the localisation estimate puts the robot when the frame was taken."""
        return self._pose_at(self.frame.stamp)

    def household(self) -> tuple[str, ...]:
        return self.residents

    # --- SkeletonSource -----------------------------------------------------------------
    def window(self, person: str, frames: int) -> FloatArray | None:
        """The person's last ``frames`` skeletons from the current view: a joint counts where
        the camera sees it now (as the simulator's skeleton camera gives them) and was
        tracked when the frame was taken."""
        stream = self.bodies.get(person)
        pose, joints = self.robot_pose(), self.head_joints()
        if not stream or pose is None or joints is None or self.info is None:
            return None
        if all(o.name != person for o in self.frame.observations):
            return None
        placed = last_frames(stream, frames)
        optical = self.camera.to_optical(placed.reshape(-1, 3), pose, *joints)
        seen = in_image(optical, self.info).reshape(frames, NUM_JOINTS)
        seen &= ~np.isnan(placed).any(axis=2)
        level = to_level(self.camera, placed, pose, joints[0])
        level[~seen] = np.nan
        return sensor_tilt(level, self.tilt_deg)

    def framing(self, person: str) -> tuple[float, bool] | None:
        if self.info is None:
            return None
        return framing(self.observe(), person, float(self.info.height))


def nearest(history: Iterable[tuple[float, T]], stamp: float) -> T | None:
    """The value stamped nearest to ``stamp`` in ``(stamp, value)`` pairs, None if none."""
    best = min(history, key=lambda item: abs(item[0] - stamp), default=None)
    return None if best is None else best[1]


class NavigationState:
    """Edge side, when MoveTo runs in the robot process: the pose and velocity the
    behaviour tasks read from the navigation module, fed from bridged topics instead."""

    def __init__(self, bus: Bus, pose_topic: str) -> None:
        self.pose: Pose2D | None = None
        self.velocity = (0.0, 0.0, 0.0)
        bus.subscribe(pose_topic, Pose2D, self._on_pose, depth=1)
        bus.subscribe(names.ODOM, Odometry, self._on_odom, depth=1)

    def _on_pose(self, pose: Pose2D) -> None:
        self.pose = pose

    def _on_odom(self, msg: Odometry) -> None:
        self.velocity = (msg.twist.linear.x, msg.twist.linear.y, msg.twist.angular.z)


add_route(Route(names.OBSERVATIONS, json_codec(CameraObservations), depth=1))
add_route(Route(names.HEARTBEAT, json_codec(Heartbeat), depth=50))
