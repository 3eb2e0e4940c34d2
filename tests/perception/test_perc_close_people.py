"""People close to the camera fill the image and their box is cut by its border: the
estimated height must still be the body's centre, not the camera's height."""

from __future__ import annotations

import math

import numpy as np
import pytest

from amiro.core.runtime import Runtime
from amiro.perception.config import PerceptionConfig
from amiro.perception.estimation import CameraGeometry, body_centre_row
from amiro.perception.stack import SimPeopleFinder
from amiro.robot.camera import Camera
from amiro.sim.config import SimConfig
from amiro.sim.simulator import Simulation, build_sim


def sim_with(posture: str, x: float) -> Simulation:
    cfg = SimConfig.model_validate(
        {
            "start": {"x": 4.0, "y": 2.0, "theta": 0.0},
            "residents": [
                {"name": "maria", "posture": posture, "pose": {"x": x, "y": 2.1, "theta": math.pi}}
            ],
        }
    )
    return build_sim(Runtime(seed=3), cfg)


@pytest.mark.parametrize(
    "posture,x,torso_z",
    [("standing", 5.0, 0.85), ("standing", 5.4, 0.85), ("sitting_desk", 5.6, 0.625)],
)
def test_close_people_get_their_body_centre_height(posture: str, x: float, torso_z: float) -> None:
    sim = sim_with(posture, x)
    (obs,) = sim.observe()
    box = obs.bbox
    assert box.cy + box.height / 2 >= 479  # the image border cut the body's lower end
    finder = SimPeopleFinder(sim, np.random.default_rng(0), PerceptionConfig())
    seen = [p.position for _ in range(6) for p in finder.look()]
    assert seen
    for p in seen:
        assert p.z == pytest.approx(torso_z, abs=0.12)
        assert math.hypot(p.x - x, p.y - 2.1) < 0.15


def test_an_uncut_box_keeps_its_centre_row() -> None:
    cam = Camera()
    geom = CameraGeometry.from_info(cam.info(0.0), cam.params.height, cam.params.forward)
    top, bottom = np.array([100.0, 0.0]), np.array([300.0, 480.0])
    row = body_centre_row(geom, top, bottom, np.array([3.0, 1.0]), np.array([0.1, 0.0]))
    assert row[0] == pytest.approx(200.0)
    # cut at both ends, 1 m away, level head: the centre of 0..1.70 m is below the camera
    assert row[1] > 240.0 + geom.fy * (1.15 - 0.85) / 1.0 - 1.0
