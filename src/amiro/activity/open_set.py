"""Training windows from real clips, and the decision rule picked on validation data.

Real clips of amiro's activities train those classes; clips of every other action train
the ``unknown`` outcome, so the model learns what it does not know from real people.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from amiro.activity.augment import drop_joints
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


THRESHOLDS = tuple(float(t) for t in np.round(np.arange(0.3, 0.96, 0.05), 2))
UNKNOWN_WEIGHTS = (1.0, 0.8, 0.6, 0.5, 0.4, 0.3, 0.2)


def decisions(probs: np.ndarray, unknown: int, threshold: float, weight: float) -> np.ndarray:
    """The recogniser's outcome per row (``unknown`` for no activity)."""
    weighed = probs.copy()
    weighed[:, unknown] *= weight
    best = weighed.argmax(axis=1)
    confidence = probs[np.arange(len(probs)), best]
    out: np.ndarray = np.where((best == unknown) | (confidence < threshold), unknown, best)
    return out


def choose_decision(
    probs: np.ndarray, labels: np.ndarray, hidden: np.ndarray, unknown: int
) -> tuple[float, float, float]:
    """The confidence floor and ``unknown`` weight that best balance, on validation windows,
    known accuracy and unknown rejection on whole skeletons and known accuracy on the same
    windows with joints hidden (``hidden``: their probabilities): the mean of the three,
    highest; ties go to the lower floor and the weight nearest 1.  Returns (floor, weight,
    score)."""
    known = labels != unknown
    best = (THRESHOLDS[0], 1.0, -1.0)
    for weight in UNKNOWN_WEIGHTS:
        for floor in THRESHOLDS:
            said = decisions(probs, unknown, floor, weight)
            said_hidden = decisions(hidden, unknown, floor, weight)
            score = float(
                np.mean(
                    [
                        (said[known] == labels[known]).mean(),
                        (said[~known] == unknown).mean(),
                        (said_hidden[known] == labels[known]).mean(),
                    ]
                )
            )
            if score > best[2] + 1e-9:
                best = (floor, weight, score)
    return best


HIDDEN_SHARE = 0.3  # joints hidden in the validation copies the decision rule must serve


def hide_joints(frames: FloatArray, seed: int = 0) -> FloatArray:
    """Copies of validation windows with :data:`HIDDEN_SHARE` of their joints unseen."""
    rng = np.random.default_rng(seed)
    return np.stack([drop_joints(f, HIDDEN_SHARE, rng) for f in frames])
