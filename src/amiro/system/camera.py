"""Perception and activity on a real robot's RGB-D camera, from the system configuration.

``build_system`` calls :func:`build_camera_modules` instead of the simulator's builders when
``robot.adapter`` is not ``sim``: one :class:`CameraFeed` reads the robot port's camera
topics, the ``camera`` people finder and (with ``activity.backend: camera-onnx``) the pose
skeleton source share it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from amiro.activity.config import ActivityConfig
from amiro.activity.ports import ActivityRecognizer
from amiro.core.config import ConfigError
from amiro.core.runtime import Runtime
from amiro.perception.camera_finder import CameraPeopleFinder
from amiro.perception.config import CameraSection, PerceptionConfig
from amiro.perception.faces import FaceGallery, dlib_gallery
from amiro.perception.ports import Detector
from amiro.perception.stack import PoseSource
from amiro.robot.camera_feed import CameraFeed


class CameraConfigs(Protocol):
    """What is read from the system configuration (a ``SystemConfig``)."""

    @property
    def perception(self) -> PerceptionConfig: ...

    @property
    def activity(self) -> ActivityConfig: ...


@dataclass
class CameraModules:
    feed: CameraFeed
    people: CameraPeopleFinder
    activity: ActivityRecognizer


def build_detector(cfg: CameraSection) -> Detector:
    if cfg.detector == "onnx":
        from amiro.perception.onnx_yolo import YoloOnnxDetector

        assert cfg.model is not None  # the section's validator requires it
        return YoloOnnxDetector(cfg.model, min_score=cfg.min_score)
    from amiro.perception.hog import HogPeopleDetector

    return HogPeopleDetector(min_score=cfg.min_score)


def build_faces(cfg: PerceptionConfig) -> FaceGallery | None:
    """The dlib gallery with ``faces.backend: dlib``; else people are tracked unnamed."""
    if cfg.faces.backend != "dlib":
        return None
    return dlib_gallery(cfg.faces.gallery, cfg.faces.threshold)


def build_camera_activity(
    runtime: Runtime, cfg: ActivityConfig, feed: CameraFeed, people: CameraPeopleFinder
) -> ActivityRecognizer:
    """The activity model on skeletons the configured pose model finds in the camera."""
    from amiro.activity.camera_skeletons import CameraSkeletonSource
    from amiro.activity.onnx_model import ActivityModel
    from amiro.activity.pose import PoseOnnxEstimator
    from amiro.activity.recognizer import SkeletonActivityRecognizer

    pose = cfg.pose
    if pose.model is None:
        raise ConfigError("activity.pose.model: camera-onnx needs a pose model (ONNX file)")
    model = ActivityModel(cfg.model)
    estimator = PoseOnnxEstimator(pose.model, pose.keypoints, pose.min_score, pose.nms_iou)
    source = runtime.add(
        CameraSkeletonSource(
            feed,
            estimator,
            model.info.fps,  # the rate the activity model was trained at
            pose.min_keypoint,
            locate=people.locate,
            place=people.place,
        )
    )
    return SkeletonActivityRecognizer(
        source, model, cfg.window_frames, cfg.min_confidence, cfg.min_visible
    )


def build_camera_modules(
    runtime: Runtime, cfg: CameraConfigs, localization: PoseSource
) -> CameraModules:
    """The camera feed, people finder and activity recogniser of a real robot, added to
    ``runtime``; people are placed in the map with ``localization`` (the robot's pose)."""
    p = cfg.perception
    if p.backend != "camera":
        raise ConfigError(
            f"perception.backend: {p.backend} reads the simulator; a real robot needs camera"
        )
    if cfg.activity.backend != "camera-onnx":
        raise ConfigError(
            f"activity.backend: {cfg.activity.backend} reads the simulator; a real robot needs "
            "camera-onnx (with activity.pose.model)"
        )
    c = p.camera
    feed = runtime.add(CameraFeed(c.yaw, c.pitch, c.head_joints, c.max_skew_s))
    people = CameraPeopleFinder(feed, build_detector(c), p, localization, build_faces(p))
    activity = build_camera_activity(runtime, cfg.activity, feed, people)
    return CameraModules(feed, people, activity)
