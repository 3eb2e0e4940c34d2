"""The simulator backends: the detector's error profile, faces, and the whole finder."""

from __future__ import annotations

import math

import numpy as np
import pytest

from amiro.core.config import ConfigError
from amiro.core.messages import BoundingBox2D, Point
from amiro.core.runtime import Runtime
from amiro.perception.config import FaceSection, PerceptionConfig
from amiro.perception.ports import Frame
from amiro.perception.sim_detector import SimDetector
from amiro.perception.sim_faces import SimFaceIdentifier
from amiro.perception.stack import SimPeopleFinder, build_people_finder
from amiro.robot.camera import CameraObservation
from amiro.sim.config import SimConfig
from amiro.sim.perception_oracle import OraclePeopleFinder
from amiro.sim.simulator import build_sim


def obs(posture: str, depth: float, face: bool = True, backlit: bool = False) -> CameraObservation:
    return CameraObservation(
        "maria",
        BoundingBox2D(320, 240, 100, 300),
        depth,
        face,
        backlit,
        Point(),
        posture,
        "idle",
        False,
    )


def counting_error(posture: str, depth: float, n: int = 2000) -> float:
    det = SimDetector(np.random.default_rng(0))
    frame = Frame(observations=[obs(posture, depth)])
    return float(np.mean([abs(len(det.detect(frame)) - 1) for _ in range(n)]))


def test_detector_errors_follow_the_paper() -> None:
    assert counting_error("standing", 3.0) < 0.02
    lying = counting_error("lying_couch", 3.5)
    assert 0.6 < lying < 0.95  # paper: 0.82
    assert counting_error("lying_couch", 2.0) < counting_error("lying_couch", 5.0)


def test_faces_fail_when_backlit_and_never_guess_strangers() -> None:
    faces = SimFaceIdentifier(np.random.default_rng(0), ["maria", "ion"])
    lit = [faces.identify(obs("standing", 2.0)) for _ in range(500)]
    dark = [faces.identify(obs("standing", 2.0, backlit=True)) for _ in range(500)]
    assert lit.count("maria") > 400 and dark.count("maria") < 50
    assert faces.identify(obs("standing", 2.0, face=False)) is None
    stranger = SimFaceIdentifier(np.random.default_rng(0), ["ion"], FaceSection(confusion_rate=0))
    assert {stranger.identify(obs("standing", 2.0)) for _ in range(100)} == {None}


def sim_with_maria() -> tuple[Runtime, object]:
    cfg = SimConfig.model_validate(
        {
            "start": {"x": 4.0, "y": 2.0, "theta": 0.0},
            "residents": [{"name": "maria", "pose": {"x": 7.0, "y": 2.2, "theta": math.pi}}],
        }
    )
    runtime = Runtime(seed=4)
    return runtime, build_sim(runtime, cfg)


def test_finder_names_and_locates_the_person() -> None:
    _runtime, sim = sim_with_maria()
    finder = build_people_finder(sim, np.random.default_rng(1), PerceptionConfig())  # type: ignore[arg-type]
    assert isinstance(finder, SimPeopleFinder)
    seen = [p for _ in range(10) for p in finder.look()]
    named = [p for p in seen if p.name == "maria"]
    assert named and {p.track_id for p in named} == {named[0].track_id}
    last = named[-1].position
    assert math.hypot(last.x - 7.0, last.y - 2.2) < 0.2
    assert last.z == pytest.approx(0.85, abs=0.15)


def test_oracle_stays_a_named_backend() -> None:
    _runtime, sim = sim_with_maria()
    cfg = PerceptionConfig(backend="oracle")
    assert isinstance(build_people_finder(sim, np.random.default_rng(1), cfg), OraclePeopleFinder)  # type: ignore[arg-type]


def test_dlib_faces_need_images_the_simulator_does_not_render() -> None:
    _runtime, sim = sim_with_maria()
    cfg = PerceptionConfig.model_validate({"faces": {"backend": "dlib"}})
    with pytest.raises(ConfigError, match=r"perception\.faces\.backend: dlib needs camera images"):
        build_people_finder(sim, np.random.default_rng(1), cfg)  # type: ignore[arg-type]
