"""The paper's section-4.2 RGB-D dataset, generated: people at 2–5 m in five postures seen
from five camera placements, with depth images, head angles and ground truth.

People are a few boxes each (legs, trunk, head), in a scene with a floor, a wall behind and
the couch or desk their posture needs.  Depth images are ray-cast in batches (no per-pixel
Python), with the noise of Pepper's depth sensor (sigma growing with the square of the
depth) and dropped pixels.  The person box comes from the sim :class:`Camera`; the ground
truth follows the simulator's convention: the body's centre, at the height of its torso.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from amiro.core.messages import Pose2D
from amiro.perception.estimation import CameraGeometry, Views, improved
from amiro.robot.camera import Camera

FloatArray = npt.NDArray[np.float64]

POSTURES = ("standing_front", "standing_back", "sitting_desk", "sitting_couch", "lying_couch")
CAMERAS = ("rotated_right", "rotated_left", "centred", "right_1m", "left_1m")
DISTANCES = (2.0, 3.0, 4.0, 5.0)
SIM_POSTURE = {
    "standing_front": "standing",
    "standing_back": "standing",
    "sitting_desk": "sitting_desk",
    "sitting_couch": "sitting_couch",
    "lying_couch": "lying_couch",
}

# Body parts in the person's frame (forward, left, up): (min corner, max corner), metres
# for a person of scale 1.  The footprint is centred on the person's position.
BODY_PARTS: dict[str, tuple[tuple[tuple[float, ...], tuple[float, ...]], ...]] = {
    "standing": (
        ((-0.10, -0.16, 0.0), (0.10, 0.16, 0.85)),
        ((-0.15, -0.22, 0.85), (0.15, 0.22, 1.45)),
        ((-0.10, -0.08, 1.45), (0.10, 0.08, 1.70)),
    ),
    "sitting": (
        ((-0.25, -0.20, 0.45), (0.0, 0.20, 1.0)),
        ((-0.05, -0.17, 0.42), (0.25, 0.17, 0.58)),
        ((0.12, -0.17, 0.0), (0.25, 0.17, 0.45)),
        ((-0.20, -0.08, 1.0), (-0.02, 0.08, 1.25)),
    ),
    "lying": (
        ((-0.90, -0.16, 0.42), (-0.05, 0.16, 0.62)),
        ((-0.05, -0.22, 0.42), (0.60, 0.22, 0.72)),
        ((0.60, -0.09, 0.45), (0.90, 0.09, 0.65)),
    ),
}
MAX_PARTS = 6  # body parts plus furniture, per scene


@dataclass(frozen=True, slots=True)
class DatasetSpec:
    people: int = 17
    images: int = 5
    distances: tuple[float, ...] = DISTANCES
    depth_width: int = 80  # Pepper's depth camera also streams 80 x 60
    depth_height: int = 60
    rotation_rad: float = 0.3  # head yaw of the rotated placements
    pitch_rad: float = 0.15  # head pitch while recording (looks down), plus a little jitter
    depth_sigma: float = 1.4e-3  # noise sigma = depth_sigma * z^2 (metres)
    dropout: float = 0.03  # share of pixels with no depth reading
    max_range: float = 8.0
    batch: int = 64

    @property
    def size(self) -> int:
        return self.people * len(self.distances) * len(POSTURES) * len(CAMERAS) * self.images


@dataclass(frozen=True, eq=False)
class RgbdBatch:
    """Samples in rows: depth images (metres, 0 = no reading) and everything to score."""

    depth: npt.NDArray[np.float32]  # (B, h, w)
    box: FloatArray  # (B, 4) person box in RGB pixels: cx, cy, width, height
    truth: FloatArray  # (B, 3) body centre at torso height, map frame
    views: Views
    distance: FloatArray  # nominal camera-to-person distance
    posture: npt.NDArray[np.int64]  # index into POSTURES
    camera: npt.NDArray[np.int64]  # index into CAMERAS
    person: npt.NDArray[np.int64]

    @property
    def depth_scale(self) -> float:
        """Depth-image pixels per RGB pixel."""
        return float(self.depth.shape[2]) / 640.0


@dataclass(frozen=True, slots=True)
class _Scene:
    pose: Pose2D
    yaw: float
    pitch: float
    truth: tuple[float, float, float]
    body: FloatArray  # (k, 2, 3) part corners in the map frame, axis-aligned after rotation
    heading: float
    boxes: FloatArray  # (MAX_PARTS, 2, 3) lo/hi in each part's frame
    centres: FloatArray  # (MAX_PARTS, 3)
    yaws: FloatArray  # (MAX_PARTS,)


def _furniture(posture: str) -> list[tuple[tuple[float, ...], tuple[float, ...]]]:
    """Furniture around the person, in map offsets from the person (camera looks along +x)."""
    if posture in ("sitting_couch", "lying_couch"):
        return [((-0.35, -1.1, 0.0), (0.45, 1.1, 0.42)), ((0.45, -1.1, 0.0), (0.65, 1.1, 0.85))]
    if posture == "sitting_desk":
        return [((-0.4, 0.35, 0.0), (0.4, 1.15, 0.75))]
    return []


def _scene(
    spec: DatasetSpec,
    posture: str,
    camera: str,
    distance: float,
    scale: float,
    rng: np.random.Generator,
    cam: Camera,
) -> _Scene:
    lateral = {"right_1m": -1.0, "left_1m": 1.0}.get(camera, 0.0)
    yaw = {"rotated_right": -spec.rotation_rad, "rotated_left": spec.rotation_rad}.get(camera, 0.0)
    yaw += float(rng.normal(0.0, 0.02))
    pose = Pose2D(0.0, lateral, 0.0)
    px = cam.params.forward + distance + float(rng.normal(0.0, 0.05))
    py = float(rng.normal(0.0, 0.05))
    heading = {
        "standing_front": math.pi,
        "standing_back": 0.0,
        "sitting_desk": math.pi / 2,
        "sitting_couch": math.pi,
        "lying_couch": math.pi / 2 if rng.random() < 0.5 else -math.pi / 2,
    }[posture] + float(rng.normal(0.0, 0.1))
    kind = SIM_POSTURE[posture].split("_")[0]
    parts = np.array(BODY_PARTS[kind], dtype=np.float64) * scale
    if kind == "lying":  # lies on the seat whatever the person's size
        parts[:, :, 2] += 0.42 * (1.0 - scale)
    z_lo, z_hi = parts[:, 0, 2].min(), parts[:, 1, 2].max()
    truth = (px, py, 0.5 * float(z_lo + z_hi))
    furniture = np.array(_furniture(posture), dtype=np.float64).reshape(-1, 2, 3)
    n_body, n_furn = len(parts), len(furniture)
    boxes = np.zeros((MAX_PARTS, 2, 3))
    boxes[:, 0] = 1.0  # empty boxes (lo > hi) pad the scene
    boxes[:n_body] = parts
    centres = np.zeros((MAX_PARTS, 3))
    centres[:n_body] = (px, py, 0.0)
    yaws = np.zeros(MAX_PARTS)
    yaws[:n_body] = heading
    boxes[n_body : n_body + n_furn] = furniture
    centres[n_body : n_body + n_furn] = (px, py, 0.0)
    pitch = spec.pitch_rad + float(rng.normal(0.0, 0.02))
    return _Scene(pose, yaw, pitch, truth, parts, heading, boxes, centres, yaws)


def _person_box(scene: _Scene, cam: Camera) -> tuple[float, float, float, float]:
    """The person's box in the RGB image: projected part corners, clipped to the image."""
    c, s = math.cos(scene.heading), math.sin(scene.heading)
    corners = np.array(
        [
            [x, y, z]
            for lo, hi in scene.body
            for x, y, z in itertools.product(*zip(lo, hi, strict=True))
        ]
    )
    mx = scene.truth[0] + c * corners[:, 0] - s * corners[:, 1]
    my = scene.truth[1] + s * corners[:, 0] + c * corners[:, 1]
    optical = cam.to_optical(
        np.stack([mx, my, corners[:, 2]], axis=1), scene.pose, scene.yaw, scene.pitch
    )
    uv = cam.project(optical[optical[:, 2] > 0.05])
    w, h = cam.params.width, cam.params.image_height
    u0, v0 = np.clip(uv.min(axis=0), 0.0, [w, h])
    u1, v1 = np.clip(uv.max(axis=0), 0.0, [w, h])
    return float(u0 + u1) / 2, float(v0 + v1) / 2, float(u1 - u0), float(v1 - v0)


