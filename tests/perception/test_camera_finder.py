"""The camera people finder on generated RGB-D frames sent over the bus's camera topics.

A person is an upright cylinder rendered by ray casting from the head camera, so the depth
image and the person's box (what an ideal detector reports, answered here by a generated
ONNX model) are exact; the finder must put the person back at their map position, for
several robot poses and head angles, through the head joint states or a fixed camera.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.config import ConfigError
from amiro.core.messages import (
    BoundingBox2D,
    CameraInfo,
    Detection2D,
    Header,
    Image,
    JointState,
    Pose2D,
)
from amiro.core.runtime import Runtime
from amiro.perception.camera_finder import CameraPeopleFinder, head_crop
from amiro.perception.config import CameraSection, PerceptionConfig
from amiro.perception.hog import HogPeopleDetector
from amiro.perception.onnx_standins import fixed_answer_model
from amiro.perception.onnx_yolo import YoloOnnxDetector
from amiro.perception.ports import Frame
from amiro.perception.synthetic_scene import Cylinder, Scene, render
from amiro.robot.camera import Camera
from amiro.robot.camera_feed import CameraFeed, RgbdFrame, depth_metres, rgb_pixels

CAMERA = Camera()


def publish(
    rt: Runtime, scene: Scene, yaw: float | None, pitch: float | None, depth_scale: int = 1
) -> None:
    """One camera frame (and the head joints, when given) on the robot port's topics."""
    stamp = rt.clock.now()
    header = Header(stamp, "camera")
    h, w = scene.depth.shape
    depth = scene.depth[::depth_scale, ::depth_scale].astype(np.float32)
    rt.bus.publisher(names.IMAGE, Image).publish(Image(header, h, w, "rgb8", scene.rgb))
    rt.bus.publisher(names.DEPTH, Image).publish(
        Image(header, depth.shape[0], depth.shape[1], "32FC1", depth)
    )
    rt.bus.publisher(names.CAMERA_INFO, CameraInfo).publish(CAMERA.info(stamp))
    if yaw is not None and pitch is not None:
        rt.bus.publisher(names.JOINT_STATES, JointState).publish(
            JointState(header, (names.HEAD_YAW, names.HEAD_PITCH), (yaw, pitch))
        )
    rt.spin_for(0.05)


def box_detector(tmp_path: Path, box: BoundingBox2D, score: float = 0.9) -> YoloOnnxDetector:
    """A generated ONNX model that finds a person at ``box`` of a 640 x 480 image."""
    r, dy = 0.5, 40.0  # a 320 model letterboxes 640 x 480 at half scale, 40 px bands
    row = np.zeros(85, dtype=np.float32)
    row[:5] = box.cx * r, box.cy * r + dy, box.width * r, box.height * r, 1.0
    row[5] = score
    return YoloOnnxDetector(fixed_answer_model(tmp_path / "det.onnx", row[None]))


def finder_for(
    tmp_path: Path, scene: Scene, pose: Pose2D, cfg: PerceptionConfig
) -> tuple[Runtime, CameraPeopleFinder]:
    rt = Runtime(SimClock(), seed=1)
    c = cfg.camera
    feed = rt.add(CameraFeed(c.yaw, c.pitch, c.head_joints, c.max_skew_s))
    rt.start()
    box = scene.boxes[0]
    assert box is not None
    return rt, CameraPeopleFinder(feed, box_detector(tmp_path, box), cfg, lambda: pose)


def frame(finder: CameraPeopleFinder) -> RgbdFrame:
    latest = finder.feed.latest()
    assert latest is not None
    return latest


# (robot pose, head yaw, head pitch, person's offset from the robot: metres ahead, left)
CASES = [
    (Pose2D(0.0, 0.0, 0.0), 0.0, 0.0, (2.0, 0.0)),
    (Pose2D(1.0, -2.0, 1.2), 0.0, 0.2, (3.0, 0.5)),
    (Pose2D(-3.0, 4.0, -2.5), 0.5, 0.1, (2.5, 1.6)),
    (Pose2D(2.0, 2.0, math.pi), -0.6, 0.3, (1.6, -1.0)),
    (Pose2D(0.5, 0.5, 0.3), 0.3, -0.1, (4.5, 1.0)),
]


