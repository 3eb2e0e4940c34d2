import numpy as np

from amiro.activity.labels import ACTIONS, IDLE
from amiro.activity.motion import FPS, Body, View, perform, to_camera
from amiro.activity.normalize import normalize_bones, preprocess
from amiro.activity.skeleton import PARENT, SEGMENT_LENGTH, J


def _bone_lengths(frames: np.ndarray) -> np.ndarray:
    children = list(range(1, 25))
    bones = frames[:, children] - frames[:, [PARENT[j] for j in children]]
    lengths: np.ndarray = np.linalg.norm(bones, axis=-1)
    return lengths


def test_bones_get_the_standard_lengths_and_keep_directions() -> None:
    rng = np.random.default_rng(1)
    frames = perform("hand_waving", Body.random(rng), rng)
    out = normalize_bones(frames)
    np.testing.assert_allclose(
        _bone_lengths(out), np.tile(SEGMENT_LENGTH[1:], (len(out), 1)), atol=1e-9
    )
    fore = frames[:, J["WristRight"]] - frames[:, J["ElbowRight"]]
    fore_out = out[:, J["WristRight"]] - out[:, J["ElbowRight"]]
    cos = (
        np.sum(fore * fore_out, axis=1)
        / np.linalg.norm(fore, axis=1)
        / np.linalg.norm(fore_out, axis=1)
    )
    assert np.all(cos > 0.9999)


def test_missing_parent_hangs_child_from_nearest_seen_ancestor() -> None:
    rng = np.random.default_rng(2)
    frames = perform("pointing", Body.random(rng), rng)
    frames[:, J["ElbowRight"]] = np.nan
    out = normalize_bones(frames)
    assert np.isnan(out[:, J["ElbowRight"]]).all()
    reach = np.linalg.norm(out[:, J["WristRight"]] - out[:, J["ShoulderRight"]], axis=1)
    np.testing.assert_allclose(
        reach, SEGMENT_LENGTH[J["ElbowRight"]] + SEGMENT_LENGTH[J["WristRight"]]
    )


def test_view_normalisation_removes_camera_angle_and_distance() -> None:
    rng = np.random.default_rng(3)
    body_frames = perform("drink_water", Body.random(rng), rng)
    a = preprocess(to_camera(body_frames, View(yaw=0.0, distance=2.0)))
    b = preprocess(to_camera(body_frames, View(yaw=0.9, distance=3.5, height=1.3)))
    np.testing.assert_allclose(a, b, atol=1e-6)
    c = preprocess(to_camera(perform("typing", Body.random(rng), rng), View()))
    assert not np.allclose(a[: len(c)], c[: len(a)], atol=1e-2)


def test_every_action_makes_a_plausible_body_over_the_floor() -> None:
    rng = np.random.default_rng(4)
    body = Body.random(rng)
    for action in (*ACTIONS, IDLE):
        frames = perform(action, body, rng)
        assert 15 < len(frames) < 120 and np.isfinite(frames).all()
        assert frames[..., 1].min() > 0.0
    fell = perform("falling", body, rng)
    assert fell[-1, J["Head"], 1] < 0.5 < fell[0, J["Head"], 1]
    stood = perform("standing_up", body, rng)
    assert stood[-1, J["SpineBase"], 1] > stood[0, J["SpineBase"], 1] + 0.2


def test_same_seed_same_motion() -> None:
    def make(seed: int) -> np.ndarray:
        rng = np.random.default_rng(seed)
        return perform("sneeze_cough", Body.random(rng), rng)

    np.testing.assert_array_equal(make(5), make(5))
    assert make(5).shape != make(6).shape or not np.allclose(make(5), make(6))


def _drink_and_sneeze_cues(action: str, rng: np.random.Generator) -> tuple[float, float, float]:
    """(s with a hand at the face, how far the head tips back, peak forward head speed)."""
    frames = perform(action, Body.random(rng), rng)
    head = frames[:, J["Head"]]
    near = np.minimum(
        np.linalg.norm(frames[:, J["HandLeft"]] - head, axis=1),
        np.linalg.norm(frames[:, J["HandRight"]] - head, axis=1),
    )
    behind_neck = head[:, 2] - frames[:, J["Neck"], 2]  # body frame: z points behind
    forward_speed = float((-np.diff(head[:, 2]) * FPS).max())
    return (
        float((near < 0.25).sum() / FPS),
        float(behind_neck.max() - behind_neck[0]),
        forward_speed,
    )


def test_drinking_holds_the_cup_head_back_and_sneezing_jerks_forward_briefly() -> None:
    rng = np.random.default_rng(7)
    drink = np.array([_drink_and_sneeze_cues("drink_water", rng) for _ in range(10)])
    sneeze = np.array([_drink_and_sneeze_cues("sneeze_cough", rng) for _ in range(10)])
    assert np.median(drink[:, 0]) > 1.5 > np.median(sneeze[:, 0])
    assert drink[:, 1].min() > 0.03 > sneeze[:, 1].max()
    assert sneeze[:, 2].min() > 1.2 > drink[:, 2].max()
    assert np.ptp(drink[:, 0]) > 0.5 and np.ptp(sneeze[:, 2]) > 1.0  # varied, not one template


def test_view_normalisation_removes_camera_pitch_and_height() -> None:
    rng = np.random.default_rng(5)
    body_frames = perform("hand_waving", Body.random(rng), rng)
    level = preprocess(to_camera(body_frames, View(height=0.9)))
    for pitch, height in ((0.35, 1.6), (-0.2, 0.5)):
        pitched = preprocess(to_camera(body_frames, View(pitch=pitch, height=height)))
        np.testing.assert_allclose(level, pitched, atol=1e-6)
