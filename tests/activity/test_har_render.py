"""The simulated pose estimator and depth camera, and the whole 2D -> 3D path through them."""

import numpy as np

from amiro.activity.dataset import subject_body, window
from amiro.activity.labels import ACTIONS
from amiro.activity.onnx_model import ActivityModel
from amiro.activity.render import depth_image, project, through_pose_estimator
from amiro.activity.skeleton import J, visible
from amiro.robot.camera import Camera

CAMERA = Camera()
INFO = CAMERA.info(0.0)


def test_projection_matches_the_simulated_head_camera() -> None:
    joints = window("typing", subject_body(0, 0), 0.0, np.random.default_rng(0), 2)[0]
    optical = joints * np.array([-1.0, -1.0, 1.0])  # Kinect axes to optical axes
    np.testing.assert_allclose(project(joints, INFO), CAMERA.project(optical))


def test_nearer_joints_hide_farther_ones_in_the_depth_image() -> None:
    joints = np.full((25, 3), np.nan)
    joints[J["HandRight"]] = [0.0, 0.0, 2.0]
    joints[J["SpineMid"]] = [0.0, 0.0, 2.5]  # straight behind the hand
    joints[J["Head"]] = [0.0, 0.5, 2.5]
    depth = depth_image(joints, INFO, scale=1.0, wall_m=6.0)
    (hand_u, hand_v), (head_u, head_v) = project(joints, INFO)[[J["HandRight"], J["Head"]]]
    assert depth[int(hand_v), int(hand_u)] == 2.0  # the spine behind it is hidden
    assert depth[int(head_v), int(head_u)] == 2.5
    assert depth[0, 0] == 6.0


def test_the_shipped_model_classifies_skeletons_rebuilt_from_2d_keypoints() -> None:
    model = ActivityModel()
    rng = np.random.default_rng(3)
    windows = [window(a, subject_body(5, 0), 0.0, rng, 30) for a in ACTIONS]
    rebuilt = [through_pose_estimator(w, INFO) for w in windows]
    seen = np.mean([visible(r).mean() for r in rebuilt])
    assert 0.6 < seen < 1.0  # feet and edge joints get lost, most of the body does not
    error = np.nanmedian(np.linalg.norm(np.stack(rebuilt) - np.stack(windows), axis=-1))
    assert error < 0.05
    predicted = [model.classes[int(model.classify(r).argmax())] for r in rebuilt]
    assert sum(p == a for p, a in zip(predicted, ACTIONS, strict=True)) >= 8
