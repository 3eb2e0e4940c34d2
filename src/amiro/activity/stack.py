"""Build the configured activity recogniser on the robot's head camera and skeleton stream.

Both come from the in-process simulator or from a feed of its bridged topics, so the
embedded system and a deployment's edge run the same recogniser.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, TypeAlias

import numpy as np

from amiro.activity.config import ActivityConfig
from amiro.activity.ports import ActivityRecognizer
from amiro.core import registry
from amiro.robot.camera import HeadCamera

if TYPE_CHECKING:  # the recogniser loads onnxruntime: only when that backend is chosen
    from amiro.activity.recognizer import SkeletonSource

registry.register("activity", "oracle", "amiro.activity.stack:oracle_recognizer")
registry.register("activity", "onnx", "amiro.activity.stack:onnx_recognizer")

Factory: TypeAlias = (
    "Callable[[HeadCamera, SkeletonSource, np.random.Generator, ActivityConfig], "
    "ActivityRecognizer]"
)


def oracle_recognizer(
    camera: HeadCamera, skeletons: SkeletonSource, rng: np.random.Generator, cfg: ActivityConfig
) -> ActivityRecognizer:
    from amiro.sim.activity_oracle import OracleActivityRecognizer

    return OracleActivityRecognizer(camera, rng, cfg.accuracy)


def onnx_recognizer(
    camera: HeadCamera, skeletons: SkeletonSource, rng: np.random.Generator, cfg: ActivityConfig
) -> ActivityRecognizer:
    from amiro.activity.onnx_model import ActivityModel
    from amiro.activity.recognizer import SkeletonActivityRecognizer

    return SkeletonActivityRecognizer(
        skeletons, ActivityModel(cfg.model), cfg.window_frames, cfg.min_confidence, cfg.min_visible
    )


def build_activity_recognizer(
    camera: HeadCamera, skeletons: SkeletonSource, rng: np.random.Generator, cfg: ActivityConfig
) -> ActivityRecognizer:
    """The backend ``cfg.backend`` names ("onnx": the shipped model on the residents'
    skeleton streams; "oracle": the camera's ground truth with errors)."""
    factory: Factory = registry.resolve("activity", cfg.backend)
    return factory(camera, skeletons, rng, cfg)
