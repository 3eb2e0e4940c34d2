"""``build_camera_modules``: the camera backends built from a SystemConfig and run on the
bus's camera topics, with generated ONNX detector and pose models; and its config errors."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from amiro.activity.camera_skeletons import CameraSkeletonSource
from amiro.activity.dataset import subject_body, window
from amiro.activity.render import SOURCES, depth_image, project
from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.config import ConfigError
from amiro.core.messages import CameraInfo, Header, Image, Pose2D
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.perception.onnx_standins import fixed_answer_model
from amiro.robot.camera import Camera
from amiro.system import SystemConfig
from amiro.system.camera import build_camera_modules

INFO = Camera().info(0.0)
COCO_SOURCE = SOURCES["coco17"]  # the NTU joint under each COCO-17 keypoint


class StillCamera(Node):
    """One RGB-D frame, published again and again as a camera would."""

    def __init__(self, depth: np.ndarray) -> None:
        super().__init__("still_camera")
        self.depth = depth.astype(np.float32)

    def on_start(self) -> None:
        self.pubs = [self.create_publisher(t, Image) for t in (names.IMAGE, names.DEPTH)]
        self.info = self.create_publisher(names.CAMERA_INFO, CameraInfo)
        self.create_timer(1.0 / 15.0, self.play)

    def play(self) -> None:
        h = Header(self.now(), "camera")
        rgb = np.zeros((INFO.height, INFO.width, 3), dtype=np.uint8)
        self.pubs[0].publish(Image(h, INFO.height, INFO.width, "rgb8", rgb))
        d = self.depth
        self.pubs[1].publish(Image(h, d.shape[0], d.shape[1], "32FC1", d))
        self.info.publish(INFO)


def models(tmp_path: Path) -> tuple[Path, Path, np.ndarray]:
    """A detector and a pose model that both see one person (a drinking skeleton), and the
    depth image of that person."""
    joints = window("drink_water", subject_body(1, 0), 0.0, np.random.default_rng(1), 1)[0]
    uv = project(joints, INFO)[COCO_SOURCE]
    lo, hi = uv.min(axis=0), uv.max(axis=0)
    box = np.concatenate([(lo + hi) / 2 * 0.5 + [0, 40], (hi - lo) * 0.5])  # letterboxed
    detector_row = np.zeros(85)
    detector_row[:6] = *box, 1.0, 0.9
    keypoints = np.concatenate([uv * 0.5 + [0, 40], np.ones((17, 1))], axis=1)
    pose_row = np.concatenate([box, [0.9], keypoints.ravel()])
    return (
        fixed_answer_model(tmp_path / "det.onnx", detector_row[None]),
        fixed_answer_model(tmp_path / "pose.onnx", pose_row[None], channels_first=True),
        depth_image(joints, INFO),
    )


def config(detector: Path | None, pose: Path | None, **activity: object) -> SystemConfig:
    return SystemConfig.model_validate(
        {
            "robot": {"adapter": "ros2"},
            "perception": {"backend": "camera", "camera": {"detector": "onnx", "model": detector}},
            "activity": {"backend": "camera-onnx", "pose": {"model": pose}, **activity},
        }
    )


def test_people_and_their_activity_from_the_camera_topics(tmp_path: Path) -> None:
    detector, pose, depth = models(tmp_path)
    rt = Runtime(SimClock(), seed=1)
    modules = build_camera_modules(rt, config(detector, pose), lambda: Pose2D(1.0, 2.0, 0.5))
    rt.add(StillCamera(depth))
    rt.start()
    rt.spin_for(0.2)
    modules.people.look()
    rt.spin_for(0.2)
    (person,) = modules.people.look()
    assert person.track_id == "person_1" and person.name is None
    rt.spin_for(2.5)
    reading = modules.activity.observe("person_1")
    assert reading.skeleton_complete and reading.confidence > 0
    source = rt.node("camera_skeletons")
    assert isinstance(source, CameraSkeletonSource) and source.stats.frames >= 30


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"activity": {"backend": "onnx"}}, "activity.backend: onnx reads the simulator"),
        ({"activity": {"backend": "camera-onnx"}}, "activity.pose.model: camera-onnx needs"),
        ({"perception": {"backend": "sim"}}, "perception.backend: sim reads the simulator"),
    ],
)
def test_configs_that_cannot_run_on_a_camera_are_refused(
    tmp_path: Path, change: dict[str, object], message: str
) -> None:
    detector, pose, _ = models(tmp_path)
    cfg = config(detector, pose).model_dump()
    for section, values in change.items():
        cfg[section] = values
    with pytest.raises(ConfigError, match=message):
        build_camera_modules(Runtime(SimClock()), SystemConfig.model_validate(cfg), Pose2D)
