"""Assembles the people finder the behaviour tasks use, from the ``perception:`` config.

The ``sim`` backend is the module's real pipeline run on the simulator: detector boxes, the
depth of each box, face identity, the 3D estimator with the head joints and the robot's
pose, and the tracker.  The ``oracle`` backend is kept for tests and as a baseline.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

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
from amiro.perception.oracle import OraclePeopleFinder
from amiro.perception.ports import Frame, PeopleFinder, SeenPerson
from amiro.perception.sim_detector import SimDetector, best_match
from amiro.perception.sim_faces import SimFaceIdentifier
from amiro.perception.tracking import Measurement, PeopleTracker
from amiro.sim.messages import CameraObservation
from amiro.sim.simulator import Simulation

# Depth the simulator's camera reports for a box no resident explains (a false positive):
# whatever lies behind it, drawn in this range (m).
BACKGROUND_DEPTH = (1.0, 6.0)

PoseSource = Callable[[], Pose2D | None]


class SimPeopleFinder:
    """Detector → depth → face → 3D estimate → tracks, on the simulated head camera."""

    def __init__(
        self,
        sim: Simulation,
        rng: np.random.Generator,
        cfg: PerceptionConfig,
        localization: PoseSource | None = None,
    ) -> None:
        self.sim = sim
        self.cfg = cfg
        self.localization = localization
        self.geometry = camera_geometry(sim)
        rng_detect, rng_face, self.rng = rng.spawn(3)
        self.detector = SimDetector(
            rng_detect, cfg.detector, (self.geometry.width, self.geometry.height)
        )
        self.faces = SimFaceIdentifier(rng_face, (r.name for r in sim.config.residents), cfg.faces)
        self.tracker = PeopleTracker(cfg.tracking)

    def look(self) -> list[SeenPerson]:
        observations = self.sim.observe()
        detections = [
            d for d in self.detector.detect(Frame(observations=observations)) if d.label == "person"
        ]
        found = self._measure(detections, observations)
        tracks = self.tracker.update(self.sim.robot.now(), found)
        return [
            SeenPerson(t.name, t.position, t.score, t.id, t.face_backlit)
            for t in tracks
            if t.confirmed
        ]

    def _measure(
        self, detections: list[Detection2D], observations: list[CameraObservation]
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
        points = self.estimate([d.bbox for d in detections], depth)
        return [
            Measurement(
                Point(*map(float, p)),
                d.score,
                names.get(id(o)) if o is not None else None,
                bool(o is not None and o.face_visible and o.backlit),
            )
            for d, o, p in zip(detections, matched, points, strict=True)
        ]

    def estimate(self, boxes: list[BoundingBox2D], depth: FloatArray) -> FloatArray:
        """Map-frame points of the people in ``boxes`` at their depth readings."""
        estimate = self.localization() if self.localization is not None else None
        views = robot_views(self.sim, len(boxes), estimate)
        u = np.array([b.cx for b in boxes])
        v = np.array([b.cy for b in boxes])
        if self.cfg.estimator == "paper":
            return paper_formula(self.geometry, u, v, depth, views)
        half = np.array([b.height / 2 for b in boxes])
        row = body_centre_row(self.geometry, v - half, v + half, depth, views.head_pitch)
        return improved(self.geometry, u, row, depth, views)


def robot_views(sim: Simulation, n: int, pose: Pose2D | None = None) -> Views:
    """The robot's pose (the localisation estimate when given, else the simulator's truth)
    and head joints now, for ``n`` detections."""
    robot = sim.robot
    pose = pose if pose is not None else robot.true_pose
    return Views.single(pose.x, pose.y, pose.theta, robot.head_yaw, robot.head_pitch, n)


def camera_geometry(sim: Simulation) -> CameraGeometry:
    camera = sim.residents.camera
    return CameraGeometry.from_info(camera.info(0.0), camera.params.height, camera.params.forward)


def build_people_finder(
    sim: Simulation,
    rng: np.random.Generator,
    cfg: PerceptionConfig,
    localization: PoseSource | None = None,
) -> PeopleFinder:
    """The people finder ``cfg.backend`` names; positions go into the map frame through
    ``localization`` (the robot's pose estimate), or the simulator's true pose without it."""
    if cfg.backend == "oracle":
        return OraclePeopleFinder(sim, rng, cfg.position_noise_m)
    if cfg.faces.backend == "dlib":
        raise ConfigError(
            "perception.faces.backend: dlib needs camera images and the simulated camera "
            "renders none; use sim here (FaceGallery + DlibFaceEmbedder work on real images)"
        )
    return SimPeopleFinder(sim, rng, cfg, localization)
