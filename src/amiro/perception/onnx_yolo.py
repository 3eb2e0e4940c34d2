"""A user-supplied YOLO-style ONNX model run with onnxruntime.

Layout (YOLOv5 export): input (1, 3, S, S) float32 RGB in [0, 1], letterboxed; output
(1, N, 5 + C) rows of box centre, size (input pixels), objectness and C class scores.
Labels default to the 80 COCO names shipped with amiro (person, cup, bottle, chair, couch...).
"""

from __future__ import annotations

import importlib
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from amiro.core.config import ConfigError
from amiro.core.messages import BoundingBox2D, Detection2D
from amiro.perception.hog import import_cv2
from amiro.perception.ports import Frame, require_rgb


def coco_labels() -> list[str]:
    text = resources.files("amiro").joinpath("data/perception/coco_labels.txt").read_text()
    return [line.strip() for line in text.splitlines() if line.strip()]


def open_session(model: Path, who: str) -> Any:
    """An onnxruntime CPU session of ``model``, or a one-line ConfigError."""
    try:
        ort = importlib.import_module("onnxruntime")
    except ImportError as exc:
        raise ConfigError(f"{who} needs onnxruntime: {exc}") from None
    if not Path(model).is_file():
        raise ConfigError(f"{model}: no such model file")
    try:
        return ort.InferenceSession(str(model), providers=["CPUExecutionProvider"])
    except Exception as exc:  # onnxruntime raises its own exception types
        raise ConfigError(f"{model}: not a usable ONNX model: {exc}") from None


def input_size(session: Any, default: int = 640) -> int:
    """The square input side of a YOLO-layout model (``default`` when dynamic)."""
    side = session.get_inputs()[0].shape[2]
    return int(side) if isinstance(side, int) else default


def letterbox(
    rgb: npt.NDArray[Any], size: int
) -> tuple[npt.NDArray[np.float32], float, float, float]:
    """YOLO's input: ``rgb`` scaled into a ``size`` square on grey 114, as (1, 3, S, S)
    floats in [0, 1]; with the scale and the offsets (dx, dy) to undo it."""
    cv2 = import_cv2()
    h, w = rgb.shape[:2]
    r = size / max(h, w)
    nw, nh = round(w * r), round(h * r)
    canvas = np.full((size, size, 3), 114, dtype=np.uint8)
    dx, dy = (size - nw) / 2.0, (size - nh) / 2.0
    image = np.ascontiguousarray(rgb, dtype=np.uint8)
    canvas[int(dy) : int(dy) + nh, int(dx) : int(dx) + nw] = cv2.resize(image, (nw, nh))
    blob = canvas.astype(np.float32).transpose(2, 0, 1)[None] / 255.0
    return blob, r, float(int(dx)), float(int(dy))


class YoloOnnxDetector:
    def __init__(
        self,
        model: Path,
        labels: list[str] | None = None,
        min_score: float = 0.25,
        nms_iou: float = 0.45,
    ) -> None:
        self.session = open_session(model, "the ONNX detector")
        self.input_name = self.session.get_inputs()[0].name
        self.size = input_size(self.session)
        self.labels = labels or coco_labels()
        self.min_score = min_score
        self.nms_iou = nms_iou
        self.cv2 = import_cv2()

    def detect(self, frame: Frame) -> list[Detection2D]:
        rgb = require_rgb(frame, "the ONNX detector")
        blob, r, dx, dy = letterbox(rgb, self.size)
        (out,) = self.session.run(None, {self.input_name: blob})[:1]
        rows = np.asarray(out, dtype=np.float64).reshape(-1, out.shape[-1])
        if rows.shape[1] != 5 + len(self.labels):
            raise ValueError(
                f"model output has {rows.shape[1]} columns, expected {5 + len(self.labels)}"
            )
        classes = np.argmax(rows[:, 5:], axis=1)
        scores = rows[:, 4] * rows[np.arange(len(rows)), 5 + classes]
        keep = scores >= self.min_score
        rows, classes, scores = rows[keep], classes[keep], scores[keep]
        cx, cy = (rows[:, 0] - dx) / r, (rows[:, 1] - dy) / r
        w, h = rows[:, 2] / r, rows[:, 3] / r
        rects = [
            [float(a - c / 2), float(b - d / 2), float(c), float(d)]
            for a, b, c, d in zip(cx, cy, w, h, strict=True)
        ]
        picked = (
            self.cv2.dnn.NMSBoxesBatched(
                rects, scores.tolist(), classes.tolist(), self.min_score, self.nms_iou
            )
            if rects
            else []
        )
        return [
            Detection2D(
                self.labels[int(classes[i])],
                float(scores[i]),
                BoundingBox2D(float(cx[i]), float(cy[i]), float(w[i]), float(h[i])),
            )
            for i in np.ravel(picked)
        ]