def render_depth(
    geom: CameraGeometry,
    views: Views,
    scene: tuple[FloatArray, FloatArray, FloatArray, FloatArray],
    size: tuple[int, int],
    wall_x: FloatArray,
    max_range: float,
) -> FloatArray:
    """Noise-free z-depth images (B, h, w) of a floor, a wall at ``wall_x`` and oriented
    boxes; ``scene`` is (lo, hi, centre, yaw) per box, (B, K, 3) x 3 and (B, K), and boxes
    with lo > hi on x are absent."""
    lo, hi, centres, yaws = scene
    w, h = size
    scale = w / geom.width
    cols, rows = np.meshgrid((np.arange(w) + 0.5) / scale, (np.arange(h) + 0.5) / scale)
    b, n = len(views.x), cols.size
    flat = Views(
        *(
            np.repeat(a, n)
            for a in (views.x, views.y, views.theta, views.head_yaw, views.head_pitch)
        )
    )
    uu, vv = np.tile(cols.ravel(), b), np.tile(rows.ravel(), b)
    origin = improved(geom, uu, vv, np.zeros(b * n), flat).reshape(b, n, 3)
    ray = (improved(geom, uu, vv, np.ones(b * n), flat).reshape(b, n, 3) - origin).astype(
        np.float32
    )
    ray[np.abs(ray) < 1e-9] = 1e-9  # no division by zero in the slab test
    inv = 1.0 / ray
    t = np.where(ray[..., 2] < 0, -origin[..., 2] * inv[..., 2], np.inf).astype(np.float32)
    t_wall = np.where(ray[..., 0] > 0, (wall_x[:, None] - origin[..., 0]) * inv[..., 0], np.inf)
    t = np.minimum(t, t_wall.astype(np.float32))
    for k in range(lo.shape[1]):
        present = (lo[:, k, 0] <= hi[:, k, 0])[:, None]
        c, s = np.cos(yaws[:, k])[:, None], np.sin(yaws[:, k])[:, None]
        ox = origin[..., 0] - centres[:, None, k, 0]
        oy = origin[..., 1] - centres[:, None, k, 1]
        local: tuple[tuple[Any, Any], ...] = (
            (c * ox + s * oy, c * ray[..., 0] + s * ray[..., 1]),
            (-s * ox + c * oy, -s * ray[..., 0] + c * ray[..., 1]),
            (origin[..., 2] - centres[:, None, k, 2], ray[..., 2]),
        )
        near = np.full(t.shape, -np.inf, dtype=np.float32)
        far = np.full(t.shape, np.inf, dtype=np.float32)
        for axis, (o, d) in enumerate(local):
            step = np.where(np.abs(d) < 1e-9, 1e-9, d)
            t1 = (lo[:, None, k, axis] - o) / step
            t2 = (hi[:, None, k, axis] - o) / step
            near = np.maximum(near, np.minimum(t1, t2))
            far = np.minimum(far, np.maximum(t1, t2))
        hit = present & (far >= near) & (near > 0) & (near < t)
        t = np.where(hit, near, t)
    t = np.where(t <= max_range, t, 0.0)
    return t.reshape(b, h, w).astype(np.float64)


