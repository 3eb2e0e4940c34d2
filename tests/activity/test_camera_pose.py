"""The ONNX pose estimator on tiny YOLO-pose-layout models built here, and COCO-17 keypoints
in the NTU layout.

The models answer fixed rows whatever the image, so decoding is checked against known
numbers: both output orientations, letterbox undone, low scores dropped, overlapping
people suppressed, a wrong output width refused.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

from amiro.activity.dataset import subject_body, window
from amiro.activity.keypoints import COCO_17, to_ntu
from amiro.activity.labels import ACTIONS
from amiro.activity.onnx_model import ActivityModel
from amiro.activity.pose import PoseOnnxEstimator
from amiro.activity.render import through_pose_estimator
from amiro.activity.skeleton import JOINTS, J
from amiro.core.config import ConfigError
from amiro.perception.onnx_standins import fixed_answer_model
from amiro.robot.camera import Camera

IMAGE = np.zeros((480, 640, 3), dtype=np.uint8)  # a 320 model: half scale, 40 px bands


def pose_row(
    cx: float, cy: float, w: float, h: float, score: float, keypoints: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """One candidate in input (letterboxed) pixels: box, score, 17 x (x, y, confidence)."""
    return np.concatenate([[cx, cy, w, h, score], keypoints.ravel()])


def keypoints_at(u0: float, v0: float, conf: float = 0.9) -> npt.NDArray[np.float64]:
    k = np.zeros((17, 3))
    k[:, 0] = u0 + np.arange(17)
    k[:, 1] = v0 + 2 * np.arange(17)
    k[:, 2] = conf
    return k


@pytest.mark.parametrize("channels_first", [True, False])
def test_people_boxes_and_keypoints_in_image_pixels(tmp_path: Path, channels_first: bool) -> None:
    rows = np.stack(
        [
            pose_row(100, 120, 40, 100, 0.9, keypoints_at(90, 80)),
            pose_row(102, 121, 40, 100, 0.8, keypoints_at(91, 80)),  # the same person: dropped
            pose_row(250, 150, 30, 90, 0.7, keypoints_at(240, 110)),
            pose_row(200, 200, 30, 90, 0.3, keypoints_at(200, 160)),  # under min_score
        ]
    )
    model = fixed_answer_model(tmp_path / "pose.onnx", rows, channels_first=channels_first)
    people = PoseOnnxEstimator(model, "coco17", min_score=0.5).estimate(IMAGE)
    assert [p.score for p in people] == pytest.approx([0.9, 0.7])
    first = people[0]
    assert (first.box.cx, first.box.cy, first.box.width, first.box.height) == pytest.approx(
        (200.0, 160.0, 80.0, 200.0)
    )
    assert first.keypoints.shape == (17, 3)
    np.testing.assert_allclose(first.keypoints[0], [180.0, 80.0, 0.9], rtol=1e-6)
    np.testing.assert_allclose(first.keypoints[16], [212.0, 144.0, 0.9], rtol=1e-6)


def test_a_model_of_another_layout_is_refused(tmp_path: Path) -> None:
    rows = np.zeros((3, 5 + 3 * 25))  # BODY_25 rows read as COCO-17
    with pytest.raises(ConfigError, match=r"expected \(1, 56, N\)"):
        PoseOnnxEstimator(fixed_answer_model(tmp_path / "p.onnx", rows), "coco17")
    with pytest.raises(ConfigError, match="unknown keypoint format 'h36m'"):
        PoseOnnxEstimator(tmp_path / "p.onnx", "h36m")
    with pytest.raises(ConfigError, match="no such model"):
        PoseOnnxEstimator(tmp_path / "missing.onnx")


def test_coco_fills_every_joint_but_the_feet() -> None:
    k = np.zeros((1, 17, 3))
    k[0, :, 0] = np.arange(17) * 10.0
    k[0, :, 1] = 100.0
    k[0, :, 2] = 1.0
    ntu = to_ntu(k, "coco17")[0]
    missing = [JOINTS[j] for j in range(25) if np.isnan(ntu[j]).any()]
    assert missing == ["FootLeft", "FootRight"]
    index = {name: i for i, name in enumerate(COCO_17)}
    assert ntu[J["WristLeft"], 0] == 10.0 * index["left_wrist"]
    assert ntu[J["SpineBase"], 0] == 5.0 * (index["left_hip"] + index["right_hip"])
    k[0, index["left_elbow"], 2] = 0.1  # an unsure elbow: no elbow, and no hand past it
    lost = [JOINTS[j] for j in range(25) if np.isnan(to_ntu(k, "coco17")[0, j]).any()]
    assert set(lost) == {"FootLeft", "FootRight", "ElbowLeft", "HandLeft", "HandTipLeft",
                         "ThumbLeft"}  # fmt: skip


def test_the_shipped_model_classifies_skeletons_rebuilt_from_coco_keypoints() -> None:
    """The camera-onnx path on a head pitched 0.2 rad down: COCO-17 keypoints (no feet),
    lifted with the depth image and levelled again."""
    model = ActivityModel()
    info = Camera().info(0.0)
    rng = np.random.default_rng(4)
    windows = [window(a, subject_body(7, 0), 0.0, rng, 30) for a in ACTIONS]
    rebuilt = [through_pose_estimator(w, info, "coco17", pitch=0.2) for w in windows]
    assert all(np.isnan(r[:, [J["FootLeft"], J["FootRight"]]]).all() for r in rebuilt)
    error = np.nanmedian(np.linalg.norm(np.stack(rebuilt) - np.stack(windows), axis=-1))
    assert error < 0.05  # levelled back into the model's view
    predicted = [model.classes[int(model.classify(r).argmax())] for r in rebuilt]
    assert sum(p == a for p, a in zip(predicted, ACTIONS, strict=True)) >= 7
