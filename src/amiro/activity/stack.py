"""Build the configured activity recogniser for the simulated home."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from amiro.activity.config import ActivityConfig
from amiro.activity.ports import ActivityRecognizer
from amiro.core import registry
from amiro.sim.simulator import Simulation

registry.register("activity", "oracle", "amiro.activity.stack:oracle_recognizer")
registry.register("activity", "onnx", "amiro.activity.stack:onnx_recognizer")

Factory = Callable[[Simulation, np.random.Generator, ActivityConfig], ActivityRecognizer]


def oracle_recognizer(
    sim: Simulation, rng: np.random.Generator, cfg: ActivityConfig
) -> ActivityRecognizer:
    from amiro.activity.oracle import OracleActivityRecognizer

    return OracleActivityRecognizer(sim, rng, cfg.accuracy)


def onnx_recognizer(
    sim: Simulation, rng: np.random.Generator, cfg: ActivityConfig
) -> ActivityRecognizer:
    from amiro.activity.onnx_model import ActivityModel
    from amiro.activity.recognizer import SkeletonActivityRecognizer
    from amiro.sim.skeletons import SkeletonCamera

    return SkeletonActivityRecognizer(
        SkeletonCamera(sim, rng),
        ActivityModel(cfg.model),
        cfg.window_frames,
        cfg.min_confidence,
        cfg.min_visible,
    )


def build_activity_recognizer(
    sim: Simulation, rng: np.random.Generator, cfg: ActivityConfig
) -> ActivityRecognizer:
    """The backend ``cfg.backend`` names ("onnx": the shipped model on the residents'
    simulated skeleton streams; "oracle": ground truth with errors)."""
    factory: Factory = registry.resolve("activity", cfg.backend)
    return factory(sim, rng, cfg)
