"""The activity model at run time: onnxruntime only, no torch.

:class:`ActivityModel` classifies whole windows (preprocessing included);
:meth:`ActivityModel.stream` returns a classifier that takes one frame at a time and
carries the LSTM states, so each new frame costs one step instead of a whole window.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np
import onnxruntime as ort

from amiro.activity.labels import UNKNOWN
from amiro.activity.normalize import ViewFrame, first_view, preprocess_batch, view_features
from amiro.activity.skeleton import FloatArray
from amiro.core.config import ConfigError

METADATA_KEY = "amiro_activity"
# Share of the image height a whole person fills in the training views (NTU RGB+D subjects
# 2-4 m from a Kinect v2): the framing RecognizeActivity moves the base to reproduce.
BOX_HEIGHT_RANGE = (0.45, 0.85)
MODEL_FILE = "har_multistage_lstm.onnx"
DEFAULT_THRESHOLD = 0.5  # a model without a validated threshold


def shipped_model_path() -> Path:
    return Path(str(resources.files("amiro").joinpath(f"data/models/{MODEL_FILE}")))


@dataclass(frozen=True)
class ModelInfo:
    """What the ONNX metadata says: ``classes`` are the network's outputs (amiro's
    activities, then ``unknown`` when the model has that outcome); ``threshold`` the
    confidence below which it reports no activity, chosen on validation data."""

    classes: tuple[str, ...]
    fps: float
    hidden: int
    stages: int
    features: int
    box_height_fraction: tuple[float, float]
    threshold: float = DEFAULT_THRESHOLD
    # ``unknown``'s probability is scaled by this before the argmax (chosen on validation
    # data with joints missing: a partly hidden body otherwise reads as "something else").
    unknown_weight: float = 1.0


class ActivityModel:
    """An exported multi-stage LSTM (see ``amiro har train``) in an onnxruntime session."""

    def __init__(self, path: str | Path | None = None) -> None:
        self.path = Path(path) if path is not None else shipped_model_path()
        if not self.path.is_file():
            raise ConfigError(f"{self.path}: no such activity model file")
        options = ort.SessionOptions()
        # One small LSTM per call: a second thread costs more in hand-offs than it saves,
        # and the robot's other modules need the cores.
        options.intra_op_num_threads = 1
        options.inter_op_num_threads = 1
        options.execution_mode = ort.ExecutionMode.ORT_SEQUENTIAL
        options.graph_optimization_level = ort.GraphOptimizationLevel.ORT_ENABLE_ALL
        try:
            self.session = ort.InferenceSession(
                str(self.path), options, providers=["CPUExecutionProvider"]
            )
            raw = self.session.get_modelmeta().custom_metadata_map[METADATA_KEY]
        except Exception as exc:  # any unreadable or foreign file is a bad config
            raise ConfigError(f"{self.path}: not an amiro activity model ({exc})") from None
        meta = json.loads(raw)
        self.info = ModelInfo(
            tuple(meta["classes"]),
            float(meta["fps"]),
            int(meta["hidden"]),
            int(meta["stages"]),
            int(meta["features"]),
            (float(meta["box_height_fraction"][0]), float(meta["box_height_fraction"][1])),
            float(meta.get("threshold", DEFAULT_THRESHOLD)),
            float(meta.get("unknown_weight", 1.0)),
        )

    @property
    def outcomes(self) -> tuple[str, ...]:
        """Every output of the network, ``unknown`` included when it has one."""
        return self.info.classes

    @property
    def classes(self) -> tuple[str, ...]:
        """The activities the model recognises (its outcomes but ``unknown``)."""
        return tuple(c for c in self.info.classes if c != UNKNOWN)

    def decide(self, probs: np.ndarray, threshold: float | None = None) -> tuple[str | None, float]:
        """The activity of one probability vector and its confidence; None when the
        model says ``unknown`` (its probability weighed by ``unknown_weight``) or is less
        sure than ``threshold`` (default: the model's)."""
        weighed = probs
        if UNKNOWN in self.info.classes and self.info.unknown_weight != 1.0:
            weighed = probs.copy()
            weighed[self.info.classes.index(UNKNOWN)] *= self.info.unknown_weight
        best = int(np.argmax(weighed))
        confidence = float(probs[best])
        label = self.outcomes[best]
        floor = self.info.threshold if threshold is None else threshold
        return (None if label == UNKNOWN or confidence < floor else label), confidence

    def zero_state(self, batch: int) -> tuple[np.ndarray, np.ndarray]:
        shape = (self.info.stages, batch, self.info.hidden)
        return np.zeros(shape, np.float32), np.zeros(shape, np.float32)

    def run(
        self, feats: np.ndarray, h: np.ndarray, c: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Raw network step: features ``(B, T, F)`` and states in, probabilities and states out."""
        probs, h, c = self.session.run(None, {"features": feats, "h0": h, "c0": c})
        return probs, h, c

    def classify_batch(self, frames: FloatArray) -> np.ndarray:
        """Class probabilities ``(B, classes)`` of raw skeleton windows ``(B, T, 25, 3)``."""
        h, c = self.zero_state(len(frames))
        return self.run(preprocess_batch(frames), h, c)[0]

    def classify(self, frames: FloatArray) -> np.ndarray:
        """Class probabilities of one raw skeleton window ``(T, 25, 3)``."""
        probs: np.ndarray = self.classify_batch(frames[None])[0]
        return probs

    def stream(self) -> StreamingClassifier:
        return StreamingClassifier(self)


class StreamingClassifier:
    """Frame-by-frame classification: the view is fixed by the first frame after
    :meth:`reset`, the LSTM states carry the past.  After n frames the prediction equals
    :meth:`ActivityModel.classify` of those n frames."""

    def __init__(self, model: ActivityModel) -> None:
        self.model = model
        self.reset()

    def reset(self) -> None:
        self.view: ViewFrame | None = None
        self.h, self.c = self.model.zero_state(1)
        self.frames = 0

    def push(self, frame: FloatArray) -> np.ndarray:
        """Add one raw frame ``(25, 3)``; returns the updated class probabilities."""
        if self.view is None:
            self.view = first_view(frame)
        feats = view_features(self.view, frame[None])[None]
        probs, self.h, self.c = self.model.run(feats, self.h, self.c)
        self.frames += 1
        out: np.ndarray = probs[0]
        return out
