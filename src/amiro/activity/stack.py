"""Build the configured activity recogniser: on the robot's head camera and skeleton stream
(the in-process simulator or a feed of its bridged topics, so the embedded system and a
deployment's edge run the same recogniser), or on a real robot's camera through a pose
model.  Backends are looked up by name in the registry (:mod:`amiro.activity.backends`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from amiro.activity.config import ActivityConfig
from amiro.activity.ports import ActivityRecognizer
from amiro.core import registry
from amiro.core.config import ConfigError
from amiro.robot.camera import HeadCamera

if TYPE_CHECKING:  # these load onnxruntime: only when their backend is chosen
    from amiro.activity.camera_skeletons import BoxPlacer, PersonLocator
    from amiro.activity.pose import PoseEstimator
    from amiro.activity.recognizer import SkeletonSource
    from amiro.core.runtime import Runtime
    from amiro.robot.camera_feed import CameraFeed


@dataclass(frozen=True)
class CameraSkeletons:
    """A real robot's camera for a pose model: the runtime its skeleton source joins, the
    feed, and the people finder's ``locate``/``place``, so skeletons take the tracks' names."""

    runtime: Runtime
    feed: CameraFeed
    locate: PersonLocator
    place: BoxPlacer


@dataclass(frozen=True)
class ActivityInputs:
    """What a recogniser is built on: the simulator's ``head`` camera and ``skeletons``
    stream, or a real robot's ``camera``; the others are None."""

    cfg: ActivityConfig
    rng: np.random.Generator
    head: HeadCamera | None = None
    skeletons: SkeletonSource | None = None
    camera: CameraSkeletons | None = None

    def simulated(self) -> tuple[HeadCamera, SkeletonSource]:
        """The simulator's head camera and skeletons, or the error a real robot's config gets."""
        if self.head is None or self.skeletons is None:
            raise ConfigError(
                f"activity.backend: {self.cfg.backend} reads the simulator; a real robot needs "
                "camera-onnx (with activity.pose.model)"
            )
        return self.head, self.skeletons


def onnx_recognizer(inputs: ActivityInputs) -> ActivityRecognizer:
    from amiro.activity.onnx_model import ActivityModel
    from amiro.activity.recognizer import SkeletonActivityRecognizer

    _, skeletons = inputs.simulated()
    cfg = inputs.cfg
    return SkeletonActivityRecognizer(
        skeletons, ActivityModel(cfg.model), cfg.window_frames, cfg.min_confidence, cfg.min_visible
    )


def camera_onnx_recognizer(inputs: ActivityInputs) -> ActivityRecognizer:
    """The activity model on skeletons the configured ONNX pose model finds in the camera."""
    from amiro.activity.pose import PoseOnnxEstimator

    pose = inputs.cfg.pose
    _real_camera(inputs)
    if pose.model is None:
        raise ConfigError("activity.pose.model: camera-onnx needs a pose model (ONNX file)")
    estimator = PoseOnnxEstimator(pose.model, pose.keypoints, pose.min_score, pose.nms_iou)
    return _camera_recognizer(inputs, estimator)


def camera_mediapipe_recognizer(inputs: ActivityInputs) -> ActivityRecognizer:
    """The activity model on skeletons MediaPipe BlazePose (shipped in ``amiro[pose]``)
    finds in the camera: one person per image, tracked from frame to frame."""
    from amiro.activity.mediapipe_pose import MediaPipePoseEstimator

    _real_camera(inputs)
    return _camera_recognizer(inputs, MediaPipePoseEstimator(inputs.cfg.pose.min_score))


def _real_camera(inputs: ActivityInputs) -> CameraSkeletons:
    if inputs.camera is None:
        raise ConfigError(
            f"activity.backend: {inputs.cfg.backend} reads a real robot's camera "
            "(robot.adapter: ros2); on the simulator use onnx"
        )
    return inputs.camera


def _camera_recognizer(inputs: ActivityInputs, estimator: PoseEstimator) -> ActivityRecognizer:
    from amiro.activity.camera_skeletons import CameraSkeletonSource
    from amiro.activity.onnx_model import ActivityModel
    from amiro.activity.recognizer import SkeletonActivityRecognizer

    cfg, camera = inputs.cfg, _real_camera(inputs)
    model = ActivityModel(cfg.model)
    source = camera.runtime.add(
        CameraSkeletonSource(
            camera.feed,
            estimator,
            model.info.fps,  # the rate the activity model was trained at
            cfg.pose.min_keypoint,
            locate=camera.locate,
            place=camera.place,
        )
    )
    return SkeletonActivityRecognizer(
        source, model, cfg.window_frames, cfg.min_confidence, cfg.min_visible
    )


def build_activity_recognizer(
    camera: HeadCamera, skeletons: SkeletonSource, rng: np.random.Generator, cfg: ActivityConfig
) -> ActivityRecognizer:
    """The backend ``cfg.backend`` names ("onnx": the shipped model on the residents'
    skeleton streams; "oracle": the camera's ground truth with errors)."""
    return create_recognizer(ActivityInputs(cfg, rng, camera, skeletons))


def create_recognizer(inputs: ActivityInputs) -> ActivityRecognizer:
    recognizer: ActivityRecognizer = registry.create("activity", inputs.cfg.backend, inputs)
    return recognizer
