"""``behavior.planner``'s planning settings, apart from the planners so that reading a config
does not load unified-planning."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from amiro.core.config import Section

Engine = Literal["kairos", "pyperplan", "fast-downward"]


class PlanningConfig(Section):
    engine: Engine = "kairos"
    temporal: bool = Field(default=False, description="durative actions (engine kairos)")
    timeout_s: float = Field(default=10.0, gt=0.0)
    speed_mps: float = Field(default=0.35, gt=0.0, description="for durations from distances")
    max_replans: int = Field(default=6, ge=0)

    @model_validator(mode="after")
    def _temporal_engine(self) -> PlanningConfig:
        if self.temporal and self.engine != "kairos":
            raise ValueError(f"temporal planning needs engine kairos, not {self.engine}")
        return self
