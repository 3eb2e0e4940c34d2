"""Real Kinect v1 skeleton sets onto NTU-25: synthetic snippets in each layout, one real file."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from amiro.activity.augment import mirror
from amiro.activity.kinect_v1 import LAYOUTS, NECK_SHARE, resample_rate, to_ntu
from amiro.activity.motion import FPS, Body, View, perform, to_camera
from amiro.activity.real_sets import read_cad60, read_citi, read_florence, read_kard
from amiro.activity.skeleton import J, visible
from amiro.core.config import ConfigError


def _truth(seed: int = 0, frames: int = 20) -> np.ndarray:
    """An NTU-25 performance in Kinect space (metres), the source of every snippet."""
    rng = np.random.default_rng(seed)
    body = Body.random(rng)
    clips = [perform("drink_water", body, rng)]
    while sum(len(c) for c in clips) < frames:
        clips.append(perform("drink_water", body, rng))
    out: np.ndarray = to_camera(np.concatenate(clips), View())[:frames]
    return out


def _write_text(path: Path, raw_mm: np.ndarray) -> None:
    path.write_text(
        "\n".join(" ".join(f"{v:.4f}" for v in joint) for joint in raw_mm.reshape(-1, 3))
    )


def test_tracked_joints_keep_their_place_and_the_missing_ones_are_derived_or_unseen() -> None:
    truth = _truth()
    layout = LAYOUTS["florence3d"]
    mapped = to_ntu(truth[:, [J[n] for n in layout]] * 1000.0, "florence3d", 1e-3)
    for name in layout:
        np.testing.assert_allclose(mapped.frames[:, J[name]], truth[:, J[name]], atol=1e-9)
    base = (truth[:, J["HipLeft"]] + truth[:, J["HipRight"]]) / 2
    np.testing.assert_allclose(mapped.frames[:, J["SpineBase"]], base, atol=1e-9)
    neck = mapped.frames[:, J["Neck"]]
    expected = truth[:, J["SpineShoulder"]] + NECK_SHARE * (
        truth[:, J["Head"]] - truth[:, J["SpineShoulder"]]
    )
    np.testing.assert_allclose(neck, expected, atol=1e-9)
    hand_dir = mapped.frames[:, J["HandRight"]] - mapped.frames[:, J["WristRight"]]
    fore_dir = truth[:, J["WristRight"]] - truth[:, J["ElbowRight"]]
    assert np.all(np.sum(hand_dir * fore_dir, axis=1) > 0)  # the hand beyond the wrist
    assert set(np.flatnonzero(mapped.derived)) == {
        J[n] for n in ("SpineBase", "Neck", "HandLeft", "HandRight")
    }
    seen = visible(mapped.frames)
    for name in ("HandTipLeft", "ThumbRight", "FootLeft", "FootRight"):
        assert not seen[:, J[name]].any()


def test_a_wrong_layout_or_shape_is_a_config_error() -> None:
    with pytest.raises(ConfigError):
        to_ntu(np.zeros((3, 15, 3)), "kinect9")
    with pytest.raises(ConfigError):
        to_ntu(np.zeros((3, 19, 3)), "kard")


def test_resampling_30_hz_to_the_model_rate_keeps_the_duration() -> None:
    frames = np.arange(61, dtype=float)[:, None, None] * np.ones((1, 25, 3))
    out = resample_rate(frames, 30.0, FPS)
    assert len(out) == int(2.0 * FPS) + 1
    np.testing.assert_array_equal(out[:, 0, 0], np.arange(0, 61, 30.0 / FPS))


def test_kard_files_in_mm_with_x_to_the_right_come_out_in_kinect_metres(tmp_path: Path) -> None:
    truth = _truth(1, 20)
    raw = truth[:, [J[n] for n in LAYOUTS["kard"]]] * np.array([-1000.0, 1000.0, 1000.0])
    _write_text(tmp_path / "a16_s03_e02_realworld.txt", raw)
    (clip,) = read_kard(tmp_path)
    assert (clip.subject, clip.action, clip.label) == (3, 16, "drink_water")
    assert len(clip.frames) == 10  # 20 frames at 30 Hz are 10 at 15 Hz
    np.testing.assert_allclose(
        clip.frames[:, J["HandRight"]], truth[::2, J["HandRight"]], atol=1e-6
    )


def test_florence_files_of_other_actions_are_unknown(tmp_path: Path) -> None:
    truth = _truth(2, 12)
    _write_text(
        tmp_path / "a04_s7_id100.txt", truth[:, [J[n] for n in LAYOUTS["florence3d"]]] * 1e3
    )
    (clip,) = read_florence(tmp_path)
    assert (clip.subject, clip.action, clip.label) == (7, 4, None)


def test_citi_up_axis_and_cad60_mirroring_are_undone(tmp_path: Path) -> None:
    truth = _truth(3, 100)
    raw = truth[:, [J[n] for n in LAYOUTS["citi"]]]
    citi = np.stack([raw[..., 0], raw[..., 2], raw[..., 1]], axis=-1)  # x, depth, up
    (tmp_path / "citi_data").mkdir()
    (tmp_path / "citi_labels").mkdir()
    np.save(tmp_path / "citi_data" / "citi_data_0001.npy", citi.reshape(100, 57))
    np.save(tmp_path / "citi_labels" / "action_labels.npy", np.array([[14]], np.uint8))
    np.save(tmp_path / "citi_labels" / "subject_labels.npy", np.array([[5]], np.uint8))
    (clip,) = read_citi(tmp_path)
    assert clip.label == "hand_waving" and clip.subject == 5
    np.testing.assert_allclose(clip.frames[:, J["Head"]], truth[::2, J["Head"]], atol=1e-9)

    seen = mirror(truth[:60])  # what CAD-60's NITE records of this performance
    cad = seen[:, [J[n] for n in LAYOUTS["cad60"]]] * 1e3
    np.savez(
        tmp_path / "cad.npz",
        frames=cad.astype(np.float32),
        seg_start=np.array([30, 0]),
        seg_len=np.array([30, 30]),
        label=np.array([4, 4]),
        person=np.array([2, 2]),
        segment_index=np.array([2, 1]),
    )
    (clip,) = read_cad60(tmp_path / "cad.npz")
    assert (clip.subject, clip.label, len(clip.frames)) == (2, "drink_water", 30)
    np.testing.assert_allclose(
        clip.frames[:, J["ElbowRight"]], truth[:60:2, J["ElbowRight"]], atol=1e-5
    )


def test_a_real_kard_recording_reads_as_an_upright_person_facing_the_sensor(
    real_har: Path,
) -> None:
    clips = read_kard(real_har / "kard" / "kard_realworld")
    assert len(clips) == 540
    drink = next(c for c in clips if c.label == "drink_water")
    f = drink.frames
    assert np.all(f[:, J["Head"], 1] > f[:, J["SpineBase"], 1] + 0.4)  # y up, metres
    assert np.all((f[:, J["SpineBase"], 2] > 1.0) & (f[:, J["SpineBase"], 2] < 5.0))
    across = f[:, J["ShoulderRight"], 0] - f[:, J["ShoulderLeft"], 0]
    assert np.median(across) > 0.2  # Kinect space: the right shoulder on +x
