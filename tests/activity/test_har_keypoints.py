import numpy as np
import pytest

from amiro.activity.keypoints import BLAZEPOSE_33, BODY_25, to_ntu
from amiro.activity.render import body25_keypoints
from amiro.activity.skeleton import J
from amiro.core.config import ConfigError


def _ntu_pixels(frames: int = 3) -> np.ndarray:
    rng = np.random.default_rng(0)
    return rng.uniform(50.0, 400.0, (frames, 25, 2))


def _body25_from(ntu: np.ndarray) -> np.ndarray:
    """BODY_25 keypoints placed where the NTU joints are (ears/eyes/nose at the head)."""
    return body25_keypoints(ntu, 10_000, 10_000)


def test_openpose_joints_land_on_their_ntu_places() -> None:
    ntu = _ntu_pixels()
    mapped = to_ntu(_body25_from(ntu), "openpose_body25")
    direct = [J[n] for n in ("SpineBase", "SpineShoulder", "Head", "ElbowLeft", "KneeRight")]
    np.testing.assert_allclose(mapped[:, direct], ntu[:, direct])
    np.testing.assert_allclose(mapped[:, J["FootLeft"]], ntu[:, J["FootLeft"]])
    spine_mid = ntu[:, J["SpineBase"]] + 0.56 * (
        ntu[:, J["SpineShoulder"]] - ntu[:, J["SpineBase"]]
    )
    np.testing.assert_allclose(mapped[:, J["SpineMid"]], spine_mid)
    # the hand continues the forearm beyond the wrist
    forearm = ntu[:, J["WristRight"]] - ntu[:, J["ElbowRight"]]
    np.testing.assert_allclose(mapped[:, J["HandRight"]], ntu[:, J["WristRight"]] + 0.3 * forearm)
    assert np.isfinite(mapped).all()


def test_low_confidence_falls_back_or_leaves_the_joint_unseen() -> None:
    ntu = _ntu_pixels(2)
    kp = _body25_from(ntu)
    ears = [BODY_25.index("LEar"), BODY_25.index("REar")]
    kp[:, ears, :2] += 40.0  # the ears would move the head: they must be ignored now
    kp[:, ears, 2] = 0.05
    kp[1, BODY_25.index("LWrist"), 2] = 0.0
    mapped = to_ntu(kp, "openpose_body25", min_confidence=0.3)
    np.testing.assert_allclose(mapped[:, J["Head"]], ntu[:, J["Head"]])  # from the eyes
    hand = [J[n] for n in ("WristLeft", "HandLeft", "HandTipLeft", "ThumbLeft")]
    assert np.isnan(mapped[1, hand]).all() and np.isfinite(mapped[0, hand]).all()
    assert np.isfinite(mapped[1, J["ElbowLeft"]]).all()


def test_blazepose_maps_sides_hands_and_spine() -> None:
    rng = np.random.default_rng(1)
    kp = np.concatenate([rng.uniform(0, 300, (2, 33, 2)), np.full((2, 33, 1), 0.9)], axis=2)
    k = {name: i for i, name in enumerate(BLAZEPOSE_33)}
    mapped = to_ntu(kp, "mediapipe_blazepose33")
    np.testing.assert_allclose(mapped[:, J["ShoulderLeft"]], kp[:, k["left_shoulder"], :2])
    np.testing.assert_allclose(mapped[:, J["ThumbRight"]], kp[:, k["right_thumb"], :2])
    hips = (kp[:, k["left_hip"], :2] + kp[:, k["right_hip"], :2]) / 2
    np.testing.assert_allclose(mapped[:, J["SpineBase"]], hips)
    hand = kp[:, [k["left_wrist"], k["left_pinky"], k["left_index"]], :2].mean(axis=1)
    np.testing.assert_allclose(mapped[:, J["HandLeft"]], hand)


def test_bad_formats_and_shapes_are_config_errors() -> None:
    with pytest.raises(ConfigError, match="unknown keypoint format"):
        to_ntu(np.zeros((1, 25, 3)), "h36m17")
    with pytest.raises(ConfigError, match=r"\(frames, 33, 3\)"):
        to_ntu(np.zeros((1, 25, 3)), "mediapipe_blazepose33")
