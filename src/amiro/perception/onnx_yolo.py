"""A user-supplied YOLO-style ONNX model run with onnxruntime.

Layout (YOLOv5 export): input (1, 3, S, S) float32 RGB in [0, 1], letterboxed; output
(1, N, 5 + C) rows of box centre, size (input pixels), objectness and C class scores.
Labels default to the 80 COCO names shipped with amiro (person, cup, bottle, chair, couch...).
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import numpy as np

from amiro.core.messages import BoundingBox2D, Detection2D
from amiro.core.vision import import_cv2, input_size, letterbox, open_session
from amiro.perception.ports import Frame, require_rgb


def coco_labels() -> list[str]:
    text = resources.files("amiro").joinpath("data/perception/coco_labels.txt").read_text()
    return [line.strip() for line in text.splitlines() if line.strip()]


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
