"""Pepper's head (yaw/pitch joints) and its RGB-D camera, observing residents.

The camera does not render pixels: it projects each resident's posture-dependent body box
into the image and reports what a detector and a face/skeleton pipeline could get from it
(box, noisy depth, face towards the camera, backlit face), plus ground truth for scoring.
Pitch follows Pepper's convention: positive looks down.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from amiro.core.messages import BoundingBox2D, CameraInfo, Header, Point, Pose2D
from amiro.sim.messages import CameraObservation
from amiro.sim.residents import Resident
from amiro.sim.world import World

FloatArray = npt.NDArray[np.float64]

HEAD_YAW_LIMITS = (-2.0857, 2.0857)
HEAD_PITCH_LIMITS = (-0.7068, 0.6371)


class Head:
    """Two joints driven towards commanded targets at a bounded speed."""

    def __init__(self, max_speed: float = 1.5) -> None:
        self.max_speed = max_speed
        self.yaw = 0.0
        self.pitch = 0.0
        self.target_yaw = 0.0
        self.target_pitch = 0.0

    def command(self, yaw: float | None = None, pitch: float | None = None) -> None:
        """Set joint targets (clamped to Pepper's limits); None keeps a target."""
        if yaw is not None and math.isfinite(yaw):
            self.target_yaw = min(max(yaw, HEAD_YAW_LIMITS[0]), HEAD_YAW_LIMITS[1])
        if pitch is not None and math.isfinite(pitch):
            self.target_pitch = min(max(pitch, HEAD_PITCH_LIMITS[0]), HEAD_PITCH_LIMITS[1])

    def step(self, dt: float) -> None:
        d = self.max_speed * dt
        self.yaw += max(-d, min(d, self.target_yaw - self.yaw))
        self.pitch += max(-d, min(d, self.target_pitch - self.pitch))


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

    def observe(
        self,
        world: World,
        robot_pose: Pose2D,
        head_yaw: float,
        head_pitch: float,
        residents: Iterable[Resident],
        rng: np.random.Generator,
    ) -> list[CameraObservation]:
        """One observation per present resident in view and in line of sight."""
        cam = self.position(robot_pose, head_yaw)
        out: list[CameraObservation] = []
        for res in residents:
            if not res.present:
                continue
            torso = res.torso()
            seen = self.sight(
                world,
                robot_pose,
                head_yaw,
                head_pitch,
                np.vstack([[torso.x, torso.y, torso.z], res.body_corners()]),
                res.body.z_max,
                rng,
            )
            if seen is None:
                continue
            bbox, depth = seen
            out.append(
                CameraObservation(
                    name=res.name,
                    bbox=bbox,
                    depth=depth,
                    face_visible=self._faces_camera(res, cam),
                    backlit=self._backlit(world, res, cam),
                    position=Point(torso.x, torso.y, torso.z),
                    posture=res.posture,
                    activity=res.activity,
                    skeleton_occluded=res.skeleton_occluded,
                )
            )
        return out

    def _faces_camera(self, res: Resident, cam: tuple[float, float, float]) -> bool:
        to_cam = math.atan2(cam[1] - res.y, cam[0] - res.x)
        diff = abs(math.atan2(math.sin(to_cam - res.heading), math.cos(to_cam - res.heading)))
        return diff <= math.radians(self.params.face_angle_deg)

    def _backlit(self, world: World, res: Resident, cam: tuple[float, float, float]) -> bool:
        """A light source behind the person, within a small (planar) angle of the viewing
        ray; windows are tall, so only the bearing matters."""
        ray = math.atan2(res.y - cam[1], res.x - cam[0])
        limit = math.radians(self.params.backlit_angle_deg)
        for light in world.home.lights:
            if math.hypot(light.x - res.x, light.y - res.y) < 1e-6:
                continue
            bearing = math.atan2(light.y - res.y, light.x - res.x)
            if abs(math.atan2(math.sin(bearing - ray), math.cos(bearing - ray))) > limit:
                continue
            if world.line_of_sight((res.x, res.y), (light.x, light.y), light.z):
                return True
        return False
