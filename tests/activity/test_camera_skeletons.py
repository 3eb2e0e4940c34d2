"""Skeletons from the camera: pose keypoints + depth image → levelled NTU-25 skeletons →
the shipped activity model.

A known skeleton stream (the synthetic motion the model was trained on) is played as
camera frames: a depth image with each joint at its depth, and COCO-17 keypoints where the
joints project (through a tiny generated ONNX pose model for one frame; through a stand-in
estimator that reads the frame's index from its first pixel for a whole stream).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

from amiro.activity.camera_skeletons import Body, CameraSkeletonSource
from amiro.activity.dataset import subject_body, window
from amiro.activity.lifting import level
from amiro.activity.onnx_model import ActivityModel
from amiro.activity.pose import PoseDetection, PoseEstimator, PoseOnnxEstimator
from amiro.activity.recognizer import SkeletonActivityRecognizer
from amiro.activity.render import SOURCES, depth_image, project
from amiro.activity.skeleton import JOINTS, NUM_JOINTS, FloatArray, J
from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import BoundingBox2D, CameraInfo, Header, Image, JointState, Point
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.perception.onnx_standins import fixed_answer_model
from amiro.robot.camera import Camera
from amiro.robot.camera_feed import CameraFeed

INFO = Camera().info(0.0)
MODEL = ActivityModel()
FPS = MODEL.info.fps
COCO_SOURCE = SOURCES["coco17"]  # the NTU joint under each COCO-17 keypoint
DIRECT = [J[n] for n in JOINTS if n.startswith(("Shoulder", "Elbow", "Wrist", "Hip", "Knee"))]


def coco_keypoints(joints: FloatArray) -> npt.NDArray[np.float64]:
    """COCO-17 (u, v, confidence) of one frame of camera-frame joints."""
    uv = project(joints, INFO)[COCO_SOURCE]
    return np.concatenate([uv, np.ones((17, 1))], axis=1)


def box_of(keypoints: npt.NDArray[np.float64]) -> BoundingBox2D:
    lo, hi = keypoints[:, :2].min(axis=0), keypoints[:, :2].max(axis=0)
    return BoundingBox2D(*((lo + hi) / 2), *(hi - lo))


class Player(Node):
    """Publishes camera frames of ``joints`` (camera frame, the head pitched down by
    ``pitch``) at the model's rate; the RGB image's first pixel holds the frame index."""

    def __init__(self, joints: FloatArray, pitch: float = 0.0) -> None:
        super().__init__("player")
        self.joints, self.pitch, self.index = joints, pitch, 0

    def on_start(self) -> None:
        self.rgb = self.create_publisher(names.IMAGE, Image)
        self.depth = self.create_publisher(names.DEPTH, Image)
        self.info = self.create_publisher(names.CAMERA_INFO, CameraInfo)
        self.head = self.create_publisher(names.JOINT_STATES, JointState)
        self.create_timer(1.0 / FPS, self.play)

    def play(self) -> None:
        i = self.index % len(self.joints)
        header = Header(self.now(), "camera")
        rgb = np.zeros((INFO.height, INFO.width, 3), dtype=np.uint8)
        rgb[0, 0, 0] = i
        depth = depth_image(self.joints[i], INFO).astype(np.float32)
        self.head.publish(JointState(header, (names.HEAD_PITCH,), (self.pitch,)))
        self.rgb.publish(Image(header, INFO.height, INFO.width, "rgb8", rgb))
        self.depth.publish(Image(header, depth.shape[0], depth.shape[1], "32FC1", depth))
        self.info.publish(INFO)
        self.index += 1


class IndexedPoses:
    """A pose estimator that knows every frame's keypoints (by the frame index pixel)."""

    keypoint_format = "coco17"

    def __init__(self, joints: FloatArray) -> None:
        self.joints = joints

    def estimate(self, rgb: npt.NDArray[np.uint8]) -> list[PoseDetection]:
        k = coco_keypoints(self.joints[int(rgb[0, 0, 0])])
        return [PoseDetection(box_of(k), 0.9, k)]


def stream(action: str, seed: int = 3) -> FloatArray:
    """Two seconds of ``action`` in the model's training view (a levelled camera frame)."""
    return window(action, subject_body(5, 0), 0.0, np.random.default_rng(seed), 30)


