"""The ONNX detector on tiny models built here with YOLOv5's layout: input (1, 3, S, S),
output (1, N, 5 + C) rows of centre, size (input pixels), objectness and class scores.

The models answer fixed rows whatever the image, so every step after inference is checked
against known numbers: letterbox undone to image pixels, low scores dropped, class index
to label, and non-maximum suppression per class.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt
import onnx
import pytest
from onnx import TensorProto, helper, numpy_helper

from amiro.core.config import ConfigError
from amiro.core.vision import letterbox
from amiro.perception.onnx_yolo import YoloOnnxDetector, coco_labels
from amiro.perception.ports import Frame

PERSON, BOTTLE, CUP, COUCH = 0, 39, 41, 57


def yolo_model(path: Path, rows: npt.NDArray[np.float32], size: int | str = 320) -> Path:
    """An ONNX model with YOLOv5's input and output that always answers ``rows``."""
    answer = numpy_helper.from_array(rows[None].astype(np.float32), "answer")
    graph = helper.make_graph(
        [helper.make_node("Identity", ["answer"], ["output0"])],
        "fixed_yolo",
        [helper.make_tensor_value_info("images", TensorProto.FLOAT, [1, 3, size, size])],
        [helper.make_tensor_value_info("output0", TensorProto.FLOAT, [1, *rows.shape])],
        initializer=[answer],
    )
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 13)])
    model.ir_version = 8
    onnx.checker.check_model(model)
    onnx.save(model, path)
    return path


def row(
    cx: float, cy: float, w: float, h: float, objectness: float, cls: int, p: float
) -> npt.NDArray[np.float32]:
    """One output row of an 80-class (COCO) model."""
    r = np.zeros(85, dtype=np.float32)
    r[:5] = cx, cy, w, h, objectness
    r[5 + cls] = p
    return r


FRAME = Frame(rgb=np.zeros((480, 640, 3), dtype=np.uint8))  # letterboxed: scale 0.5, 40 px bands


@pytest.fixture
def detector(tmp_path: Path) -> YoloOnnxDetector:
    rows = np.stack(
        [
            row(160, 100, 50, 80, 0.9, PERSON, 0.9),  # score 0.81
            row(165, 102, 50, 80, 0.8, PERSON, 0.9),  # overlaps the first, lower: suppressed
            row(160, 100, 50, 80, 0.9, CUP, 0.8),  # same place, other class: kept
            row(250, 200, 20, 40, 0.2, BOTTLE, 0.9),  # score 0.18 < 0.25: dropped
            row(80, 250, 120, 60, 0.95, COUCH, 0.9),
        ]
    )
    return YoloOnnxDetector(yolo_model(tmp_path / "tiny.onnx", rows))


def test_boxes_labels_scores_and_suppression(detector: YoloOnnxDetector) -> None:
    found = {d.label: d for d in detector.detect(FRAME)}
    assert sorted(found) == ["couch", "cup", "person"]
    person = found["person"]
    assert person.score == pytest.approx(0.81, abs=1e-6)
    box = person.bbox
    assert [box.cx, box.cy, box.width, box.height] == pytest.approx([320, 120, 100, 160])
    couch = found["couch"].bbox
    assert (couch.cx, couch.cy, couch.width, couch.height) == pytest.approx((160, 420, 240, 120))
    assert found["cup"].score == pytest.approx(0.72, abs=1e-6)


def test_letterbox_keeps_the_aspect_and_pads_grey(detector: YoloOnnxDetector) -> None:
    red = np.zeros((480, 640, 3), dtype=np.uint8)
    red[..., 0] = 255
    blob, scale, dx, dy = letterbox(red, detector.size)
    assert blob.shape == (1, 3, 320, 320) and (scale, dx, dy) == (0.5, 0.0, 40.0)
    assert blob[0, :, :40].max() == blob[0, :, 280:].min() == pytest.approx(114 / 255)
    assert blob[0, 0, 40:280].min() == 1.0 and blob[0, 1:, 40:280].max() == 0.0


def test_custom_labels_and_portrait_images(tmp_path: Path) -> None:
    rows = np.array([[100, 160, 40, 100, 1.0, 0.1, 0.9]], dtype=np.float32)
    model = yolo_model(tmp_path / "two.onnx", rows, size=320)
    det = YoloOnnxDetector(model, labels=["person", "walker"])
    # a 480 x 640 portrait image: scale 0.5, bands of 40 px left and right
    (found,) = det.detect(Frame(rgb=np.zeros((640, 480, 3), dtype=np.uint8)))
    assert found.label == "walker" and found.score == pytest.approx(0.9)
    assert (found.bbox.cx, found.bbox.cy) == pytest.approx((120, 320))
    coco_sized = yolo_model(tmp_path / "coco.onnx", np.zeros((1, 85), np.float32))
    with pytest.raises(ValueError, match="85 columns, expected 7"):
        YoloOnnxDetector(coco_sized, labels=["a", "b"]).detect(FRAME)


def test_no_boxes_above_the_threshold(tmp_path: Path) -> None:
    rows = np.stack([row(100, 100, 10, 10, 0.1, PERSON, 0.5)])
    assert YoloOnnxDetector(yolo_model(tmp_path / "low.onnx", rows)).detect(FRAME) == []


def test_bad_model_files_are_one_line_errors(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="no such model file"):
        YoloOnnxDetector(tmp_path / "missing.onnx")
    junk = tmp_path / "junk.onnx"
    junk.write_bytes(b"not a model")
    with pytest.raises(ConfigError, match="not a usable ONNX model"):
        YoloOnnxDetector(junk)


def test_ships_the_coco_names() -> None:
    labels = coco_labels()
    assert len(labels) == 80
    assert [labels[i] for i in (PERSON, BOTTLE, CUP, COUCH)] == ["person", "bottle", "cup", "couch"]
