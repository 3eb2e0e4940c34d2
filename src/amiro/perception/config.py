"""Configuration of the perception module (the ``perception:`` section)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Literal

from pydantic import Field, model_validator

from amiro.core.config import Section
from amiro.core.registry import backend_name
from amiro.perception import backends as _backends  # noqa: F401 - registers the names


class SimDetectorSection(Section):
    """Error profile of the simulator's person detector, fitted to the paper's Tables 11–13."""

    error_rate: dict[str, float] = Field(
        default_factory=lambda: {
            "standing": 0.0,
            "sitting_desk": 0.10,
            "sitting_couch": 0.03,
            "lying_couch": 0.78,
        },
        description="counting errors per person at the mean distance, by posture",
    )
    duplicate_share: float = Field(default=0.3, ge=0.0, le=1.0)
    false_positives_per_frame: float = Field(default=0.005, ge=0.0)
    box_jitter: float = Field(default=0.03, ge=0.0, description="sigma, fraction of box size")
    # Household objects: the paper measured people only, so these are plausible figures
    # for a COCO-trained detector, not the paper's.
    object_recall: dict[str, float] = Field(
        default_factory=lambda: {
            "cup": 0.6,
            "bottle": 0.7,
            "chair": 0.9,
            "couch": 0.95,
            "bed": 0.95,
            "dining table": 0.8,
        },
        description="share of objects found at 2 m, by label",
    )
    object_recall_loss_per_m: float = Field(default=0.1, ge=0.0, description="beyond 2 m")
    min_object_px: float = Field(default=8.0, ge=0.0, description="smaller boxes are missed")


class FaceSection(Section):
    backend: Annotated[str, backend_name("faces")] = Field(
        default="sim", description="sim: the simulator's error model; dlib: face_recognition"
    )
    threshold: float = Field(default=0.6, gt=0.0, description="max embedding distance to match")
    recognise_rate: float = Field(default=0.95, ge=0.0, le=1.0, description="sim, at 1 m")
    rate_loss_per_m: float = Field(default=0.04, ge=0.0)
    confusion_rate: float = Field(default=0.01, ge=0.0, le=1.0)
    backlit_rate: float = Field(default=0.0, ge=0.0, le=1.0, description="sim, facing light")
    gallery: dict[str, list[Path]] = Field(
        default_factory=dict, description="dlib: name -> face images to enrol"
    )


class TrackingSection(Section):
    gate_m: float = Field(default=0.8, gt=0.0)
    forget_s: float = Field(default=3.0, gt=0.0)
    smoothing: float = Field(default=0.5, gt=0.0, le=1.0)


class CameraSection(Section):
    """The ``camera`` backend: a real RGB-D camera's bus topics (the robot port) and where the
    camera sits.  Without head joints on ``/joint_states`` the camera is fixed at
    ``yaw``/``pitch`` on the base (a fixed extrinsic)."""

    detector: Annotated[str, backend_name("detector")] = Field(
        default="hog", description="hog: OpenCV's people detector; onnx: a YOLO-layout model"
    )
    model: Path | None = Field(default=None, description="onnx: the detector's model file")
    min_score: float = Field(default=0.5, ge=0.0, le=1.0, description="person boxes kept")
    mount_height: float = Field(default=1.15, gt=0.0, description="m above the floor")
    mount_forward: float = Field(default=0.08, description="m ahead of the base centre")
    yaw: float = Field(default=0.0, description="rad, fixed camera, or before joints arrive")
    pitch: float = Field(default=0.0, description="rad down, fixed camera, or before joints")
    head_joints: bool = Field(default=True, description="follow HeadYaw/HeadPitch joint states")
    max_skew_s: float = Field(default=0.1, gt=0.0, description="RGB-depth pairing, s")
    max_age_s: float = Field(default=1.0, gt=0.0, description="older frames are not looked at")

    @model_validator(mode="after")
    def _model_for_onnx(self) -> CameraSection:
        if self.detector == "onnx" and self.model is None:
            raise ValueError("detector onnx needs model: the path of a YOLO-layout ONNX file")
        return self


class PerceptionConfig(Section):
    backend: Annotated[str, backend_name("perception")] = Field(
        default="sim",
        description="sim: simulated detector + faces + estimator + tracker; oracle: ground "
        "truth; camera: the robot's RGB-D camera topics",
    )
    estimator: Literal["improved", "paper"] = "improved"
    objects_file: Path | None = Field(
        default=None, description="small household objects per home; default: amiro's own"
    )
    position_noise_m: float = Field(default=0.1, ge=0.0, description="oracle backend only")
    detector: SimDetectorSection = Field(default_factory=SimDetectorSection)
    faces: FaceSection = Field(default_factory=FaceSection)
    tracking: TrackingSection = Field(default_factory=TrackingSection)
    camera: CameraSection = Field(default_factory=CameraSection)