def generate(
    rng: np.random.Generator, spec: DatasetSpec | None = None, camera: Camera | None = None
) -> Iterator[RgbdBatch]:
    """The dataset in batches of ``spec.batch`` samples (people x distances x postures x
    cameras x images, in that order)."""
    spec = spec or DatasetSpec()
    cam = camera or Camera()
    geom = CameraGeometry.from_info(cam.info(0.0), cam.params.height, cam.params.forward)
    scales = rng.uniform(0.9, 1.1, spec.people)
    combos = list(
        itertools.product(
            range(spec.people),
            spec.distances,
            range(len(POSTURES)),
            range(len(CAMERAS)),
            range(spec.images),
        )
    )
    for start in range(0, len(combos), spec.batch):
        chunk = combos[start : start + spec.batch]
        scenes = [
            _scene(spec, POSTURES[p], CAMERAS[c], d, float(scales[i]), rng, cam)
            for i, d, p, c, _ in chunk
        ]
        views = Views(
            np.array([s.pose.x for s in scenes]),
            np.array([s.pose.y for s in scenes]),
            np.array([s.pose.theta for s in scenes]),
            np.array([s.yaw for s in scenes]),
            np.array([s.pitch for s in scenes]),
        )
        boxes = np.stack([s.boxes for s in scenes])
        depth = render_depth(
            geom,
            views,
            (
                boxes[:, :, 0],
                boxes[:, :, 1],
                np.stack([s.centres for s in scenes]),
                np.stack([s.yaws for s in scenes]),
            ),
            (spec.depth_width, spec.depth_height),
            np.array([s.truth[0] + 1.5 for s in scenes]),
            spec.max_range,
        )
        depth = depth + spec.depth_sigma * depth**2 * rng.standard_normal(depth.shape)
        depth[rng.random(depth.shape) < spec.dropout] = 0.0
        yield RgbdBatch(
            depth=np.maximum(depth, 0.0).astype(np.float32),
            box=np.array([_person_box(s, cam) for s in scenes]),
            truth=np.array([s.truth for s in scenes]),
            views=views,
            distance=np.array([d for _, d, _, _, _ in chunk]),
            posture=np.array([p for _, _, p, _, _ in chunk], dtype=np.int64),
            camera=np.array([c for _, _, _, c, _ in chunk], dtype=np.int64),
            person=np.array([i for i, _, _, _, _ in chunk], dtype=np.int64),
        )
