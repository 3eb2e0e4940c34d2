from pathlib import Path

import numpy as np
import pytest

from amiro.activity.augment import drop_joints, occlude, time_warp
from amiro.activity.bench import run_bench
from amiro.activity.dataset import subject_body, window
from amiro.activity.labels import ACTIONS
from amiro.activity.onnx_model import ActivityModel, shipped_model_path
from amiro.activity.skeleton import visible
from amiro.core.config import ConfigError


def test_streaming_matches_the_window_frame_for_frame(tiny_model: ActivityModel) -> None:
    rng = np.random.default_rng(0)
    frames = drop_joints(window("typing", subject_body(1, 0), 0.0, rng), 0.2, rng)
    stream = tiny_model.stream()
    for n, frame in enumerate(frames[:12], start=1):
        np.testing.assert_allclose(stream.push(frame), tiny_model.classify(frames[:n]), atol=1e-5)
    stream.reset()
    assert stream.frames == 0


def test_exported_model_carries_its_metadata(tiny_model: ActivityModel) -> None:
    assert tiny_model.classes == ACTIONS
    low, high = tiny_model.info.box_height_fraction
    assert 0 < low < high < 1
    probs = tiny_model.classify_batch(
        np.stack(
            [window(a, subject_body(2, 0), 30.0, np.random.default_rng(1)) for a in ACTIONS[:3]]
        )
    )
    assert probs.shape == (3, len(ACTIONS))
    np.testing.assert_allclose(probs.sum(axis=1), 1.0, atol=1e-5)


def test_augmentation_hides_joints_as_asked() -> None:
    rng = np.random.default_rng(2)
    frames = window("pointing", subject_body(3, 0), 0.0, rng)
    dropped = drop_joints(frames, 0.3, rng)
    assert (~visible(dropped)).sum(axis=1).tolist() == [8] * len(frames)
    assert np.isnan(occlude(frames, rng)).any()


def test_time_warp_plays_the_motion_faster_or_slower() -> None:
    rng = np.random.default_rng(3)
    frames = window("hand_waving", subject_body(3, 0), 0.0, rng)  # 40 frames
    same = time_warp(frames, 40, 1.0, rng)
    np.testing.assert_allclose(same, frames)
    fast = time_warp(frames, 20, 2.0, rng)  # 40 source frames in 20: every other one
    np.testing.assert_allclose(fast[[0, -1]], frames[[0, -1]])
    slow = time_warp(frames[:10], 19, 0.5, rng)  # 9 intervals in 18: midpoints between
    np.testing.assert_allclose(slow[1], (frames[0] + frames[1]) / 2)
    assert time_warp(frames, 16, 1.4, rng).shape == (16, 25, 3)


def test_bench_reports_every_length(tiny_model: ActivityModel) -> None:
    report = run_bench(tiny_model, iterations=2, repeats=1)
    assert list(report["lengths"]) == ["5", "10", "15", "20", "25", "30", "60"]
    assert all(v > 0 for v in report["lengths"].values()) and report["stream_ms_per_frame"] > 0


def test_bad_model_files_are_config_errors(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="no such"):
        ActivityModel(tmp_path / "none.onnx")
    junk = tmp_path / "junk.onnx"
    junk.write_bytes(b"not onnx")
    with pytest.raises(ConfigError, match="not an amiro activity model"):
        ActivityModel(junk)


def test_the_shipped_model_is_small_and_loads() -> None:
    path = shipped_model_path()
    assert path.stat().st_size < 5_000_000
    assert ActivityModel(path).classes == ACTIONS
