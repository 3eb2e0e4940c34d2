"""The ``activity:`` section of the system configuration."""

from __future__ import annotations

from pathlib import Path
from typing import Literal

from pydantic import Field

from amiro.core.config import Section


class ActivityConfig(Section):
    backend: Literal["onnx", "oracle"] = "onnx"
    model: Path | None = Field(default=None, description="ONNX model; default: the shipped one")
    window_frames: int = Field(default=30, ge=2, le=300, description="frames per decision")
    min_confidence: float = Field(default=0.5, ge=0.0, le=1.0)
    min_visible: float = Field(
        default=0.6, ge=0.0, le=1.0, description="share of joints seen to try classifying"
    )
    accuracy: float = Field(default=0.95, ge=0.0, le=1.0, description="oracle backend only")
    fall_detection: bool = Field(default=True, description="watch everyone in view for falls")
    fall_period_s: float = Field(default=0.5, gt=0.0, description="s between fall checks")
