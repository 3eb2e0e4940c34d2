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
from amiro.activity.stack import ActivityInputs, CameraSkeletons, create_recognizer
from amiro.core import registry
from amiro.core.config import ConfigError
from amiro.core.runtime import Runtime
from amiro.perception.camera_finder import CameraPeopleFinder
from amiro.perception.config import CameraSection, PerceptionConfig
from amiro.perception.faces import FaceGallery, dlib_gallery
from amiro.perception.ports import Detector, PeopleFinder
from amiro.perception.stack import PerceptionInputs, PoseSource
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


def hog_detector(cfg: CameraSection) -> Detector:
    from amiro.perception.hog import HogPeopleDetector

    return HogPeopleDetector(min_score=cfg.min_score)


def onnx_detector(cfg: CameraSection) -> Detector:
    from amiro.perception.onnx_yolo import YoloOnnxDetector

    assert cfg.model is not None  # the section's validator requires it
    return YoloOnnxDetector(cfg.model, min_score=cfg.min_score)


def unnamed_faces(cfg: PerceptionConfig) -> FaceGallery | None:
    """``faces.backend: sim`` on a camera: the simulator's face model needs its ground
    truth, so people are tracked unnamed."""
    return None


def dlib_faces(cfg: PerceptionConfig) -> FaceGallery:
    return dlib_gallery(cfg.faces.gallery, cfg.faces.threshold)


def camera_people_finder(inputs: PerceptionInputs) -> PeopleFinder:
    """The configured detector and faces on a real robot's camera feed."""
    if inputs.feed is None or inputs.localization is None:
        raise ConfigError(
            "perception.backend: camera reads a real robot's camera topics: build it with "
            "amiro.system.camera.build_camera_modules (robot.adapter: ros2 or naoqi)"
        )
    p = inputs.cfg
    detector: Detector = registry.create("detector", p.camera.detector, p.camera)
    faces: FaceGallery | None = registry.create("faces", p.faces.backend, p)
    return CameraPeopleFinder(inputs.feed, detector, p, inputs.localization, faces)


def build_camera_modules(
    runtime: Runtime, cfg: CameraConfigs, localization: PoseSource
) -> CameraModules:
    """The camera feed, people finder and activity recogniser of a real robot, added to
    ``runtime``; people are placed in the map with ``localization`` (the robot's pose)."""
    p = cfg.perception
    c = p.camera
    feed = runtime.add(CameraFeed(c.yaw, c.pitch, c.head_joints, c.max_skew_s))
    inputs = PerceptionInputs(p, runtime.rng, localization, feed=feed)
    people = registry.create("perception", p.backend, inputs)
    if not isinstance(people, CameraPeopleFinder):  # the pose model shares its tracks
        raise ConfigError(
            f"perception.backend: {p.backend} gave no CameraPeopleFinder, which a robot's "
            "camera needs (activity's pose model shares its tracks)"
        )
    camera = CameraSkeletons(runtime, feed, people.locate, people.place)
    activity = create_recognizer(ActivityInputs(cfg.activity, runtime.rng, camera=camera))
    return CameraModules(feed, people, activity)
