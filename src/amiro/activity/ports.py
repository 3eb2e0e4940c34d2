"""The activity-recognition port the RecognizeActivity task uses."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol


@dataclass(frozen=True)
class ActivityReading:
    """The activity seen now (None when nothing could be classified) and why.

    ``box_height_fraction`` is the share of the image height the person's box fills (None
    when unknown); ``clipped`` says the box touches the image's top or bottom edge.
    """

    label: str | None
    confidence: float
    skeleton_complete: bool
    box_height_fraction: float | None = None
    clipped: bool = False


class ActivityRecognizer(Protocol):
    # The box-height range the model was trained on, or None when framing does not matter.
    box_range: tuple[float, float] | None

    def observe(self, person: str) -> ActivityReading: ...