def setup(
    truth: FloatArray, pitch: float = 0.0, estimator: PoseEstimator | None = None
) -> tuple[Runtime, CameraSkeletonSource]:
    """The camera (head pitched down by ``pitch``) playing ``truth``, and the source; the
    estimator defaults to one that knows the keypoints of every frame."""
    rt = Runtime(SimClock(), seed=1)
    feed = rt.add(CameraFeed())
    seen = level(truth, -pitch)  # what the pitched camera sees
    rt.add(Player(seen, pitch))
    source = rt.add(CameraSkeletonSource(feed, estimator or IndexedPoses(seen), FPS))
    rt.start()
    return rt, source


@pytest.mark.parametrize("pitch", [0.0, 0.25])
def test_one_frame_through_an_onnx_pose_model_gives_the_levelled_skeleton(
    tmp_path: Path, pitch: float
) -> None:
    truth = stream("drink_water")[:1]
    seen_by_camera = level(truth, -pitch)
    k = coco_keypoints(seen_by_camera[0])
    letterboxed = np.concatenate([k[:, :2] * 0.5 + [0.0, 40.0], k[:, 2:]], axis=1)
    b = box_of(k)
    row = np.concatenate([[b.cx * 0.5, b.cy * 0.5 + 40, b.width * 0.5, b.height * 0.5, 0.9]])
    model = fixed_answer_model(
        tmp_path / "pose.onnx", np.concatenate([row, letterboxed.ravel()])[None]
    )
    rt, source = setup(truth, pitch, PoseOnnxEstimator(model))
    rt.spin_for(0.1)
    skeleton = source.window("anyone", 1)
    assert skeleton is not None
    rebuilt = skeleton[0]
    missing = [JOINTS[j] for j in range(NUM_JOINTS) if np.isnan(rebuilt[j]).any()]
    assert missing == ["FootLeft", "FootRight"]  # COCO has no feet
    error = np.linalg.norm(rebuilt[DIRECT] - truth[0][DIRECT], axis=1)
    # Exact where the joint's own depth shows; a hand in front of a hip hides the hip.
    assert np.median(error) < 0.01 and (error < 0.05).sum() >= len(DIRECT) - 2
    assert source.stats.frames >= 1 and source.stats.ms_per_frame > 0


@pytest.mark.parametrize(
    ("action", "pitch"), [("drink_water", 0.2), ("standing_up", 0.0), ("falling", 0.2)]
)
def test_the_activity_model_recognises_a_camera_stream(action: str, pitch: float) -> None:
    truth = stream(action)
    rt, source = setup(truth, pitch)
    recognizer = SkeletonActivityRecognizer(source, MODEL, window_frames=30)
    rt.spin_for(len(truth) / FPS)
    reading = recognizer.observe("anyone")
    assert reading.skeleton_complete
    assert reading.label == action
    assert reading.box_height_fraction is not None and reading.box_height_fraction > 0.2


def test_a_person_is_matched_to_the_body_where_they_are_tracked() -> None:
    truth = stream("drink_water")
    rt, source = setup(truth)
    rt.spin_for(0.2)
    (body,) = source.bodies
    assert source.body_of("ana") is body  # no finder: the only body in view
    source.bodies.append(Body(body.box, body.last_seen))
    assert source.body_of("ana") is None  # two bodies and nothing to tell them apart
    source.bodies.pop()
    body.position = Point(2.0, 1.0, 0.9)
    source.locate = lambda name: Point(2.1, 1.0, 0.9) if name == "ana" else None
    assert source.body_of("ana") is body
    source.locate = lambda name: Point(4.0, 1.0, 0.9)  # tracked elsewhere: not this body
    assert source.body_of("ana") is None and source.window("ana", 30) is None
    assert source.framing("ana") is None


def test_a_body_out_of_view_gets_unseen_frames_then_is_forgotten() -> None:
    truth = stream("drink_water")
    rt, source = setup(truth)
    rt.spin_for(0.5)
    source.estimator = type("Nobody", (), {"keypoint_format": "coco17",
                                           "estimate": lambda self, rgb: []})()  # fmt: skip
    rt.spin_for(0.5)
    frames = source.window("anyone", 30)
    assert frames is not None and np.isnan(frames[-5:]).all()
    rt.spin_for(2.0)
    assert source.bodies == [] and source.window("anyone", 30) is None
