"""The simulator's object detector: boxes from the camera model with YOLO's error profile.

The paper (Tables 11–13) counts detections per image: people lying down are missed or split
in two far more often than anyone else, errors grow with distance, and a few false positives
appear.  This backend reproduces those counting errors on the simulator's observations of
people; household objects are found with a recall by label that falls with distance.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Protocol, TypeVar

import numpy as np

from amiro.core.messages import BoundingBox2D, Detection2D
from amiro.core.vision import iou
from amiro.perception.config import SimDetectorSection
from amiro.perception.ports import Frame
from amiro.perception.sim_objects import ObjectObservation
from amiro.robot.camera import CameraObservation


def distance_factor(distance: float) -> float:
    """Relative error rate by distance (mean 1 over 2–5 m), after the paper's Table 13."""
    return min(0.5 + 0.4 * max(distance - 2.0, 0.0), 1.3)


class SimDetector:
    """Boxes from observations: people jittered, sometimes missed or duplicated; objects
    found by label and distance."""

    def __init__(
        self,
        rng: np.random.Generator,
        cfg: SimDetectorSection | None = None,
        image_size: tuple[int, int] = (640, 480),
    ) -> None:
        self.rng = rng
        self.cfg = cfg or SimDetectorSection()
        self.width, self.height = image_size

    def error_rate(self, obs: CameraObservation) -> float:
        return self.cfg.error_rate.get(obs.posture, 0.0) * distance_factor(obs.depth)

    def detect(self, frame: Frame) -> list[Detection2D]:
        found: list[Detection2D] = []
        for obs in frame.observations:
            found.extend(self._person(obs))
        for obj in frame.objects:
            if self.rng.random() < self.object_recall(obj):
                found.append(self._object(obj))
        for _ in range(int(self.rng.poisson(self.cfg.false_positives_per_frame))):
            found.append(self._false_positive())
        return found

    def _person(self, obs: CameraObservation) -> list[Detection2D]:
        rate = self.error_rate(obs)
        draw = float(self.rng.random())
        if draw < rate * (1.0 - self.cfg.duplicate_share):
            return []
        score = float(np.clip(0.95 - 0.04 * obs.depth + 0.03 * self.rng.standard_normal(), 0.3, 1))
        box = self._jitter(obs.bbox)
        if draw >= rate:
            return [Detection2D("person", score, box)]
        # A duplicate: a wide (lying) body split in two, else a second, upper-body box.
        b = box
        if b.width > b.height:
            halves = (b.cx - b.width / 4, b.cx + b.width / 4)
            return [
                Detection2D("person", score, BoundingBox2D(c, b.cy, b.width / 2, b.height))
                for c in halves
            ]
        upper = BoundingBox2D(b.cx, b.cy - b.height / 4, b.width, b.height / 2)
        return [Detection2D("person", score, box), Detection2D("person", 0.8 * score, upper)]

    def object_recall(self, obj: ObjectObservation) -> float:
        """Chance to find ``obj``: by label, falling with distance; none when tiny."""
        if min(obj.bbox.width, obj.bbox.height) < self.cfg.min_object_px:
            return 0.0
        recall = self.cfg.object_recall.get(obj.label, 0.0)
        return max(recall - self.cfg.object_recall_loss_per_m * max(obj.depth - 2.0, 0.0), 0.0)

    def _object(self, obj: ObjectObservation) -> Detection2D:
        score = 0.9 - 0.05 * obj.depth + 0.03 * self.rng.standard_normal()
        return Detection2D(obj.label, float(np.clip(score, 0.3, 1.0)), self._jitter(obj.bbox))

    def _jitter(self, b: BoundingBox2D) -> BoundingBox2D:
        """Noisy edges, except where the person runs off the image: a detector sees the
        body reach the border there."""
        j = self.cfg.box_jitter * self.rng.standard_normal(4)
        w = max(b.width * (1 + j[2]), 1.0)
        h = max(b.height * (1 + j[3]), 1.0)
        cx, cy = b.cx + j[0] * b.width, b.cy + j[1] * b.height
        u0, v0, u1, v1 = cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2
        if b.cx - b.width / 2 <= 0.0:
            u0 = 0.0
        if b.cy - b.height / 2 <= 0.0:
            v0 = 0.0
        if b.cx + b.width / 2 >= self.width:
            u1 = float(self.width)
        if b.cy + b.height / 2 >= self.height:
            v1 = float(self.height)
        jittered = BoundingBox2D((u0 + u1) / 2, (v0 + v1) / 2, u1 - u0, v1 - v0)
        return clip_box(jittered, self.width, self.height)

    def _false_positive(self) -> Detection2D:
        h = float(self.rng.uniform(0.15, 0.6)) * self.height
        w = h * float(self.rng.uniform(0.3, 0.6))
        cx = float(self.rng.uniform(w / 2, self.width - w / 2))
        cy = float(self.rng.uniform(h / 2, self.height - h / 2))
        return Detection2D("person", float(self.rng.uniform(0.3, 0.6)), BoundingBox2D(cx, cy, w, h))


def clip_box(b: BoundingBox2D, width: int, height: int) -> BoundingBox2D:
    """The part of ``b`` inside a ``width`` x ``height`` image (at least one pixel), as a
    real detector reports it."""
    u0 = min(max(b.cx - b.width / 2, 0.0), width - 1.0)
    v0 = min(max(b.cy - b.height / 2, 0.0), height - 1.0)
    u1 = min(max(b.cx + b.width / 2, u0 + 1.0), float(width))
    v1 = min(max(b.cy + b.height / 2, v0 + 1.0), float(height))
    return BoundingBox2D((u0 + u1) / 2, (v0 + v1) / 2, u1 - u0, v1 - v0)


class Boxed(Protocol):
    @property
    def bbox(self) -> BoundingBox2D: ...


BoxedT = TypeVar("BoxedT", bound=Boxed)


def best_match(
    box: BoundingBox2D, observations: Sequence[BoxedT], min_iou: float = 0.2
) -> BoxedT | None:
    """The observation whose box overlaps ``box`` most (at least ``min_iou``)."""
    scored = [(iou(box, o.bbox), i) for i, o in enumerate(observations)]
    best = max(scored, default=(0.0, -1))
    return observations[best[1]] if best[0] >= min_iou and not math.isnan(best[0]) else None
