"""Assembles the people finder the behaviour tasks use, from the ``perception:`` config.

The ``sim`` backend is the module's real pipeline run on the simulated head camera: detector
boxes, the depth of each box, face identity, the 3D estimator with the head joints and the
robot's pose, and the tracker.  It reads the camera through :class:`HeadCamera`, so it runs
the same in one process and on a deployment's edge.  The ``oracle`` backend is kept for
tests and as a baseline, chosen only by name.  Backends are looked up by name in the
registry (:mod:`amiro.perception.backends`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from amiro.core import registry
from amiro.core.bus import Bus
from amiro.core.config import ConfigError
from amiro.core.messages import BoundingBox2D, Detection2D, Point, Pose2D
from amiro.perception.config import PerceptionConfig
from amiro.perception.estimation import (
    CameraGeometry,
    FloatArray,
    Views,
    body_centre_row,
    improved,
    paper_formula,
)
from amiro.perception.ports import Frame, PeopleFinder, SeenPerson
from amiro.perception.sim_detector import SimDetector, best_match
from amiro.perception.sim_faces import SimFaceIdentifier
from amiro.perception.tracking import Measurement, PeopleTracker
from amiro.robot.camera import CameraObservation, HeadCamera

if TYPE_CHECKING:
    from amiro.robot.camera_feed import CameraFeed

# Depth the simulator's camera reports for a box no resident explains (a false positive):
# whatever lies behind it, drawn in this range (m).
BACKGROUND_DEPTH = (1.0, 6.0)

PoseSource = Callable[[], Pose2D | None]


@dataclass(frozen=True)
class _Optics:
    """The camera's geometry and the detector sized to its image, once the camera reported."""

    geometry: CameraGeometry
    detector: SimDetector


class SimPeopleFinder:
    """Detector → depth → face → 3D estimate → tracks, on the robot's head camera.

    ``camera`` is the in-process simulator or a feed of its bridged topics: the same code runs
    on the embedded system and on a deployment's edge.
    """

    def __init__(
        self,
        camera: HeadCamera,
        rng: np.random.Generator,
        cfg: PerceptionConfig,
        localization: PoseSource | None = None,
    ) -> None:
        self.camera = camera
        self.cfg = cfg
        self.localization = localization
        self._rng_detect, rng_face, self.rng = rng.spawn(3)
        self.faces = SimFaceIdentifier(rng_face, camera.household(), cfg.faces)
        self.tracker = PeopleTracker(cfg.tracking)
        self._optics: _Optics | None = None
        self.estimates = 0  # people placed in the map so far, for reports

    def look(self) -> list[SeenPerson]:
        optics = self._ready()
        pose, joints = self._pose(), self.camera.head_joints()
        if optics is None or pose is None or joints is None:
            return []  # nothing from the robot yet
        observations = self.camera.observe()
        detections = [
            d
            for d in optics.detector.detect(Frame(observations=observations))
            if d.label == "person"
        ]
        views = Views.single(pose.x, pose.y, pose.theta, *joints, len(detections))
        found = self._measure(detections, observations, optics.geometry, views)
        self.estimates += len(found)
        tracks = self.tracker.update(self.camera.now(), found)
        return [
            SeenPerson(t.name, t.position, t.score, t.id, t.face_backlit)
            for t in tracks
            if t.confirmed
        ]

    def _ready(self) -> _Optics | None:
        if self._optics is None:
            info = self.camera.camera_info()
            if info is None:
                return None
            geometry = CameraGeometry.from_info(info, *self.camera.camera_mount())
            size = (geometry.width, geometry.height)
            self._optics = _Optics(geometry, SimDetector(self._rng_detect, self.cfg.detector, size))
        return self._optics

    def _pose(self) -> Pose2D | None:
        """The localisation estimate, else whatever pose the camera's source knows."""
        estimate = self.localization() if self.localization is not None else None
        return estimate if estimate is not None else self.camera.robot_pose()

    def _measure(
        self,
        detections: list[Detection2D],
        observations: list[CameraObservation],
        geometry: CameraGeometry,
        views: Views,
    ) -> list[Measurement]:
        if not detections:
            return []
        matched = [best_match(d.bbox, observations) for d in detections]
        # The simulator's camera reports the z-depth of the torso centre (not its surface).
        depth = np.array(
            [
                o.depth if o is not None else float(self.rng.uniform(*BACKGROUND_DEPTH))
                for o in matched
            ]
        )
        names = {id(o): self.faces.identify(o) for o in matched if o is not None}
        points = self.estimate(geometry, [d.bbox for d in detections], depth, views)
        return [
            Measurement(
                Point(*map(float, p)),
                d.score,
                names.get(id(o)) if o is not None else None,
                bool(o is not None and o.face_visible and o.backlit),
            )
            for d, o, p in zip(detections, matched, points, strict=True)
        ]

    def estimate(
        self, geometry: CameraGeometry, boxes: list[BoundingBox2D], depth: FloatArray, views: Views
    ) -> FloatArray:
        """Map-frame points of the people in ``boxes`` at their depth readings."""
        u = np.array([b.cx for b in boxes])
        v = np.array([b.cy for b in boxes])
        if self.cfg.estimator == "paper":
            return paper_formula(geometry, u, v, depth, views)
        half = np.array([b.height / 2 for b in boxes])
        row = body_centre_row(geometry, v - half, v + half, depth, views.head_pitch)
        return improved(geometry, u, row, depth, views)


@dataclass(frozen=True)
class PerceptionInputs:
    """What a people finder is built on: the simulator's head camera (or a feed of its
    topics) in ``head``, or a real robot's RGB-D camera in ``feed``; the other is None.
    Positions go into the map frame through ``localization`` (the robot's pose estimate)."""

    cfg: PerceptionConfig
    rng: np.random.Generator
    localization: PoseSource | None = None
    head: HeadCamera | None = None
    feed: CameraFeed | None = None
    bus: Bus | None = None  # for finders that read people others publish (hri)

    def simulated_head(self) -> HeadCamera:
        """The simulator's head camera, or the one-line error a real robot's config gets."""
        if self.head is None:
            raise ConfigError(
                f"perception.backend: {self.cfg.backend} reads the simulator; a real robot "
                "needs camera"
            )
        return self.head


def sim_people_finder(inputs: PerceptionInputs) -> PeopleFinder:
    head, cfg = inputs.simulated_head(), inputs.cfg
    if cfg.faces.backend != "sim":  # the simulator's own face model, on its ground truth
        raise ConfigError(
            f"perception.faces.backend: {cfg.faces.backend} needs camera images and the "
            "simulated camera renders none; use sim here (FaceGallery + DlibFaceEmbedder work "
            "on real images)"
        )
    return SimPeopleFinder(head, inputs.rng, cfg, inputs.localization)


def build_people_finder(
    camera: HeadCamera,
    rng: np.random.Generator,
    cfg: PerceptionConfig,
    localization: PoseSource | None = None,
    bus: Bus | None = None,
) -> PeopleFinder:
    """The people finder ``cfg.backend`` names, on ``camera`` (the simulator or a feed of its
    topics); positions go into the map frame through ``localization`` (the robot's pose
    estimate), or the pose the camera's source knows without it."""
    inputs = PerceptionInputs(cfg, rng, localization, head=camera, bus=bus)
    finder: PeopleFinder = registry.create("perception", cfg.backend, inputs)
    return finder
