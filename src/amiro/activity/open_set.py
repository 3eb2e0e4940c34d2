"""Training windows from real clips, and the confidence threshold picked on validation data.

Real clips of amiro's activities train those classes; clips of every other action train
the ``unknown`` outcome, so the model learns what it does not know from real people.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from amiro.activity.labels import UNKNOWN
from amiro.activity.real_sets import Clip
from amiro.activity.skeleton import FloatArray


def clip_windows(
    clips: Sequence[Clip], classes: Sequence[str], length: int, stride: int
) -> tuple[FloatArray, np.ndarray]:
    """Windows of ``length`` frames every ``stride`` frames (a short clip once, its first
    frame repeated before it) and their class index (``unknown`` for other actions)."""
    index = {name: i for i, name in enumerate(classes)}
    frames, labels = [], []
    for clip in clips:
        f = clip.frames
        if len(f) < length:
            f = np.concatenate([np.repeat(f[:1], length - len(f), axis=0), f])
        for end in range(len(f), length - 1, -stride):
            frames.append(f[end - length : end])
            labels.append(index[clip.label or UNKNOWN])
    return np.stack(frames), np.array(labels, dtype=np.int64)


def choose_threshold(
    probs: np.ndarray, labels: np.ndarray, unknown: int, grid: Sequence[float] | None = None
) -> float:
    """The confidence floor that best balances known accuracy and unknown rejection on
    validation windows: the mean of the two, highest; ties go to the lower floor."""
    best = probs.argmax(axis=1)
    confidence = probs.max(axis=1)
    known = labels != unknown
    scores = []
    candidates = list(grid) if grid is not None else list(np.round(np.arange(0.3, 0.96, 0.05), 2))
    for floor in candidates:
        said = np.where((best == unknown) | (confidence < floor), unknown, best)
        parts = []
        if known.any():
            parts.append(float((said[known] == labels[known]).mean()))
        if (~known).any():
            parts.append(float((said[~known] == unknown).mean()))
        scores.append(float(np.mean(parts)) if parts else 0.0)
    return float(candidates[int(np.argmax(scores))])
