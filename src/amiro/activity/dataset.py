"""The synthetic dataset: subjects and camera views split as NTU RGB+D does.

Cross-subject holds out whole subjects; cross-view holds out whole camera positions.
Samples are fixed-length windows cut anywhere in two back-to-back clips of one action,
the way a robot sees a continuous stream, stored raw (Kinect space, NaN = unseen).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from amiro.activity.labels import ACTIONS
from amiro.activity.motion import (
    FPS,
    Body,
    View,
    perform,
    sensor_noise,
    to_camera,
)
from amiro.activity.skeleton import FloatArray

SUBJECTS = 40
TEST_SUBJECTS = tuple(range(0, SUBJECTS, 5))
TRAIN_SUBJECTS = tuple(s for s in range(SUBJECTS) if s not in TEST_SUBJECTS)
CAMERAS_DEG = (-60.0, -30.0, 0.0, 30.0, 60.0)
TEST_CAMERAS_DEG = (-60.0, 60.0)
TRAIN_CAMERAS_DEG = tuple(c for c in CAMERAS_DEG if c not in TEST_CAMERAS_DEG)
WINDOW = 40  # frames stored per sample; training crops shorter windows from it


@dataclass
class Samples:
    frames: FloatArray  # (N, WINDOW, 25, 3)
    labels: np.ndarray  # (N,) index into ACTIONS

    def __len__(self) -> int:
        return len(self.labels)


def subject_body(subject: int, seed: int) -> Body:
    """The same subject (size, proportions, handedness) for every split and clip."""
    return Body.random(np.random.default_rng([seed, subject]))


def window(
    action: str, body: Body, camera_deg: float, rng: np.random.Generator, length: int = WINDOW
) -> FloatArray:
    """One raw sample: ``length`` frames of ``action`` seen from one camera, with noise."""
    sitting = None if action in ("standing_up", "falling") else bool(rng.random() < 0.5)
    clips = [perform(action, body, rng, FPS, sitting) for _ in range(2)]
    stream = np.concatenate(clips)
    while len(stream) < length:
        stream = np.concatenate([stream[:1], stream])
    start = int(rng.integers(0, len(stream) - length + 1))
    view = View(
        yaw=np.deg2rad(camera_deg + rng.uniform(-10.0, 10.0)),
        distance=rng.uniform(2.0, 4.0),
        height=rng.uniform(0.8, 1.3),
        pitch=rng.uniform(-0.1, 0.1),
    )
    return sensor_noise(to_camera(stream[start : start + length], view), rng)


def generate(
    subjects: tuple[int, ...],
    cameras_deg: tuple[float, ...],
    per_cell: int,
    rng: np.random.Generator,
    seed: int = 0,
) -> Samples:
    """``per_cell`` windows for every (subject, camera, action)."""
    frames, labels = [], []
    for subject in subjects:
        body = subject_body(subject, seed)
        for cam in cameras_deg:
            for label, action in enumerate(ACTIONS):
                for _ in range(per_cell):
                    frames.append(window(action, body, cam, rng))
                    labels.append(label)
    return Samples(np.stack(frames), np.array(labels, dtype=np.int64))
