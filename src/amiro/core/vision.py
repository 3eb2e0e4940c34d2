"""Image-model plumbing shared by perception's detectors and activity's pose models:
OpenCV and onnxruntime loaded on demand with one-line errors, YOLO-style letterboxing, box
overlap."""

from __future__ import annotations

import importlib
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from amiro.core.config import ConfigError
from amiro.core.messages import BoundingBox2D


def import_cv2() -> Any:
    try:
        return importlib.import_module("cv2")
    except ImportError as exc:
        raise ConfigError(
            f"this needs the extra amiro[vision] (opencv-python-headless<5): {exc}"
        ) from None


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


def iou(a: BoundingBox2D, b: BoundingBox2D) -> float:
    """Intersection over union of two boxes."""
    ix = min(a.cx + a.width / 2, b.cx + b.width / 2) - max(a.cx - a.width / 2, b.cx - b.width / 2)
    iy = min(a.cy + a.height / 2, b.cy + b.height / 2) - max(
        a.cy - a.height / 2, b.cy - b.height / 2
    )
    if ix <= 0 or iy <= 0:
        return 0.0
    inter = ix * iy
    union = a.width * a.height + b.width * b.height - inter
    return inter / union if union > 0 else 0.0
