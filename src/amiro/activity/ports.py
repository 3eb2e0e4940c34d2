"""The activity-recognition port the RecognizeActivity task uses."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol


@dataclass(frozen=True)
class ActivityReading:
    """The activity seen now (None when nothing could be classified) and why."""

    label: str | None
    confidence: float
    skeleton_complete: bool


class ActivityRecognizer(Protocol):
    def observe(self, person: str) -> ActivityReading: ...
