"""The model-backed activity recogniser: a skeleton stream in, an ActivityReading out."""

from __future__ import annotations

from typing import Protocol

from amiro.activity.onnx_model import ActivityModel
from amiro.activity.ports import ActivityReading
from amiro.activity.posture import FallLatch
from amiro.activity.skeleton import FloatArray, visible


class SkeletonSource(Protocol):
    """Where skeletons come from: the simulator, or a pose estimator on the robot's camera."""

    def window(self, person: str, frames: int) -> FloatArray | None:
        """The person's last ``frames`` skeletons (Kinect space, NaN unseen); None if unseen."""
        ...

    def framing(self, person: str) -> tuple[float, bool] | None:
        """(box height / image height, box clipped by the image edge), None if unseen."""
        ...


class SkeletonActivityRecognizer:
    """Classifies the last ``window_frames`` skeletons of a person with the ONNX model.

    Too few joints seen (``min_visible``) reports an incomplete skeleton instead of a guess;
    the ``unknown`` outcome, or a winning class below ``min_confidence`` (default: the
    model's validated threshold), reports no label; "falling" needs a body ending flat,
    and holds while it stays down (:class:`amiro.activity.posture.FallLatch`).
    """

    def __init__(
        self,
        source: SkeletonSource,
        model: ActivityModel,
        window_frames: int = 30,
        min_confidence: float | None = None,
        min_visible: float = 0.6,
    ) -> None:
        self.source = source
        self.model = model
        self.window_frames = window_frames
        self.min_confidence = min_confidence
        self.min_visible = min_visible
        self.box_range: tuple[float, float] | None = model.info.box_height_fraction
        self.falls = FallLatch()

    def observe(self, person: str) -> ActivityReading:
        framing = self.source.framing(person)
        box, clipped = framing if framing is not None else (None, False)
        frames = self.source.window(person, self.window_frames)
        if frames is None or float(visible(frames).mean()) < self.min_visible:
            return ActivityReading(None, 0.0, False, box, clipped)
        label, confidence = self.model.decide(self.model.classify(frames), self.min_confidence)
        label = self.falls(person, label, frames)
        return ActivityReading(label, confidence, True, box, clipped)
