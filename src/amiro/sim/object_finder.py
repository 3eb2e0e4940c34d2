"""Household objects in the simulated home: detector boxes → depth → map positions.

The same detector as people (:class:`SimDetector`) sees cups, bottles, chairs, couches,
beds and tables; each box is placed in the map with the improved estimator.
"""

from __future__ import annotations

import numpy as np

from amiro.core.messages import Point
from amiro.perception.config import PerceptionConfig
from amiro.perception.estimation import CameraGeometry, Views, improved
from amiro.perception.ports import Frame, SeenObject
from amiro.perception.sim_detector import SimDetector, best_match
from amiro.perception.sim_objects import household_objects, observe_objects
from amiro.sim.simulator import Simulation


class SimObjectFinder:
    """What household objects the simulated head camera finds now, and where."""

    def __init__(self, sim: Simulation, rng: np.random.Generator, cfg: PerceptionConfig) -> None:
        self.sim = sim
        self.objects = household_objects(sim.world, cfg.objects_file)
        self.geometry = camera_geometry(sim)
        rng_detect, self.rng = rng.spawn(2)
        self.detector = SimDetector(
            rng_detect, cfg.detector, (self.geometry.width, self.geometry.height)
        )

    def look(self) -> list[SeenObject]:
        robot = self.sim.robot
        seen = observe_objects(
            self.sim.residents.camera,
            self.sim.world,
            robot.true_pose,
            robot.head_yaw,
            robot.head_pitch,
            self.objects,
            self.rng,
        )
        found = [
            (d, o)
            for d in self.detector.detect(Frame(objects=seen))
            if (o := best_match(d.bbox, [s for s in seen if s.label == d.label])) is not None
        ]
        if not found:
            return []
        points = improved(
            self.geometry,
            np.array([d.bbox.cx for d, _ in found]),
            np.array([d.bbox.cy for d, _ in found]),
            np.array([o.depth for _, o in found]),
            robot_views(self.sim, len(found)),
        )
        return [
            SeenObject(d.label, Point(*map(float, p)), d.score)
            for (d, _), p in zip(found, points, strict=True)
        ]


def robot_views(sim: Simulation, n: int) -> Views:
    """The simulator's true pose and head joints now, for ``n`` detections."""
    pose = sim.robot_pose()
    return Views.single(pose.x, pose.y, pose.theta, *sim.head_joints(), n)


def camera_geometry(sim: Simulation) -> CameraGeometry:
    return CameraGeometry.from_info(sim.camera_info(), *sim.camera_mount())
