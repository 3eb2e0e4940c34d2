"""The robot's head camera as the rest of amiro sees it: its pinhole model and its port.

:class:`Camera` is the geometry of Pepper's head RGB-D camera (intrinsics from the fields of
view, the optical frame, projection, line of sight).  :class:`HeadCamera` is the port that
perception and activity read, whichever robot runs: the in-process simulator offers it
directly; split over ROS 2, the edge offers the same from bridged topics, so both run the
same perception and activity code.

A simulated frame renders no pixels: it is the list of :class:`CameraObservation`.  Of their
ground-truth fields only those the simulated detector (box, depth, posture) and face backend
(name, face towards the camera, backlight) model are read by the real modules; the rest is
for the oracles and scoring.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np
import numpy.typing as npt

from amiro.core.messages import BoundingBox2D, CameraInfo, Header, Point, Pose2D
from amiro.home.world import World

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class CameraObservation:
    """One resident as the head camera sees them, plus ground truth for oracles.

    ``bbox`` is in pixels of the RGB image, ``depth`` the noisy z-depth (metres along the
    optical axis) of the torso, ``position`` the true torso centre in the map frame.
    """

    name: str
    bbox: BoundingBox2D
    depth: float
    face_visible: bool
    backlit: bool
    position: Point
    posture: str
    activity: str
    skeleton_occluded: bool


@dataclass(frozen=True, slots=True)
class CameraParams:
    height: float = 1.15  # m above the floor (Pepper's forehead)
    forward: float = 0.08  # m ahead of the base centre
    width: int = 640
    image_height: int = 480
    hfov_deg: float = 55.2
    vfov_deg: float = 44.3
    depth_sigma: float = 1.4e-3  # noise sigma = depth_sigma * z^2
    max_range: float = 8.0
    face_angle_deg: float = 70.0
    backlit_angle_deg: float = 20.0
    frame_id: str = "camera"


class Camera:
    """Pinhole RGB-D camera on Pepper's head."""

    def __init__(self, params: CameraParams | None = None) -> None:
        self.params = p = params or CameraParams()
        self.fx = (p.width / 2.0) / math.tan(math.radians(p.hfov_deg) / 2.0)
        self.fy = (p.image_height / 2.0) / math.tan(math.radians(p.vfov_deg) / 2.0)
        self.cx = p.width / 2.0
        self.cy = p.image_height / 2.0

    def info(self, stamp: float) -> CameraInfo:
        k = (self.fx, 0.0, self.cx, 0.0, self.fy, self.cy, 0.0, 0.0, 1.0)
        return CameraInfo(
            Header(stamp, self.params.frame_id), self.params.width, self.params.image_height, k
        )

    def position(self, robot: Pose2D, head_yaw: float) -> tuple[float, float, float]:
        """Camera centre in the map frame (the head turns about the base's vertical axis)."""
        yaw = robot.theta + head_yaw
        f = self.params.forward
        return robot.x + f * math.cos(yaw), robot.y + f * math.sin(yaw), self.params.height

    def to_optical(
        self, points: FloatArray, robot: Pose2D, head_yaw: float, head_pitch: float
    ) -> FloatArray:
        """Map-frame points (N, 3) to the optical frame (x right, y down, z forward)."""
        cx, cy, cz = self.position(robot, head_yaw)
        yaw = robot.theta + head_yaw
        d = points - np.array([cx, cy, cz])
        fwd = d[:, 0] * math.cos(yaw) + d[:, 1] * math.sin(yaw)
        left = -d[:, 0] * math.sin(yaw) + d[:, 1] * math.cos(yaw)
        up = d[:, 2]
        cp, sp = math.cos(head_pitch), math.sin(head_pitch)
        z = fwd * cp - up * sp
        y = -(fwd * sp + up * cp)
        return np.stack([-left, y, z], axis=1)

    def project(self, optical: FloatArray) -> FloatArray:
        """Pixel (u, v) of optical-frame points with z > 0."""
        z = optical[:, 2]
        return np.stack(
            [self.cx + self.fx * optical[:, 0] / z, self.cy + self.fy * optical[:, 1] / z], axis=1
        )

    def sight(
        self,
        world: World,
        robot_pose: Pose2D,
        head_yaw: float,
        head_pitch: float,
        points: FloatArray,
        height: float,
        rng: np.random.Generator,
    ) -> tuple[BoundingBox2D, float] | None:
        """Pixel box and noisy z-depth of a body given by its centre (``points[0]``) and the
        corners of its box (the rest), all in the map frame; None when its centre is out of
        view or out of range, or walls or anything taller than ``height`` hide it."""
        p = self.params
        opt = self.to_optical(points, robot_pose, head_yaw, head_pitch)
        z = float(opt[0, 2])
        if not 0.1 < z <= p.max_range:
            return None
        u, v = self.project(opt[:1])[0]
        if not (0.0 <= u < p.width and 0.0 <= v < p.image_height):
            return None
        cam = self.position(robot_pose, head_yaw)
        if not world.line_of_sight((cam[0], cam[1]), (points[0, 0], points[0, 1]), height):
            return None
        uv = self.project(opt[1:][opt[1:, 2] > 0.05])
        u0, v0 = np.clip(uv.min(axis=0), 0.0, [p.width, p.image_height])
        u1, v1 = np.clip(uv.max(axis=0), 0.0, [p.width, p.image_height])
        box = BoundingBox2D(
            float(u0 + u1) / 2.0, float(v0 + v1) / 2.0, float(u1 - u0), float(v1 - v0)
        )
        return box, z + p.depth_sigma * z**2 * float(rng.standard_normal())


class HeadCamera(Protocol):
    def now(self) -> float:
        """The time of the current frame (s)."""
        ...

    def observe(self) -> list[CameraObservation]:
        """The current frame: everyone the head camera sees."""
        ...

    def head_joints(self) -> tuple[float, float] | None:
        """(HeadYaw, HeadPitch) when the frame was taken; None before any joint state."""
        ...

    def camera_info(self) -> CameraInfo | None:
        """The RGB image's intrinsics; None before the camera has reported them."""
        ...

    def camera_mount(self) -> tuple[float, float]:
        """Where the camera sits: height above the floor and ahead of the base centre (m)."""
        ...

    def robot_pose(self) -> Pose2D | None:
        """A pose the source itself knows: the simulator's ground truth in one process (for
        evaluations without localisation), None from a bus feed."""
        ...

    def household(self) -> tuple[str, ...]:
        """The residents' names: the face gallery's enrolled people."""
        ...
