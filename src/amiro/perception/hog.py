"""OpenCV's HOG + linear SVM people detector (Dalal and Triggs) on real RGB images.

Needs opencv-python-headless 4.x (5.x dropped the HOG people detector).
"""

from __future__ import annotations

import numpy as np

from amiro.core.messages import BoundingBox2D, Detection2D
from amiro.core.vision import import_cv2
from amiro.perception.ports import Frame, require_rgb


class HogPeopleDetector:
    """Person boxes; the SVM margin is squashed into a [0, 1] score."""

    def __init__(self, min_score: float = 0.5, scale: float = 1.05, stride: int = 8) -> None:
        self.cv2 = import_cv2()
        self.hog = self.cv2.HOGDescriptor()
        self.hog.setSVMDetector(self.cv2.HOGDescriptor_getDefaultPeopleDetector())
        self.min_score = min_score
        self.scale = scale
        self.stride = stride

    def detect(self, frame: Frame) -> list[Detection2D]:
        rgb = np.ascontiguousarray(require_rgb(frame, "the HOG detector"), dtype=np.uint8)
        gray = self.cv2.cvtColor(rgb, self.cv2.COLOR_RGB2GRAY)
        rects, weights = self.hog.detectMultiScale(
            gray, winStride=(self.stride, self.stride), padding=(8, 8), scale=self.scale
        )
        found = []
        for (x, y, w, h), margin in zip(rects, np.ravel(weights), strict=True):
            score = float(1.0 / (1.0 + np.exp(-float(margin))))
            if score >= self.min_score:
                box = BoundingBox2D(x + w / 2.0, y + h / 2.0, float(w), float(h))
                found.append(Detection2D("person", score, box))
        return found
