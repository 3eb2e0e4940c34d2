"""``amiro har bench``: inference time with preprocessing, as the paper's Table 16 measures.

Wall time is read here only to measure speed, never to drive behaviour.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from amiro.activity.dataset import subject_body
from amiro.activity.motion import View, perform, sensor_noise, to_camera
from amiro.activity.onnx_model import ActivityModel

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


def run_bench(model: ActivityModel, iterations: int = 100) -> dict[str, Any]:
    """Mean milliseconds per window for each length, and per frame when streaming."""
    frames = _stream_of(max(LENGTHS))
    lengths: dict[str, float] = {}
    for n in LENGTHS:
        window = frames[:n]
        model.classify(window)  # warm-up
        start = time.perf_counter()
        for _ in range(iterations):
            model.classify(window)
        lengths[str(n)] = round((time.perf_counter() - start) * 1000.0 / iterations, 4)
    stream = model.stream()
    stream.push(frames[0])
    pushed = 0
    start = time.perf_counter()
    for _ in range(max(1, iterations // len(frames) + 1)):
        stream.reset()
        for frame in frames:
            stream.push(frame)
            pushed += 1
    per_frame = (time.perf_counter() - start) * 1000.0 / pushed
    return {
        "lengths": lengths,
        "stream_ms_per_frame": round(per_frame, 4),
        "iterations": iterations,
        "paper_ms": {str(k): v for k, v in PAPER_MS.items()},
        "targets_ms": TARGETS_MS,
        "model_bytes": model.path.stat().st_size,
    }
