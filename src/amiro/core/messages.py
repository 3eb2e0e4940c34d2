"""Message vocabulary: frozen dataclasses shaped like ROS 2 standard messages.

SI units, REP-103 axes (x forward, y left, z up, yaw counter-clockwise) and REP-105 frame
names (``map``, ``odom``, ``base_footprint``, ``laser``, ``camera``).  Keeping the field names
of the ROS messages makes conversion to rclpy types mechanical.  Time stamps are seconds of
the runtime clock as ``float``.  Messages that carry arrays compare by identity (``eq=False``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]


# --- std_msgs / builtin_interfaces ---------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Header:
    stamp: float = 0.0
    frame_id: str = ""


@dataclass(frozen=True, slots=True)
class String:
    data: str


# --- geometry_msgs -------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Vector3:
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0


@dataclass(frozen=True, slots=True)
class Point:
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0


@dataclass(frozen=True, slots=True)
class Quaternion:
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    w: float = 1.0

    @staticmethod
    def from_yaw(yaw: float) -> Quaternion:
        return Quaternion(z=math.sin(yaw / 2.0), w=math.cos(yaw / 2.0))

    @property
    def yaw(self) -> float:
        siny = 2.0 * (self.w * self.z + self.x * self.y)
        cosy = 1.0 - 2.0 * (self.y * self.y + self.z * self.z)
        return math.atan2(siny, cosy)


@dataclass(frozen=True, slots=True)
class Pose2D:
    """Planar pose (x, y, theta): what a ground robot's planners actually use."""

    x: float = 0.0
    y: float = 0.0
    theta: float = 0.0

    def distance_to(self, other: Pose2D | Point) -> float:
        return math.hypot(other.x - self.x, other.y - self.y)

    def to_pose(self) -> Pose:
        return Pose(Point(self.x, self.y, 0.0), Quaternion.from_yaw(self.theta))


@dataclass(frozen=True, slots=True)
class Pose:
    position: Point = field(default_factory=Point)
    orientation: Quaternion = field(default_factory=Quaternion)

    def to_pose2d(self) -> Pose2D:
        return Pose2D(self.position.x, self.position.y, self.orientation.yaw)


@dataclass(frozen=True, slots=True)
class PoseStamped:
    header: Header
    pose: Pose


@dataclass(frozen=True, slots=True)
class Twist:
    linear: Vector3 = field(default_factory=Vector3)
    angular: Vector3 = field(default_factory=Vector3)

    @staticmethod
    def planar(vx: float, vy: float, wz: float) -> Twist:
        return Twist(Vector3(vx, vy, 0.0), Vector3(0.0, 0.0, wz))


@dataclass(frozen=True, slots=True)
class TransformStamped:
    header: Header
    child_frame_id: str
    translation: Vector3
    rotation: Quaternion


# --- nav_msgs ------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Odometry:
    header: Header
    child_frame_id: str
    pose: Pose
    twist: Twist


@dataclass(frozen=True, slots=True)
class MapMetaData:
    resolution: float
    width: int
    height: int
    origin: Pose


@dataclass(frozen=True, slots=True, eq=False)
class OccupancyGrid:
    """Row-major grid, row 0 at the origin (bottom); -1 unknown, 0 free, 100 occupied."""

    header: Header
    info: MapMetaData
    data: npt.NDArray[np.int8]


@dataclass(frozen=True, slots=True)
class Path:
    header: Header
    poses: tuple[Pose2D, ...]


# --- sensor_msgs ---------------------------------------------------------------------------


@dataclass(frozen=True, slots=True, eq=False)
class LaserScan:
    header: Header
    angle_min: float
    angle_max: float
    angle_increment: float
    time_increment: float
    scan_time: float
    range_min: float
    range_max: float
    ranges: FloatArray

    def angles(self) -> FloatArray:
        return self.angle_min + self.angle_increment * np.arange(len(self.ranges), dtype=np.float64)


@dataclass(frozen=True, slots=True)
class CameraInfo:
    """Pinhole intrinsics; ``k`` is the row-major 3x3 matrix as in sensor_msgs/CameraInfo."""

    header: Header
    width: int
    height: int
    k: tuple[float, float, float, float, float, float, float, float, float]

    @property
    def fx(self) -> float:
        return self.k[0]

    @property
    def fy(self) -> float:
        return self.k[4]

    @property
    def cx(self) -> float:
        return self.k[2]

    @property
    def cy(self) -> float:
        return self.k[5]


