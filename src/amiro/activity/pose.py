"""2D pose estimation on the robot's RGB image: the port and an ONNX backend.

:class:`PoseOnnxEstimator` runs a user-supplied model with the YOLO-pose layout (what
``yolo export format=onnx`` gives for YOLOv8/YOLO11 pose models):

- input ``(1, 3, S, S)`` float32 RGB in [0, 1], the image letterboxed on grey 114;
- output ``(1, 5 + 3K, N)`` (or ``(1, N, 5 + 3K)``): per candidate the box centre and size
  and the person score, then K keypoints as (x, y, confidence), in input pixels.

K and the keypoint order come from ``keypoints`` (``coco17`` for YOLO-pose); candidates
under ``min_score`` are dropped and overlapping ones suppressed.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

import numpy as np
import numpy.typing as npt

from amiro.activity.keypoints import FORMATS
from amiro.activity.skeleton import FloatArray
from amiro.core.config import ConfigError
from amiro.core.messages import BoundingBox2D
from amiro.core.vision import import_cv2, input_size, letterbox, open_session


@dataclass(frozen=True, eq=False)
class PoseDetection:
    """One person: box and score, and keypoints ``(K, 3)`` of (u, v, confidence) in image
    pixels, in the estimator's keypoint order."""

    box: BoundingBox2D
    score: float
    keypoints: FloatArray


class PoseEstimator(Protocol):
    keypoint_format: str  # a key of amiro.activity.keypoints.FORMATS

    def estimate(self, rgb: npt.NDArray[np.uint8]) -> list[PoseDetection]:
        """Everyone's 2D pose in an (H, W, 3) RGB image."""
        ...


class PoseOnnxEstimator:
    """A YOLO-pose-layout ONNX model in onnxruntime (layout in the module docstring)."""

    def __init__(
        self,
        model: Path,
        keypoint_format: str = "coco17",
        min_score: float = 0.5,
        nms_iou: float = 0.45,
    ) -> None:
        if keypoint_format not in FORMATS:
            raise ConfigError(
                f"unknown keypoint format {keypoint_format!r} (known: {', '.join(FORMATS)})"
            )
        self.session = open_session(model, "the ONNX pose estimator")
        self.input_name = self.session.get_inputs()[0].name
        self.size = input_size(self.session)
        self.keypoint_format = keypoint_format
        self.keypoints = len(FORMATS[keypoint_format][0])
        self.min_score = min_score
        self.nms_iou = nms_iou
        self.cv2 = import_cv2()
        declared = self.session.get_outputs()[0].shape
        if all(isinstance(d, int) for d in declared):  # a wrong layout fails at start-up
            self.rows(np.zeros(declared, dtype=np.float32))

    def rows(self, out: npt.NDArray[np.float32]) -> FloatArray:
        """The model's output as one row per candidate, ``(N, 5 + 3K)``."""
        width = 5 + 3 * self.keypoints
        raw = np.asarray(out, dtype=np.float64)
        if raw.ndim != 3 or width not in raw.shape[1:]:
            raise ConfigError(
                f"pose model output shape {raw.shape}: expected (1, {width}, N) or "
                f"(1, N, {width}) for {self.keypoints} keypoints ({self.keypoint_format})"
            )
        rows: FloatArray = raw[0].T if raw.shape[1] == width else raw[0]
        return rows

    def estimate(self, rgb: npt.NDArray[np.uint8]) -> list[PoseDetection]:
        blob, r, dx, dy = letterbox(rgb, self.size)
        rows = self.rows(self.session.run(None, {self.input_name: blob})[0])
        rows = rows[rows[:, 4] >= self.min_score]
        if not len(rows):
            return []
        shift = np.array([dx, dy])
        centres = (rows[:, :2] - shift) / r
        sizes = rows[:, 2:4] / r
        points = rows[:, 5:].reshape(len(rows), self.keypoints, 3).copy()
        points[..., :2] = (points[..., :2] - shift) / r
        rects = np.concatenate([centres - sizes / 2, sizes], axis=1).tolist()
        picked = self.cv2.dnn.NMSBoxes(rects, rows[:, 4].tolist(), self.min_score, self.nms_iou)
        return [
            PoseDetection(
                BoundingBox2D(*map(float, (*centres[i], *sizes[i]))),
                float(rows[i, 4]),
                points[i],
            )
            for i in np.ravel(picked)
        ]
