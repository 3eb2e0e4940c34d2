"""Pepper's head (yaw/pitch joints) and its RGB-D camera, observing residents.

The camera does not render pixels: it projects each resident's posture-dependent body box
into the image and reports what a detector and a face/skeleton pipeline could get from it
(box, noisy depth, face towards the camera, backlit face), plus ground truth for scoring.
Pitch follows Pepper's convention: positive looks down.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np
import numpy.typing as npt

from amiro.core.messages import Point, Pose2D
from amiro.home.world import World
from amiro.robot.camera import Camera, CameraObservation
from amiro.sim.residents import Resident

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


def observe_residents(
    camera: Camera,
    world: World,
    robot_pose: Pose2D,
    head_yaw: float,
    head_pitch: float,
    residents: Iterable[Resident],
    rng: np.random.Generator,
) -> list[CameraObservation]:
    """One observation per present resident in view and in line of sight."""
    cam = camera.position(robot_pose, head_yaw)
    out: list[CameraObservation] = []
    for res in residents:
        if not res.present:
            continue
        torso = res.torso()
        seen = camera.sight(
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
                face_visible=_faces_camera(camera, res, cam),
                backlit=_backlit(camera, world, res, cam),
                position=Point(torso.x, torso.y, torso.z),
                posture=res.posture,
                activity=res.activity,
                skeleton_occluded=res.skeleton_occluded,
            )
        )
    return out


def _faces_camera(camera: Camera, res: Resident, cam: tuple[float, float, float]) -> bool:
    to_cam = math.atan2(cam[1] - res.y, cam[0] - res.x)
    diff = abs(math.atan2(math.sin(to_cam - res.heading), math.cos(to_cam - res.heading)))
    return diff <= math.radians(camera.params.face_angle_deg)


def _backlit(camera: Camera, world: World, res: Resident, cam: tuple[float, float, float]) -> bool:
    """A light source behind the person, within a small (planar) angle of the viewing
    ray; windows are tall, so only the bearing matters."""
    ray = math.atan2(res.y - cam[1], res.x - cam[0])
    limit = math.radians(camera.params.backlit_angle_deg)
    for light in world.home.lights:
        if math.hypot(light.x - res.x, light.y - res.y) < 1e-6:
            continue
        bearing = math.atan2(light.y - res.y, light.x - res.x)
        if abs(math.atan2(math.sin(bearing - ray), math.cos(bearing - ray))) > limit:
            continue
        if world.line_of_sight((res.x, res.y), (light.x, light.y), light.z):
            return True
    return False
