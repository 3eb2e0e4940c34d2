"""``amiro perception bench-camera``: every path timed, stand-ins said to be stand-ins."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from amiro.cli import main
from amiro.perception.onnx_standins import standin_yolo


def test_bench_camera_times_every_path(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["perception", "bench-camera", "--repeats", "1", "--scenes", "5", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    for key in ("hog_ms_per_frame", "onnx_ms_per_frame", "pose_ms_per_frame"):
        assert report[key] > 0
    assert report["image"] == [640, 480]
    assert report["onnx_model"].startswith("stand-in") and "GFLOPs" in report["pose_model"]
    ideal, hog = report["placement_mae_m"]["ideal_boxes"], report["placement_mae_m"]["hog"]
    assert ideal["scenes"] == ideal["found"] == 5 and max(ideal["x"], ideal["y"], ideal["z"]) < 0.2
    assert hog["scenes"] == 5 and 0 <= hog["found"] <= 5


def test_bad_arguments_exit_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["perception", "bench-camera", "--repeats", "0"]) == 2
    assert main(["perception", "bench-camera", "--model", "/no/such.onnx"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [
        "amiro: error: --repeats and --scenes must be at least 1",
        "amiro: error: /no/such.onnx: no such model file",
    ]


def test_standin_size_follows_its_width(tmp_path: Path) -> None:
    rng = np.random.default_rng(0)
    _, narrow = standin_yolo(tmp_path / "a.onnx", 85, rng, size=64)
    _, wide = standin_yolo(tmp_path / "b.onnx", 85, rng, size=64, width=2.0)
    assert 3.5 < wide / narrow < 4.1  # the cost grows with the square of the channels
