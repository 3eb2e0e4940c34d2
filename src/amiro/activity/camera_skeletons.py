"""Skeleton streams from the robot's RGB-D camera: the ``camera-onnx`` activity source.

At the activity model's frame rate, the newest camera frame goes through a 2D pose
estimator; each person's keypoints are mapped to the NTU-25 layout
(:func:`~amiro.activity.keypoints.to_ntu`), lifted with the registered depth image
(:func:`~amiro.activity.lifting.lift_frame`) and levelled (the head pitch undone, as the
model's training views are).  Bodies are followed from frame to frame by box overlap; a
body not seen in a tick gets an unseen (NaN) frame, and is forgotten after ``forget_s``.

A person's name (or track id) is matched to the body at the position the people finder
tracks them at; without a finder or a track, the only body in view is taken.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from amiro.activity.keypoints import to_ntu
from amiro.activity.lifting import level, lift_frame
from amiro.activity.pose import PoseDetection, PoseEstimator
from amiro.activity.skeleton import NUM_JOINTS, FloatArray
from amiro.core.clock import wall_seconds
from amiro.core.messages import BoundingBox2D, Point
from amiro.core.node import Node
from amiro.core.vision import iou
from amiro.robot.camera_feed import CameraFeed, RgbdFrame

HISTORY_S = 4.0  # skeletons kept per body
MATCH_IOU = 0.3  # a pose box overlapping a body's last box this much continues it
MATCH_M = 0.8  # a tracked person's body is within this distance of the track

# Where a person is tracked (map frame), by name or track id; None if not tracked.
PersonLocator = Callable[[str], Point | None]
# Map-frame torso points of boxes in a frame (NaN rows when unknown); None without a pose.
BoxPlacer = Callable[[RgbdFrame, list[BoundingBox2D]], FloatArray | None]


@dataclass
class Body:
    """One person followed in the image: skeletons at the model's rate, newest last."""

    box: BoundingBox2D
    last_seen: float
    position: Point | None = None  # map frame, when the robot's pose was known
    frames: deque[FloatArray] = field(default_factory=deque)


@dataclass
class SkeletonStats:
    frames: int = 0  # camera frames run through the pose estimator
    total_ms: float = 0.0

    @property
    def ms_per_frame(self) -> float:
        return self.total_ms / self.frames if self.frames else 0.0


class CameraSkeletonSource(Node):
    """A :class:`~amiro.activity.recognizer.SkeletonSource` fed by the camera."""

    def __init__(
        self,
        feed: CameraFeed,
        estimator: PoseEstimator,
        fps: float,
        min_keypoint: float = 0.3,
        locate: PersonLocator | None = None,
        place: BoxPlacer | None = None,
        forget_s: float = 2.0,
        name: str = "camera_skeletons",
    ) -> None:
        super().__init__(name)
        self.feed = feed
        self.estimator = estimator
        self.fps = fps
        self.min_keypoint = min_keypoint
        self.locate = locate
        self.place = place
        self.forget_s = forget_s
        self.bodies: list[Body] = []
        self.image_height = 0
        self.stats = SkeletonStats()
        self._last_stamp: float | None = None

    def on_start(self) -> None:
        self.create_timer(1.0 / self.fps, self.tick)

    def tick(self) -> None:
        """Take the newest frame (once) into the bodies' streams."""
        frame = self.feed.latest(max_age_s=2.0 / self.fps)
        if frame is None or frame.stamp == self._last_stamp:
            self._age(self.now())
            return
        self._last_stamp = frame.stamp
        started = wall_seconds()
        poses = self.estimator.estimate(frame.rgb)
        skeletons = [self.skeleton(frame, p) for p in poses]
        self.stats.total_ms += 1000.0 * (wall_seconds() - started)
        self.stats.frames += 1
        self.image_height = frame.info.height
        places = self.place(frame, [p.box for p in poses]) if self.place and poses else None
        self._follow(frame.stamp, poses, skeletons, places)

    def skeleton(self, frame: RgbdFrame, pose: PoseDetection) -> FloatArray:
        """One person's levelled NTU-25 skeleton ``(25, 3)``, NaN where unseen."""
        fmt = self.estimator.keypoint_format
        pixels = to_ntu(pose.keypoints[None], fmt, self.min_keypoint)[0]
        return level(lift_frame(pixels, frame.depth, frame.info), frame.head_pitch)

    def _follow(
        self,
        now: float,
        poses: list[PoseDetection],
        skeletons: list[FloatArray],
        places: FloatArray | None,
    ) -> None:
        pairs = sorted(
            ((iou(b.box, p.box), bi, pi) for bi, b in enumerate(self.bodies)
             for pi, p in enumerate(poses)),
            reverse=True,
        )  # fmt: skip
        taken: dict[int, int] = {}  # pose -> body
        for overlap, bi, pi in pairs:
            if overlap >= MATCH_IOU and bi not in taken.values() and pi not in taken:
                taken[pi] = bi
        seen: set[int] = set()
        for pi, pose in enumerate(poses):
            if pi in taken:
                bi = taken[pi]
            else:
                self.bodies.append(Body(pose.box, now, frames=self._deque()))
                bi = len(self.bodies) - 1
            body = self.bodies[bi]
            body.box, body.last_seen = pose.box, now
            body.frames.append(skeletons[pi])
            if places is not None and np.isfinite(places[pi]).all():
                body.position = Point(*map(float, places[pi]))
            seen.add(bi)
        unseen = np.full((NUM_JOINTS, 3), np.nan)
        for bi, body in enumerate(self.bodies):
            if bi not in seen:
                body.frames.append(unseen)
        self._age(now)

    def _deque(self) -> deque[FloatArray]:
        return deque(maxlen=max(int(HISTORY_S * self.fps), 2))

    def _age(self, now: float) -> None:
        self.bodies = [b for b in self.bodies if now - b.last_seen <= self.forget_s]

    def body_of(self, person: str) -> Body | None:
        """The body of ``person``: nearest to where they are tracked, else the only one."""
        where = self.locate(person) if self.locate is not None else None
        if where is not None:
            placed = [b for b in self.bodies if b.position is not None]
            near = min(placed, key=lambda b: _distance(b.position, where), default=None)
            if near is not None and _distance(near.position, where) <= MATCH_M:
                return near
            return None
        return self.bodies[0] if len(self.bodies) == 1 else None

    def window(self, person: str, frames: int) -> FloatArray | None:
        body = self.body_of(person)
        if body is None or not body.frames:
            return None
        recent = list(body.frames)[-frames:]
        # The stream started less than a window ago: its first frame stands for the rest.
        return np.stack([recent[0]] * (frames - len(recent)) + recent)

    def framing(self, person: str) -> tuple[float, bool] | None:
        body = self.body_of(person)
        if body is None or self.image_height <= 0:
            return None
        h = float(self.image_height)
        top = body.box.cy - body.box.height / 2.0
        bottom = body.box.cy + body.box.height / 2.0
        return body.box.height / h, top <= 0.5 or bottom >= h - 0.5


def _distance(a: Point | None, b: Point) -> float:
    return float("inf") if a is None else float(np.hypot(a.x - b.x, a.y - b.y))
