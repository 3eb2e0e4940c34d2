"""The ``activity:`` section of the system configuration."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Literal

from pydantic import Field

from amiro.activity import backends as _backends  # noqa: F401 - registers the names
from amiro.core.config import Section
from amiro.core.registry import backend_name


class PoseSection(Section):
    """The camera backends' 2D pose estimator: ``camera-onnx`` runs ``model`` (layout in
    docs/activity.md), ``camera-mediapipe`` the BlazePose model ``amiro[pose]`` ships."""

    model: Path | None = Field(
        default=None, description="camera-onnx: a YOLO-pose-layout ONNX model"
    )
    keypoints: Literal["coco17", "openpose_body25", "mediapipe_blazepose33"] = Field(
        default="coco17", description="camera-onnx: the model's keypoint order"
    )
    min_score: float = Field(default=0.5, ge=0.0, le=1.0, description="person score kept")
    min_keypoint: float = Field(default=0.3, ge=0.0, le=1.0, description="keypoint confidence")
    nms_iou: float = Field(default=0.45, gt=0.0, le=1.0)


class ActivityConfig(Section):
    backend: Annotated[str, backend_name("activity")] = Field(
        default="onnx",
        description="onnx: the model on simulated skeletons; oracle: ground truth; "
        "camera-mediapipe: the model on skeletons MediaPipe BlazePose (amiro[pose]) finds "
        "in the robot's camera; camera-onnx: the same with a user-supplied ONNX pose model",
    )
    model: Path | None = Field(default=None, description="ONNX model; default: the shipped one")
    window_frames: int = Field(default=30, ge=2, le=300, description="frames per decision")
    min_confidence: float | None = Field(
        default=None, ge=0.0, le=1.0, description="default: the model's validated threshold"
    )
    min_visible: float = Field(
        default=0.6, ge=0.0, le=1.0, description="share of joints seen to try classifying"
    )
    accuracy: float = Field(default=0.95, ge=0.0, le=1.0, description="oracle backend only")
    fall_detection: bool = Field(default=True, description="watch everyone in view for falls")
    fall_period_s: float = Field(default=0.5, gt=0.0, description="s between fall checks")
    pose: PoseSection = Field(default_factory=PoseSection)