@dataclass(frozen=True, slots=True, eq=False)
class Image:
    """sensor_msgs/Image with the pixels as an array (``32FC1`` depth in metres, ``rgb8``)."""

    header: Header
    height: int
    width: int
    encoding: str
    data: npt.NDArray[Any]


@dataclass(frozen=True, slots=True)
class JointState:
    header: Header
    name: tuple[str, ...]
    position: tuple[float, ...]


# --- perception (vision_msgs-like) ---------------------------------------------------------


@dataclass(frozen=True, slots=True)
class BoundingBox2D:
    """Axis-aligned box in pixels: centre and size, as vision_msgs/BoundingBox2D."""

    cx: float
    cy: float
    width: float
    height: float


@dataclass(frozen=True, slots=True)
class Detection2D:
    label: str
    score: float
    bbox: BoundingBox2D
    identity: str | None = None  # a recognised face's name, else None ("unknown")


@dataclass(frozen=True, slots=True)
class Person:
    """A tracked person in the map frame (people_msgs/Person-like)."""

    id: str
    name: str | None
    position: Point
    confidence: float


@dataclass(frozen=True, slots=True)
class People:
    header: Header
    people: tuple[Person, ...]


SKELETON_JOINTS = 25  # NTU RGB+D's body layout, the one every skeleton on the bus uses


@dataclass(frozen=True, slots=True, eq=False)
class Skeleton:
    """One body in NTU RGB+D layout: ``joints`` is (25, 3) in metres, camera frame;
    ``tracked`` marks joints the sensor actually saw (missing joints are False)."""

    header: Header
    body_id: int
    joints: FloatArray
    tracked: npt.NDArray[np.bool_]


# --- speech ---------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class SpeechRequest:
    """What the robot should say (and show): the TTS input."""

    text: str
    lang: str = "en"
    display: bool = True
    say: bool = True
    act: str = ""  # the dialogue act ("hydration_reminder"): which answer to expect
    addressee: str = ""  # the person spoken to; empty: whoever is near


@dataclass(frozen=True, slots=True, eq=False)
class AudioStamped:
    """A piece of microphone audio, 16-bit mono PCM at ``rate`` Hz (audio_common_msgs'
    AudioStamped, the message ROS 2 recognisers such as whisper_ros subscribe to); the stamp
    is when its first sample was heard."""

    header: Header
    samples: npt.NDArray[np.int16]
    rate: int

    @property
    def seconds(self) -> float:
        return len(self.samples) / self.rate


@dataclass(frozen=True, slots=True)
class SpeechHeard:
    """An utterance heard by the robot.  ``intent`` is set only by sources that know it
    (the simulator's oracle); real ASR leaves it None and the NLU fills it in."""

    text: str
    lang: str
    speaker: str | None = None
    confidence: float = 1.0
    intent: str | None = None


# --- environment and behaviour ---------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class SensorReading:
    home: str
    room: str
    sensor: str
    value: float
    unit: str
    stamp: float


@dataclass(frozen=True, slots=True)
class Notification:
    """A request from the smart environment or an external health platform."""

    id: str
    user: str
    kind: str
    priority: int
    reason: str = ""
    # Where the behaviour answering it stood (amiro.behavior.checkpoint's JSON form): set
    # by the cloud's ledger when it re-sends the notification to a restarted edge.
    checkpoint: dict[str, Any] | None = field(default=None, compare=False, hash=False)


@dataclass(frozen=True, slots=True)
class Acknowledgement:
    id: str
    status: str  # done | postponed | failed
    ts: str


@dataclass(frozen=True, slots=True)
class BehaviorEvent:
    """Something the robot did or decided, with why: the stream behind logs and the dashboard."""

    stamp: float
    type: str
    graph: str | None = None
    task: str | None = None
    detail: dict[str, Any] = field(default_factory=dict, hash=False)

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"t": round(self.stamp, 3), "type": self.type}
        if self.graph is not None:
            out["graph"] = self.graph
        if self.task is not None:
            out["task"] = self.task
        out.update(self.detail)
        return out