@pytest.mark.parametrize(("pose", "yaw", "pitch", "offset"), CASES)
def test_a_person_is_placed_at_their_map_position(
    tmp_path: Path, pose: Pose2D, yaw: float, pitch: float, offset: tuple[float, float]
) -> None:
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    truth = (pose.x + c * offset[0] - s * offset[1], pose.y + s * offset[0] + c * offset[1])
    scene = render(CAMERA, pose, [Cylinder(*truth)], yaw, pitch)
    rt, finder = finder_for(tmp_path, scene, pose, PerceptionConfig(backend="camera"))
    publish(rt, scene, yaw, pitch, depth_scale=2)  # a depth camera at half the resolution
    (m,) = finder.measure(frame(finder), pose)
    assert math.hypot(m.position.x - truth[0], m.position.y - truth[1]) < 0.12
    assert m.position.z == pytest.approx(0.85, abs=0.15)  # the torso's centre
    # Two frames confirm the track; look() then reports it.
    assert finder.look() == []  # one hit is not yet a person
    publish(rt, scene, yaw, pitch)
    (seen,) = finder.look()
    assert seen.name is None and seen.track_id == "person_1"
    assert math.hypot(seen.position.x - truth[0], seen.position.y - truth[1]) < 0.12
    assert finder.stats.frames == 2 and finder.stats.ms_per_frame > 0


def test_a_fixed_camera_uses_the_configured_extrinsic(tmp_path: Path) -> None:
    pose, pitch = Pose2D(1.0, 1.0, 0.5), 0.25
    truth = (1.0 + 2.5 * math.cos(0.5), 1.0 + 2.5 * math.sin(0.5))
    scene = render(CAMERA, pose, [Cylinder(*truth)], 0.0, pitch)
    fixed = CameraSection(pitch=pitch, head_joints=False)
    rt, finder = finder_for(tmp_path, scene, pose, PerceptionConfig(backend="camera", camera=fixed))
    publish(rt, scene, yaw=None, pitch=None)
    (m,) = finder.measure(frame(finder), pose)
    assert math.hypot(m.position.x - truth[0], m.position.y - truth[1]) < 0.12
    # Ignoring the pitch would put the person visibly off: the extrinsic is what is used.
    level = CameraSection(head_joints=False)
    rt2, wrong = finder_for(tmp_path, scene, pose, PerceptionConfig(backend="camera", camera=level))
    publish(rt2, scene, yaw=None, pitch=None)
    (off,) = wrong.measure(frame(wrong), pose)
    assert abs(off.position.z - m.position.z) > 0.3


def test_no_frame_no_pose_and_stale_frames_give_nobody(tmp_path: Path) -> None:
    pose = Pose2D()
    scene = render(CAMERA, pose, [Cylinder(2.0, 0.0)])
    rt, finder = finder_for(tmp_path, scene, pose, PerceptionConfig(backend="camera"))
    assert finder.look() == [] and finder.stats.no_frame == 1
    publish(rt, scene, 0.0, 0.0)
    finder.localization = lambda: None
    assert finder.look() == [] and finder.stats.no_pose == 1
    rt.spin_for(2.0)  # older than camera.max_age_s (1 s)
    finder.localization = lambda: pose
    assert finder.look() == [] and finder.stats.no_frame == 2


def test_the_same_frame_is_processed_once(tmp_path: Path) -> None:
    pose = Pose2D()
    scene = render(CAMERA, pose, [Cylinder(2.0, 0.0)])
    rt, finder = finder_for(tmp_path, scene, pose, PerceptionConfig(backend="camera"))
    for _ in range(2):
        publish(rt, scene, 0.0, 0.0)
    first = finder.look()
    assert finder.look() == first and finder.stats.frames == 1
    assert len(first) == 0  # one frame: not confirmed, however often looked at


def test_low_scores_and_other_labels_are_not_people(tmp_path: Path) -> None:
    pose = Pose2D()
    scene = render(CAMERA, pose, [Cylinder(2.0, 0.0)])
    rt, finder = finder_for(tmp_path, scene, pose, PerceptionConfig(backend="camera"))
    assert scene.boxes[0] is not None
    finder.detector = box_detector(tmp_path, scene.boxes[0], score=0.4)  # under min_score 0.5
    publish(rt, scene, 0.0, 0.0)
    assert finder.measure(frame(finder), pose) == []

    class Cup:
        def detect(self, frame: Frame) -> list[Detection2D]:
            return [Detection2D("cup", 0.9, BoundingBox2D(320, 240, 50, 50))]

    finder.detector = Cup()
    assert finder.measure(frame(finder), pose) == []


