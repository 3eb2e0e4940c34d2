"""A generated RGB-D frame of people, for checking and timing the camera backend offline.

Each person is an upright cylinder (a torso-sized radius, a person's height) standing on the
floor in front of a far wall; every pixel's ray from the head camera (the simulator's
:class:`~amiro.sim.camera.Camera`: mount, head yaw and pitch, robot pose) is cast against
them, so the depth image holds true z-depths and each person's box is the exact extent of
their pixels, what an ideal detector would report.  For a detector that needs a human
shape (HOG), ``drawn`` paints a blurred human silhouette over each person's box.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from amiro.core.messages import BoundingBox2D, Pose2D
from amiro.core.vision import import_cv2
from amiro.robot.camera import Camera

FloatArray = npt.NDArray[np.float64]

WALL_M = 8.0  # depth where a ray meets nothing nearer
FLOOR_RGB, WALL_RGB = (90, 80, 70), (200, 200, 190)


@dataclass(frozen=True)
class Cylinder:
    """A person: centre on the floor (map frame), radius and height (m), RGB colour."""

    x: float
    y: float
    radius: float = 0.15
    height: float = 1.7
    colour: tuple[int, int, int] = (40, 60, 150)


@dataclass(frozen=True, eq=False)
class Scene:
    rgb: npt.NDArray[np.uint8]
    depth: FloatArray  # z-depth (m) at the RGB resolution
    boxes: list[BoundingBox2D | None]  # per person; None when no pixel shows them


def rays(camera: Camera, robot: Pose2D, head_yaw: float, head_pitch: float) -> FloatArray:
    """Map-frame ray directions ``(H, W, 3)`` of every pixel, scaled so that the ray
    parameter is the z-depth along the optical axis."""
    p = camera.params
    u, v = np.meshgrid(np.arange(p.width) + 0.5, np.arange(p.image_height) + 0.5)
    x, y = (u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy  # optical, z = 1
    cp, sp = math.cos(head_pitch), math.sin(head_pitch)
    forward, up, left = cp - y * sp, -sp - y * cp, -x
    yaw = robot.theta + head_yaw
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.stack([forward * cy - left * sy, forward * sy + left * cy, up], axis=-1)


def render(
    camera: Camera,
    robot: Pose2D,
    people: list[Cylinder],
    head_yaw: float = 0.0,
    head_pitch: float = 0.0,
    drawn: bool = False,
) -> Scene:
    """The frame the head camera takes of ``people`` from ``robot``'s pose; with ``drawn``,
    each person is painted as a human silhouette filling their box instead of their
    colour."""
    d = rays(camera, robot, head_yaw, head_pitch)
    origin = np.array(camera.position(robot, head_yaw))
    depth = np.full(d.shape[:2], WALL_M)
    falling = d[..., 2] < 0
    floor_t = np.where(falling, -origin[2] / np.where(falling, d[..., 2], -1.0), np.inf)
    depth = np.minimum(depth, floor_t)
    rgb = np.empty((*depth.shape, 3), dtype=np.uint8)
    rgb[:] = WALL_RGB
    rgb[floor_t <= WALL_M] = FLOOR_RGB
    owner = np.full(depth.shape, -1)
    for k, person in enumerate(people):
        t = _hit(origin, d, person)
        nearer = t < depth
        depth[nearer], owner[nearer] = t[nearer], k
        if not drawn:
            rgb[nearer] = person.colour
    boxes = [_box(owner == k) for k in range(len(people))]
    if drawn:
        cv2 = import_cv2()
        for box in boxes:
            if box is not None:
                silhouette(rgb, round(box.cx), round(box.cy - box.height / 2), box.height)
        rgb = np.asarray(cv2.GaussianBlur(rgb, (5, 5), 0), dtype=np.uint8)
    return Scene(rgb, depth, boxes)


def silhouette(
    image: npt.NDArray[np.uint8], cx: int, top: int, height: float, colour: int = 40
) -> None:
    """Draw an upright person ``height`` pixels tall (head, neck, torso, arms, legs), head
    top at ``top``, in place."""
    cv2 = import_cv2()
    s = height / 8.0  # a head is an eighth of a body

    def p(dx: float, dy: float) -> list[int]:
        return [round(cx + dx * s), round(top + dy * s)]

    grey = (colour, colour, colour)
    cv2.circle(image, p(0, 0.5), round(0.5 * s), grey, -1)
    parts = [
        [p(-0.25, 0.9), p(0.25, 0.9), p(0.25, 1.2), p(-0.25, 1.2)],  # neck
        [p(-1.0, 1.2), p(1.0, 1.2), p(0.8, 4.2), p(-0.8, 4.2)],  # torso
    ]
    for side in (-1, 1):
        parts.append([p(side, 1.3), p(1.4 * side, 1.5), p(1.3 * side, 4.3), p(0.95 * side, 4.2)])
        parts.append(
            [p(0.05 * side, 4.2), p(0.8 * side, 4.2), p(0.75 * side, 8), p(0.15 * side, 8)]
        )
    cv2.fillPoly(image, [np.array(part, dtype=np.int32) for part in parts], grey)


def _hit(origin: FloatArray, d: FloatArray, c: Cylinder) -> FloatArray:
    """Ray parameter of the first hit on the cylinder's side, inf where missed."""
    ox, oy = origin[0] - c.x, origin[1] - c.y
    a = d[..., 0] ** 2 + d[..., 1] ** 2
    b = 2.0 * (ox * d[..., 0] + oy * d[..., 1])
    disc = b * b - 4.0 * a * (ox * ox + oy * oy - c.radius**2)
    root = np.sqrt(np.maximum(disc, 0.0))
    t = (-b - root) / np.maximum(2.0 * a, 1e-12)
    z = origin[2] + t * d[..., 2]
    hit = (disc >= 0) & (t > 0) & (z >= 0.0) & (z <= c.height)
    return np.where(hit, t, np.inf)


def _box(mask: npt.NDArray[np.bool_]) -> BoundingBox2D | None:
    rows, cols = np.nonzero(mask)
    if not len(rows):
        return None
    u0, u1, v0, v1 = cols.min(), cols.max() + 1, rows.min(), rows.max() + 1
    return BoundingBox2D((u0 + u1) / 2.0, (v0 + v1) / 2.0, float(u1 - u0), float(v1 - v0))
