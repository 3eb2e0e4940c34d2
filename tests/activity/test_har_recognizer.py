import numpy as np

from amiro.activity.dataset import subject_body, window
from amiro.activity.onnx_model import ActivityModel
from amiro.activity.recognizer import SkeletonActivityRecognizer


class FakeSource:
    def __init__(self, frames: np.ndarray | None) -> None:
        self.frames = frames

    def window(self, person: str, frames: int) -> np.ndarray | None:
        return None if self.frames is None else self.frames[-frames:]

    def framing(self, person: str) -> tuple[float, bool] | None:
        return (0.95, True) if self.frames is not None else None


def test_incomplete_or_unseen_skeletons_give_no_label(tiny_model: ActivityModel) -> None:
    frames = window("drink_water", subject_body(0, 0), 0.0, np.random.default_rng(0))
    hidden = frames.copy()
    hidden[:, 4:] = np.nan
    reading = SkeletonActivityRecognizer(FakeSource(hidden), tiny_model).observe("maria")
    assert reading.label is None and not reading.skeleton_complete
    assert reading.box_height_fraction == 0.95 and reading.clipped
    assert (
        not SkeletonActivityRecognizer(FakeSource(None), tiny_model).observe("x").skeleton_complete
    )


def test_complete_skeleton_is_classified(tiny_model: ActivityModel) -> None:
    frames = window("typing", subject_body(0, 0), 0.0, np.random.default_rng(1))
    rec = SkeletonActivityRecognizer(FakeSource(frames), tiny_model, min_confidence=0.0)
    reading = rec.observe("maria")
    assert reading.skeleton_complete and reading.label in tiny_model.classes
    assert rec.box_range == tiny_model.info.box_height_fraction
