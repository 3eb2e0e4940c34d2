"""3D position of detected people: the paper's formulas (section 3.3) and an improved estimator.

Both work on arrays (one row per detection) so a frame, or a whole dataset, is one call.
Conventions follow the simulator's head: the camera sits ``mount_forward`` ahead of the base
centre at ``mount_height``, turns with the head yaw about the base's vertical axis and looks
down for positive pitch; pixels are (u right, v down).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from amiro.core.messages import CameraInfo

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class CameraGeometry:
    """Pinhole intrinsics of the RGB image and where the camera sits on the head."""

    fx: float
    fy: float
    cx: float
    cy: float
    width: int
    height: int
    mount_height: float = 1.15
    mount_forward: float = 0.08

    @classmethod
    def from_info(
        cls, info: CameraInfo, mount_height: float = 1.15, mount_forward: float = 0.08
    ) -> CameraGeometry:
        return cls(
            info.fx, info.fy, info.cx, info.cy, info.width, info.height, mount_height, mount_forward
        )

    @property
    def hfov(self) -> float:
        return 2.0 * math.atan(self.width / (2.0 * self.fx))

    @property
    def vfov(self) -> float:
        return 2.0 * math.atan(self.height / (2.0 * self.fy))


@dataclass(frozen=True, slots=True)
class Views:
    """Where the robot was and how its head was turned, one row per detection."""

    x: FloatArray
    y: FloatArray
    theta: FloatArray
    head_yaw: FloatArray
    head_pitch: FloatArray

    @classmethod
    def single(
        cls, x: float, y: float, theta: float, head_yaw: float, head_pitch: float, n: int
    ) -> Views:
        def full(v: float) -> FloatArray:
            return np.full(n, v, dtype=np.float64)

        return cls(full(x), full(y), full(theta), full(head_yaw), full(head_pitch))


def base_to_map(points: FloatArray, views: Views) -> FloatArray:
    """Points (N, 3) in each robot's base frame to the map frame."""
    c, s = np.cos(views.theta), np.sin(views.theta)
    x = views.x + c * points[:, 0] - s * points[:, 1]
    y = views.y + s * points[:, 0] + c * points[:, 1]
    return np.stack([x, y, points[:, 2]], axis=1)


def paper_formula(
    geom: CameraGeometry,
    u: FloatArray,
    v: FloatArray,
    d: FloatArray,
    views: Views,
    fov: str = "half",
) -> FloatArray:
    """Section 3.3's formulas: linear angles from the field of view, ``d`` the depth reading
    at the detection.  The paper calls ``hfov``/``vfov`` "the maximum angles": read as the
    angle at the image edge (``fov="half"``, half the field of view, the default), a pixel
    at the border gets the angle its ray really has; read as the full field of view
    (``fov="full"``), every angle comes out doubled.  The result is relative to the robot;
    it is put in the map frame with the robot's pose, and z (the drop below the camera, as
    pitch and beta grow downwards) is turned into a height above the floor."""
    if fov not in ("half", "full"):
        raise ValueError(f"fov must be 'half' or 'full', not {fov!r}")
    share = 0.5 if fov == "half" else 1.0
    alpha = share * geom.hfov * ((geom.width / 2.0 - u) / (geom.width / 2.0))
    beta = share * geom.vfov * ((v - geom.height / 2.0) / (geom.height / 2.0))
    x = d * np.cos(alpha + views.head_yaw)
    y = d * np.sin(alpha + views.head_yaw)
    z = d * np.sin(beta + views.head_pitch)
    return base_to_map(np.stack([x, y, geom.mount_height - z], axis=1), views)


def improved(
    geom: CameraGeometry,
    u: FloatArray,
    v: FloatArray,
    z_depth: FloatArray,
    views: Views,
    surface_to_centre: float = 0.0,
) -> FloatArray:
    """Pinhole back-projection of pixel (u, v) at z-depth ``z_depth`` (along the optical axis,
    as depth sensors report it), pushed ``surface_to_centre`` further along the horizontal
    viewing ray (the body's centre lies behind its visible surface), then through the head
    (pitch, yaw, camera mount) and the robot's pose into the map frame."""
    right = (u - geom.cx) / geom.fx * z_depth
    down = (v - geom.cy) / geom.fy * z_depth
    cp, sp = np.cos(views.head_pitch), np.sin(views.head_pitch)
    forward = z_depth * cp - down * sp
    up = -z_depth * sp - down * cp
    left = -right
    if surface_to_centre:
        scale = 1.0 + surface_to_centre / np.maximum(np.hypot(forward, left), 1e-6)
        forward, left = forward * scale, left * scale
    cy, sy = np.cos(views.head_yaw), np.sin(views.head_yaw)
    x = geom.mount_forward * cy + forward * cy - left * sy
    y = geom.mount_forward * sy + forward * sy + left * cy
    return base_to_map(np.stack([x, y, geom.mount_height + up], axis=1), views)


# Heights (m) that complete a body the image border cut: people stand or sit on the floor,
# and a body cut at the top of the image is a standing adult's.
FLOOR_HEIGHT = 0.0
STANDING_HEIGHT = 1.70
CLIP_MARGIN = 0.01  # a box edge this near the border (share of the image height) is cut


def body_centre_row(
    geom: CameraGeometry,
    top: FloatArray,
    bottom: FloatArray,
    z_depth: FloatArray,
    head_pitch: FloatArray,
) -> FloatArray:
    """The image row of the body's vertical centre for boxes spanning rows ``top`` to
    ``bottom`` at ``z_depth``.  The box centre, unless the image border cut the box (a person
    close to the camera): the cut end is then completed with the floor (bottom) or a
    standing person's height (top), so the estimate is not pulled to the camera's height."""
    cp, sp = np.cos(head_pitch), np.sin(head_pitch)

    def height(v: FloatArray) -> FloatArray:
        down = (v - geom.cy) / geom.fy * z_depth
        return geom.mount_height - z_depth * sp - down * cp

    def row(z: FloatArray) -> FloatArray:
        down = (geom.mount_height - z - z_depth * sp) / cp
        return geom.cy + geom.fy * down / np.maximum(z_depth, 1e-6)

    margin = CLIP_MARGIN * geom.height
    z_top, z_bottom = height(top), height(bottom)
    z_top = np.where(top <= margin, np.maximum(z_top, STANDING_HEIGHT), z_top)
    z_bottom = np.where(
        bottom >= geom.height - margin, np.minimum(z_bottom, FLOOR_HEIGHT), z_bottom
    )
    return row(0.5 * (z_top + z_bottom))
