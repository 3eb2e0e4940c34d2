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
