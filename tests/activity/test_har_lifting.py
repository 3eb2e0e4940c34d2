import numpy as np
import pytest

from amiro.activity.dataset import subject_body
from amiro.activity.lifting import lift_frame, lift_sequence, nearest_in_time, resample
from amiro.activity.motion import View, perform, to_camera
from amiro.activity.render import depth_image, project
from amiro.activity.skeleton import J
from amiro.core.config import ConfigError
from amiro.robot.camera import Camera

INFO = Camera().info(0.0)


def _skeletons() -> np.ndarray:
    rng = np.random.default_rng(0)
    body_frames = perform("hand_waving", subject_body(0, 0), rng, sitting=False)
    return to_camera(body_frames, View(distance=3.0, height=1.0))


def _render(joints: np.ndarray, scale: float) -> tuple[np.ndarray, np.ndarray]:
    """Pixels of Kinect-space joints, and the depth image (``scale`` x RGB resolution)."""
    return project(joints, INFO), depth_image(joints, INFO, scale)


@pytest.mark.parametrize("scale", [1.0, 0.5])
def test_lifting_recovers_the_joints_with_registered_depth(scale: float) -> None:
    joints = _skeletons()[10]
    pixels, depth = _render(joints, scale)
    lifted = lift_frame(pixels, depth, INFO)
    np.testing.assert_allclose(lifted, joints, atol=0.02)


def test_background_depth_and_holes_leave_the_joint_unseen() -> None:
    joints = _skeletons()[10]
    pixels, depth = _render(joints, 1.0)
    hand = J["HandTipRight"]
    pixels[hand] += 40.0  # off the body: the patch sees the wall 3 m behind
    u, v = pixels[J["KneeLeft"]].astype(int)
    depth[v - 6 : v + 7, u - 6 : u + 7] = 0.0  # no reading at all
    lifted = lift_frame(pixels, depth, INFO)
    assert np.isnan(lifted[[hand, J["KneeLeft"]]]).all()
    assert np.isfinite(np.delete(lifted, [hand, J["KneeLeft"]], axis=0)).all()


def test_rgb_frames_take_the_nearest_depth_frame_within_the_skew() -> None:
    rgb = np.arange(8) / 30.0
    depth = np.array([0.0, 1.0, 2.0, 3.0]) / 15.0 + 0.01
    np.testing.assert_array_equal(nearest_in_time(rgb, depth, 0.04), [0, 0, 1, 1, 2, 2, 3, 3])
    late = np.array([0.5])
    assert nearest_in_time(late, depth, 0.04).tolist() == [-1]
    assert nearest_in_time(rgb, np.array([]), 1.0).tolist() == [-1] * 8
    with pytest.raises(ConfigError, match="increasing"):
        nearest_in_time(rgb, depth[::-1], 0.1)


def test_a_30_hz_rgb_stream_lifts_with_15_hz_depth_and_resamples_to_15_hz() -> None:
    seq = _skeletons()[:12]
    rgb_stamps = np.arange(12) / 30.0
    rendered = [_render(f, 0.5) for f in seq]
    pixels = np.stack([p for p, _ in rendered])
    depth_idx = list(range(0, 10, 2))  # 15 Hz depth; no depth after frame 9 (stream stopped)
    depths = [rendered[i][1] for i in depth_idx]
    lifted = lift_sequence(pixels, rgb_stamps, depths, rgb_stamps[depth_idx], INFO)
    # at half resolution the wrist patch also sees the hand, 6 cm nearer
    np.testing.assert_allclose(lifted[::2][:5], seq[::2][:5], atol=0.06)
    assert np.isnan(lifted[11]).all() and np.isfinite(lifted[9]).any()
    at_15 = resample(lifted, rgb_stamps, 15.0)
    assert len(at_15) == 6
    np.testing.assert_array_equal(at_15[:5], lifted[0:10:2])
    with pytest.raises(ConfigError, match="depth images"):
        lift_sequence(pixels, rgb_stamps, depths[:2], rgb_stamps[depth_idx], INFO)