def test_images_are_converted_and_bad_encodings_dropped() -> None:
    bgr = np.zeros((2, 3, 3), dtype=np.uint8)
    bgr[..., 0] = 255  # blue in BGR
    assert rgb_pixels(Image(Header(), 2, 3, "bgr8", bgr))[0, 0].tolist() == [0, 0, 255]
    mm = np.array([[0, 1500], [2000, 65535]], dtype=np.uint16)
    assert depth_metres(Image(Header(), 2, 2, "16UC1", mm)).tolist() == [[0, 1.5], [2, 65.535]]
    nan = np.array([[np.nan, -1.0], [np.inf, 2.0]], dtype=np.float32)
    assert depth_metres(Image(Header(), 2, 2, "32FC1", nan)).tolist() == [[0, 0], [0, 2.0]]
    with pytest.raises(ValueError, match="mono8"):
        rgb_pixels(Image(Header(), 2, 3, "mono8", np.zeros((2, 3), np.uint8)))

    rt = Runtime(SimClock(), seed=1)
    feed = rt.add(CameraFeed())
    rt.start()
    header = Header(0.0, "camera")
    rt.bus.publisher(names.IMAGE, Image).publish(Image(header, 2, 3, "yuv422", bgr))
    rt.bus.publisher(names.DEPTH, Image).publish(Image(header, 2, 2, "16UC1", mm))
    rt.bus.publisher(names.CAMERA_INFO, CameraInfo).publish(CAMERA.info(0.0))
    rt.spin_for(0.05)
    assert feed.latest() is None and feed.bad_frames == 1


def test_depth_far_from_the_image_in_time_is_not_paired() -> None:
    rt = Runtime(SimClock(), seed=1)
    feed = rt.add(CameraFeed(max_skew_s=0.1))
    rt.start()
    rgb, depth = np.zeros((4, 4, 3), np.uint8), np.ones((4, 4), np.float32)
    rt.bus.publisher(names.DEPTH, Image).publish(Image(Header(0.0), 4, 4, "32FC1", depth))
    rt.bus.publisher(names.CAMERA_INFO, CameraInfo).publish(CAMERA.info(0.0))
    rt.bus.publisher(names.IMAGE, Image).publish(Image(Header(0.5), 4, 4, "rgb8", rgb))
    rt.spin_for(0.05)
    assert feed.latest() is None
    rt.bus.publisher(names.DEPTH, Image).publish(Image(Header(0.45), 4, 4, "32FC1", depth))
    rt.spin_for(0.05)
    frame = feed.latest()
    assert frame is not None and frame.stamp == 0.5


def test_head_crop_is_the_upper_half_inside_the_image() -> None:
    rgb = np.arange(480 * 640 * 3, dtype=np.uint32).reshape(480, 640, 3).astype(np.uint8)
    crop = head_crop(rgb, BoundingBox2D(620.0, 200.0, 100.0, 200.0))
    assert crop.shape == (100, 70, 3)  # rows 100-200, columns 570-640


def test_the_onnx_detector_needs_a_model() -> None:
    with pytest.raises(ValueError, match="needs model"):
        CameraSection(detector="onnx")
    with pytest.raises(ConfigError, match="no such model"):
        YoloOnnxDetector(Path("/nonexistent.onnx"))


@pytest.mark.parametrize(
    ("pose", "yaw", "pitch", "offset"),
    [
        (Pose2D(1.0, 2.0, 0.7), 0.2, 0.05, (4.5, 0.5)),
        (Pose2D(-2.0, 1.0, -2.0), -0.3, 0.1, (3.2, -0.4)),
        (Pose2D(0.0, 0.0, 3.0), 0.0, -0.05, (4.0, 0.8)),
    ],
)
def test_the_hog_path_places_a_drawn_person(
    pose: Pose2D, yaw: float, pitch: float, offset: tuple[float, float]
) -> None:
    """OpenCV's HOG on a human silhouette drawn where the person stands: its boxes are
    wider and taller than the body, the torso depth and the 3D estimate still hold."""
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    truth = (pose.x + c * offset[0] - s * offset[1], pose.y + s * offset[0] + c * offset[1])
    scene = render(CAMERA, pose, [Cylinder(*truth)], yaw, pitch, drawn=True)
    rt = Runtime(SimClock(), seed=1)
    feed = rt.add(CameraFeed())
    rt.start()
    cfg = PerceptionConfig(backend="camera")
    finder = CameraPeopleFinder(feed, HogPeopleDetector(), cfg, lambda: pose)
    publish(rt, scene, yaw, pitch)
    (m,) = finder.measure(frame(finder), pose)
    assert math.hypot(m.position.x - truth[0], m.position.y - truth[1]) < 0.1
    assert m.position.z == pytest.approx(0.85, abs=0.15)
