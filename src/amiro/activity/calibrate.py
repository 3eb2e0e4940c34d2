"""``amiro har calibrate``: pick an exported model's decision rule again on validation data.

The confidence floor and the weight of ``unknown``
(:func:`~amiro.activity.open_set.choose_decision`) are chosen on the validation subjects of
the real sets (:data:`~amiro.activity.real_sets.ROLES`), whole and with 30 % of the joints
hidden, and written into a copy of the model's metadata; the network is untouched.
Writing ONNX metadata needs the ``onnx`` package (extra ``train``).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from amiro.activity.labels import UNKNOWN
from amiro.activity.onnx_model import METADATA_KEY, ActivityModel
from amiro.activity.open_set import choose_decision, clip_windows, hide_joints
from amiro.activity.real_sets import load, role
from amiro.core.config import ConfigError

WINDOW_FRAMES = 30  # the recogniser's window
STRIDE = 10


def _probabilities(model: ActivityModel, frames: np.ndarray, batch: int = 256) -> np.ndarray:
    return np.concatenate(
        [model.classify_batch(frames[s : s + batch]) for s in range(0, len(frames), batch)]
    )


def calibrate(model_path: Path | None, real: Path, out: Path, seed: int = 0) -> dict[str, Any]:
    model = ActivityModel(model_path)
    classes = model.info.classes
    if UNKNOWN not in classes:
        raise ConfigError(f"{model.path}: a model without an unknown outcome has no open set")
    validation = [c for c in load(real) if role(c) == "validation"]
    frames, labels = clip_windows(validation, classes, WINDOW_FRAMES, STRIDE)
    floor, weight, score = choose_decision(
        _probabilities(model, frames),
        labels,
        _probabilities(model, hide_joints(frames, seed)),
        classes.index(UNKNOWN),
    )
    write_decision(model.path, out, floor, weight)
    return {
        "out": str(out),
        "threshold": floor,
        "unknown_weight": weight,
        "validation_score": round(score, 4),
        "validation_windows": len(labels),
    }


def write_decision(path: Path, out: Path, threshold: float, unknown_weight: float) -> None:
    """A copy of the ONNX model at ``path`` with this decision rule in its metadata."""
    try:
        import onnx
    except ImportError as exc:
        raise ConfigError(f"writing model metadata needs the 'train' extra: {exc}") from None
    proto = onnx.load(str(path))
    (entry,) = [e for e in proto.metadata_props if e.key == METADATA_KEY]
    meta = json.loads(entry.value)
    meta |= {"threshold": threshold, "unknown_weight": unknown_weight}
    entry.value = json.dumps(meta)
    out.parent.mkdir(parents=True, exist_ok=True)
    onnx.save(proto, str(out))
