"""``amiro perception bench-camera``: per-frame time of the camera backends on 640 x 480.

Each path is timed from the RGB-D frame to its output: people in the map frame (detector,
torso depth, 3D estimate) with OpenCV's HOG and with an ONNX detector, and skeletons (pose
model, NTU mapping, lifting) for activity.  Without a user's models the ONNX paths run
generated stand-ins with random weights and a small YOLO's compute (their GFLOPs are
reported), so inference is timed at a realistic cost; their detections mean nothing.
The placement error of people on generated frames, with ideal boxes and with HOG on drawn
silhouettes, is reported beside.
Wall time is read only here, to measure speed.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from amiro.activity.camera_skeletons import CameraSkeletonSource
from amiro.activity.keypoints import FORMATS
from amiro.activity.pose import PoseOnnxEstimator
from amiro.core.messages import BoundingBox2D, Detection2D, Pose2D
from amiro.evaluation.perception_bench import median_ms
from amiro.perception.camera_finder import CameraPeopleFinder
from amiro.perception.config import PerceptionConfig
from amiro.perception.estimation import FloatArray
from amiro.perception.hog import HogPeopleDetector
from amiro.perception.onnx_standins import standin_yolo
from amiro.perception.onnx_yolo import YoloOnnxDetector
from amiro.perception.ports import Detector, Frame
from amiro.perception.synthetic_scene import Cylinder, render
from amiro.robot.camera import Camera
from amiro.robot.camera_feed import CameraFeed, RgbdFrame

ROBOT = Pose2D(0.0, 0.0, 0.0)
PEOPLE = [Cylinder(3.2, -0.4), Cylinder(4.5, 0.8)]
COCO_OUTPUTS = 85  # YOLOv5 rows: box, objectness, 80 classes
# Stand-in widths giving about YOLOv5n's 4.5 and YOLOv8n-pose's 9.2 GFLOPs at 640 x 640.
DETECTOR_WIDTH, POSE_WIDTH = 1.07, 1.54


def bench_frame(camera: Camera) -> RgbdFrame:
    """A 640 x 480 RGB-D frame of two people (drawn silhouettes) in front of the robot."""
    scene = render(camera, ROBOT, PEOPLE, head_pitch=0.1, drawn=True)
    return RgbdFrame(0.0, scene.rgb, scene.depth, camera.info(0.0), 0.0, 0.1)


def people_ms(detector: Detector, frame: RgbdFrame, repeats: int) -> float:
    finder = CameraPeopleFinder(
        CameraFeed(), detector, PerceptionConfig(backend="camera"), lambda: ROBOT
    )
    return median_ms(lambda: finder.measure(frame, ROBOT), repeats)


def skeletons_ms(estimator: PoseOnnxEstimator, frame: RgbdFrame, repeats: int) -> float:
    source = CameraSkeletonSource(CameraFeed(), estimator, fps=15.0)

    def run() -> None:
        for person in estimator.estimate(frame.rgb)[:3]:
            source.skeleton(frame, person)

    return median_ms(run, repeats)


class IdealDetector:
    """The exact boxes of a generated scene: isolates the placement error."""

    def __init__(self, boxes: list[BoundingBox2D]) -> None:
        self.boxes = boxes

    def detect(self, frame: Frame) -> list[Detection2D]:
        return [Detection2D("person", 1.0, b) for b in self.boxes]


def placement_error(rng: np.random.Generator, scenes: int) -> dict[str, dict[str, float]]:
    """Mean absolute error (m) of people placed from generated frames, with ideal boxes
    and with HOG on the person drawn as a silhouette (``found``: frames HOG placed the
    person in, within 0.5 m): random robot poses, head yaw +-0.6 rad, pitch -0.1..0.3 rad,
    people 1.5-5 m away."""
    camera = Camera()
    ideal = IdealDetector([])
    finders = {
        "ideal_boxes": CameraPeopleFinder(CameraFeed(), ideal, PerceptionConfig(), lambda: None),
        "hog": CameraPeopleFinder(
            CameraFeed(), HogPeopleDetector(), PerceptionConfig(), lambda: None
        ),
    }
    errors: dict[str, list[FloatArray]] = {name: [] for name in finders}
    for _ in range(scenes):
        x, y, theta = rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-np.pi, np.pi)
        robot = Pose2D(float(x), float(y), float(theta))
        yaw, pitch = float(rng.uniform(-0.6, 0.6)), float(rng.uniform(-0.1, 0.3))
        distance, heading = rng.uniform(1.5, 5.0), theta + yaw + rng.uniform(-0.3, 0.3)
        person = Cylinder(x + distance * np.cos(heading), y + distance * np.sin(heading))
        truth = (person.x, person.y, person.height / 2)
        scene = render(camera, robot, [person], yaw, pitch, drawn=True)
        ideal.boxes = [b for b in scene.boxes if b is not None]
        frame = RgbdFrame(0.0, scene.rgb, scene.depth, camera.info(0.0), yaw, pitch)
        for name, finder in finders.items():
            placed = [
                np.array([m.position.x, m.position.y, m.position.z])
                for m in finder.measure(frame, robot)
            ]
            near = [e for e in (np.abs(q - truth) for q in placed) if np.hypot(e[0], e[1]) < 0.5]
            errors[name].extend(near[:1])
    return {name: _mae(e, scenes) for name, e in errors.items()}


def _mae(errors: list[FloatArray], scenes: int) -> dict[str, float]:
    mae = np.mean(errors, axis=0) if errors else np.full(3, np.nan)
    return {
        "scenes": scenes,
        "found": len(errors),
        **{axis: round(float(v), 3) for axis, v in zip("xyz", mae, strict=True)},
    }


def bench_camera(
    rng: np.random.Generator,
    repeats: int,
    scenes: int = 50,
    model: Path | None = None,
    pose_model: Path | None = None,
    keypoints: str = "coco17",
) -> dict[str, Any]:
    """Median ms per frame of each path; stand-in models where none is given."""
    frame = bench_frame(Camera())
    report: dict[str, Any] = {"image": [640, 480], "repeats": repeats}
    report["hog_ms_per_frame"] = round(people_ms(HogPeopleDetector(), frame, repeats), 1)
    with tempfile.TemporaryDirectory() as tmp:
        if model is None:
            model, gflops = standin_yolo(
                Path(tmp) / "det.onnx", COCO_OUTPUTS, rng, width=DETECTOR_WIDTH
            )
            report["onnx_model"] = f"stand-in, {gflops:.1f} GFLOPs (YOLOv5n: 4.5)"
        else:
            report["onnx_model"] = str(model)
        detector = YoloOnnxDetector(model)
        report["onnx_ms_per_frame"] = round(people_ms(detector, frame, repeats), 1)
        if pose_model is None:
            columns = 5 + 3 * len(FORMATS[keypoints][0])
            pose_model, gflops = standin_yolo(
                Path(tmp) / "pose.onnx", columns, rng, width=POSE_WIDTH
            )
            report["pose_model"] = f"stand-in, {gflops:.1f} GFLOPs (YOLOv8n-pose: 9.2)"
        else:
            report["pose_model"] = str(pose_model)
        estimator = PoseOnnxEstimator(pose_model, keypoints)
        report["pose_ms_per_frame"] = round(skeletons_ms(estimator, frame, repeats), 1)
    report["activity_frame_budget_ms"] = round(1000.0 / 15.0, 1)  # the model's 15 fps
    report["placement_mae_m"] = placement_error(rng, scenes)
    return report
