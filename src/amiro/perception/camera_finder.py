"""People in the map frame from a real RGB-D camera: the ``camera`` perception backend.

The same pipeline as the simulated one (:mod:`amiro.perception.stack`), on pixels: an image
detector's person boxes → the robust torso depth of each box in the registered depth image
→ optionally the face in the box's upper half against a gallery → the improved estimator
through the head joints (or a fixed camera's angles) and the robot's localised pose → the
tracker.  A frame is processed once, however often it is looked at.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from amiro.core.clock import wall_seconds
from amiro.core.messages import BoundingBox2D, Detection2D, Point, Pose2D
from amiro.perception.config import PerceptionConfig
from amiro.perception.estimation import CameraGeometry, FloatArray, Views
from amiro.perception.faces import FaceGallery
from amiro.perception.locate import locate_people
from amiro.perception.ports import Detector, Frame, SeenPerson
from amiro.perception.stack import PoseSource
from amiro.perception.tracking import Measurement, PeopleTracker
from amiro.robot.camera_feed import CameraFeed, RgbdFrame

FACE_SHARE = 0.5  # the face is looked for in this upper share of a person's box


@dataclass
class CameraStats:
    """What the finder did: frames processed, the per-frame processing time (wall clock,
    measured only), and frames skipped for want of a camera frame or a robot pose."""

    frames: int = 0
    no_frame: int = 0
    no_pose: int = 0
    total_ms: float = 0.0
    last_ms: float = 0.0
    last_age_s: float = 0.0  # runtime-clock age of the last frame when processed

    @property
    def ms_per_frame(self) -> float:
        return self.total_ms / self.frames if self.frames else 0.0


class CameraPeopleFinder:
    """The :class:`~amiro.perception.ports.PeopleFinder` of a robot with an RGB-D camera."""

    def __init__(
        self,
        feed: CameraFeed,
        detector: Detector,
        cfg: PerceptionConfig,
        localization: PoseSource,
        faces: FaceGallery | None = None,
    ) -> None:
        self.feed = feed
        self.detector = detector
        self.cfg = cfg
        self.localization = localization
        self.faces = faces
        self.tracker = PeopleTracker(cfg.tracking)
        self.stats = CameraStats()
        self._last_stamp: float | None = None
        self._last_seen: list[SeenPerson] = []

    def look(self) -> list[SeenPerson]:
        frame = self.feed.latest(self.cfg.camera.max_age_s)
        if frame is None:
            self.stats.no_frame += 1
            return []
        if frame.stamp == self._last_stamp:
            return self._last_seen
        pose = self.localization()
        if pose is None:
            self.stats.no_pose += 1
            return []
        started = wall_seconds()
        found = self.measure(frame, pose)
        tracks = self.tracker.update(frame.stamp, found)
        self._last_stamp = frame.stamp
        self._last_seen = [
            SeenPerson(t.name, t.position, t.score, t.id, t.face_backlit)
            for t in tracks
            if t.confirmed
        ]
        self.stats.last_ms = 1000.0 * (wall_seconds() - started)
        self.stats.total_ms += self.stats.last_ms
        self.stats.frames += 1
        self.stats.last_age_s = self.feed.now() - frame.stamp
        return self._last_seen

    def geometry(self, frame: RgbdFrame) -> CameraGeometry:
        c = self.cfg.camera
        return CameraGeometry.from_info(frame.info, c.mount_height, c.mount_forward)

    def measure(self, frame: RgbdFrame, pose: Pose2D) -> list[Measurement]:
        """This frame's people in the map frame, the robot's base at ``pose``."""
        detections = [
            d
            for d in self.detector.detect(Frame(rgb=frame.rgb))
            if d.label == "person" and d.score >= self.cfg.camera.min_score
        ]
        if not detections:
            return []
        points = self.place_at(frame, [d.bbox for d in detections], pose)
        return [
            Measurement(Point(*map(float, p)), d.score, self.identify(frame, d))
            for d, p in zip(detections, points, strict=True)
            if np.isfinite(p).all()
        ]

    def place_at(self, frame: RgbdFrame, boxes: list[BoundingBox2D], pose: Pose2D) -> FloatArray:
        """Map-frame torso centres of ``boxes`` (NaN rows without depth), base at ``pose``."""
        views = Views.single(
            pose.x, pose.y, pose.theta, frame.head_yaw, frame.head_pitch, len(boxes)
        )
        return locate_people(self.geometry(frame), frame.depth, boxes, views)

    def place(self, frame: RgbdFrame, boxes: list[BoundingBox2D]) -> FloatArray | None:
        """:meth:`place_at` the robot's current pose; None while it is not localised."""
        pose = self.localization()
        return None if pose is None else self.place_at(frame, boxes, pose)

    def locate(self, person: str) -> Point | None:
        """Where the confirmed track named ``person`` (or with that id) is, None if none."""
        for track in self.tracker.tracks:
            if track.confirmed and person in (track.name, track.id):
                return track.position
        return None

    def people(self) -> list[str]:
        """Everyone tracked now: the name when recognised, else the track id."""
        return [t.name or t.id for t in self.tracker.tracks if t.confirmed]

    def identify(self, frame: RgbdFrame, detection: Detection2D) -> str | None:
        """The enrolled name of the nearest face in the box's upper part, None if unknown."""
        if self.faces is None:
            return None
        crop = head_crop(frame.rgb, detection.bbox)
        if crop.size == 0:
            return None
        identities = self.faces.identify(crop)
        best = min(identities, key=lambda i: i.distance, default=None)
        return best.name if best is not None else None


def head_crop(rgb: np.ndarray, box: BoundingBox2D) -> np.ndarray:
    """The upper :data:`FACE_SHARE` of ``box`` (inside the image)."""
    h, w = rgb.shape[:2]
    u0 = max(int(box.cx - box.width / 2), 0)
    u1 = min(int(np.ceil(box.cx + box.width / 2)), w)
    v0 = max(int(box.cy - box.height / 2), 0)
    v1 = min(int(np.ceil(box.cy - box.height / 2 + FACE_SHARE * box.height)), h)
    return np.ascontiguousarray(rgb[v0:v1, u0:u1])
