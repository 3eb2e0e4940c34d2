"""``amiro har bench``: inference time with preprocessing, as the paper's Table 16 measures.

Wall time is read here only to measure speed, never to drive behaviour.
"""

from __future__ import annotations

import itertools
import os
import time
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np

from amiro.activity.dataset import subject_body
from amiro.activity.keypoints import to_ntu
from amiro.activity.lifting import lift_frame
from amiro.activity.motion import View, perform, sensor_noise, to_camera
from amiro.activity.onnx_model import ActivityModel
from amiro.core.config import ConfigError
from amiro.robot.camera import Camera

LENGTHS = (5, 10, 15, 20, 25, 30, 60)
PAPER_MS = {5: 6.376, 10: 12.435, 15: 18.796, 20: 24.689, 25: 30.665, 30: 36.925, 60: 72.968}
TARGETS_MS = {"30": 1.0, "stream_ms_per_frame": 0.2}


def _stream_of(frames: int) -> np.ndarray:
    rng = np.random.default_rng(0)
    body = subject_body(0, 0)
    clips: list[np.ndarray] = []
    while sum(map(len, clips)) < frames:
        clips.append(perform("drink_water", body, rng))
    return sensor_noise(to_camera(np.concatenate(clips)[:frames], View()), rng)


def per_call_ms(call: Callable[[], object], iterations: int, repeats: int) -> float:
    """Median over ``repeats`` rounds of the mean milliseconds per call: other jobs on a
    shared machine slow some rounds down, the median ignores them."""
    call()  # warm-up
    rounds = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(iterations):
            call()
        rounds.append((time.perf_counter() - start) * 1000.0 / iterations)
    return round(float(np.median(rounds)), 4)


def run_bench(model: ActivityModel, iterations: int = 200, repeats: int = 7) -> dict[str, Any]:
    """Milliseconds per window for each length, and per frame when streaming."""
    frames = _stream_of(max(LENGTHS))
    lengths = {
        str(n): per_call_ms(partial(model.classify, frames[:n]), iterations, repeats)
        for n in LENGTHS
    }
    stream = model.stream()
    order = itertools.cycle(range(len(frames)))

    def push_next() -> None:
        i = next(order)
        if i == 0:
            stream.reset()
        stream.push(frames[i])

    return {
        "lengths": lengths,
        "stream_ms_per_frame": per_call_ms(push_next, iterations, repeats),
        "iterations": iterations,
        "repeats": repeats,
        "load_average": round(os.getloadavg()[0], 2),
        "paper_ms": {str(k): v for k, v in PAPER_MS.items()},
        "targets_ms": TARGETS_MS,
        "model_bytes": model.path.stat().st_size,
    }


def photo_frame(width: int = 640, height: int = 480) -> np.ndarray:
    """A real photograph of a person (Grace Hopper, shipped with matplotlib) on a grey
    ``height`` x ``width`` RGB frame, as a head camera would give it."""
    import matplotlib.cbook
    from PIL import Image

    path = matplotlib.cbook.get_sample_data("grace_hopper.jpg", asfileobj=False)
    photo = Image.open(path).convert("RGB")
    photo = photo.resize((round(photo.width * height / photo.height), height))
    frame = np.full((height, width, 3), 114, dtype=np.uint8)
    left = (width - photo.width) // 2
    frame[:, left : left + photo.width] = np.asarray(photo)
    return frame


def pose_bench(iterations: int = 20, repeats: int = 3) -> dict[str, Any]:
    """Milliseconds per 640x480 frame of the shipped pose path (MediaPipe BlazePose, the
    NTU-25 mapping and lifting with a depth image): tracking a stream, as the camera backend
    runs, and detecting every frame afresh; or why it cannot run."""
    from amiro.activity.mediapipe_pose import MediaPipePoseEstimator

    frame = photo_frame()
    depth = np.full(frame.shape[:2], 2.5)
    info = Camera().info(0.0)
    report: dict[str, Any] = {"pose_backend": "mediapipe BlazePose full", "pose_frame": "640x480"}
    for key, tracking in (("pose_ms_per_frame", True), ("pose_detect_ms_per_frame", False)):
        try:
            estimator = MediaPipePoseEstimator(tracking=tracking)
        except ConfigError as exc:
            return report | {"pose_ms_per_frame": None, "pose_error": str(exc)}

        def one_frame(estimator: MediaPipePoseEstimator = estimator) -> None:
            for pose in estimator.estimate(frame):
                lift_frame(to_ntu(pose.keypoints[None], estimator.keypoint_format)[0], depth, info)

        report[key] = per_call_ms(one_frame, iterations, repeats)
        estimator.close()
    return report
