"""The shipped 2D pose estimator (MediaPipe BlazePose, extra ``amiro[pose]``) on real
photographs of people that ship in packages: scikit-image's ``astronaut`` (Eileen Collins)
and matplotlib's ``grace_hopper``; then the camera path (NTU-25 mapping, lifting with a
depth image, the recogniser) on a camera showing the photograph.

The face and body boxes below were read off the photographs by eye, not from the model.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
import pytest
from skimage import data

from amiro.activity.bench import photo_frame
from amiro.activity.camera_skeletons import CameraSkeletonSource
from amiro.activity.config import ActivityConfig
from amiro.activity.keypoints import BLAZEPOSE_33, to_ntu
from amiro.activity.mediapipe_pose import MediaPipePoseEstimator
from amiro.activity.skeleton import JOINTS, J
from amiro.activity.stack import ActivityInputs, CameraSkeletons, create_recognizer
from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import CameraInfo, Header, Image
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.robot.camera import Camera

K = {name: i for i, name in enumerate(BLAZEPOSE_33)}
INFO = Camera().info(0.0)
# (u0, v0, u1, v1) of the face, read off each image.
ASTRONAUT_FACE = (170, 45, 285, 190)
HOPPER_FACE = (240, 100, 415, 270)  # in bench.photo_frame's 640x480 frame


@pytest.fixture(scope="module")
def estimator() -> MediaPipePoseEstimator:
    return MediaPipePoseEstimator(tracking=False)


def inside(point: npt.NDArray[np.float64], box: tuple[int, int, int, int]) -> bool:
    return bool(box[0] <= point[0] <= box[2] and box[1] <= point[1] <= box[3])


def the_one_pose(estimator: MediaPipePoseEstimator, rgb: npt.NDArray[np.uint8]) -> np.ndarray:
    (pose,) = estimator.estimate(rgb)
    assert pose.keypoints.shape == (33, 3)
    return pose.keypoints


@pytest.mark.parametrize(
    ("image", "face"), [(data.astronaut, ASTRONAUT_FACE), (photo_frame, HOPPER_FACE)]
)
def test_keypoints_land_on_the_person(
    estimator: MediaPipePoseEstimator, image: object, face: tuple[int, int, int, int]
) -> None:
    rgb = image()  # type: ignore[operator]
    k = the_one_pose(estimator, rgb)
    for part in ("nose", "left_eye", "right_eye", "mouth_left", "mouth_right"):
        assert inside(k[K[part]], face), part
    v = k[:, 1]
    assert v[K["left_eye"]] < v[K["nose"]] < v[K["mouth_left"]]
    for side in ("left", "right"):
        assert face[3] < v[K[side + "_shoulder"]]  # shoulders below the chin
        assert v[K[side + "_shoulder"]] < v[K[side + "_wrist"]]
    # Both face the camera: the person's left is on the image's right.
    assert k[K["left_shoulder"], 0] > face[2] and k[K["right_shoulder"], 0] < face[0]
    assert k[K["left_eye"], 0] > k[K["right_eye"], 0]


def test_no_person_no_pose(estimator: MediaPipePoseEstimator) -> None:
    assert estimator.estimate(np.full((480, 640, 3), 114, dtype=np.uint8)) == []


def test_the_ntu_skeleton_of_a_photograph(estimator: MediaPipePoseEstimator) -> None:
    k = the_one_pose(estimator, data.astronaut())
    ntu = to_ntu(k[None], "mediapipe_blazepose33", min_confidence=0.5)[0]
    assert inside(ntu[J["Head"]], ASTRONAUT_FACE)
    shoulders = ntu[[J["ShoulderLeft"], J["ShoulderRight"]]]
    assert np.allclose(ntu[J["SpineShoulder"]], shoulders.mean(axis=0))
    assert ntu[J["Head"], 1] < ntu[J["Neck"], 1] < ntu[J["SpineShoulder"], 1]
    # Her legs are out of the picture: unseen, not guessed.
    assert np.isnan(ntu[[J["KneeLeft"], J["KneeRight"], J["AnkleLeft"]]]).all()


class PhotoCamera(Node):
    """A head camera looking at the photograph, a wall of depth ``depth_m`` behind it."""

    def __init__(self, rgb: npt.NDArray[np.uint8], depth_m: float) -> None:
        super().__init__("photo_camera")
        self.rgb = rgb
        self.depth = np.full(rgb.shape[:2], depth_m, dtype=np.float32)

    def on_start(self) -> None:
        self.pubs = [self.create_publisher(t, Image) for t in (names.IMAGE, names.DEPTH)]
        self.info = self.create_publisher(names.CAMERA_INFO, CameraInfo)
        self.create_timer(1.0 / 15.0, self.play)

    def play(self) -> None:
        h = Header(self.now(), "camera")
        self.pubs[0].publish(Image(h, INFO.height, INFO.width, "rgb8", self.rgb))
        self.pubs[1].publish(Image(h, INFO.height, INFO.width, "32FC1", self.depth))
        self.info.publish(INFO)


def test_the_camera_mediapipe_backend_lifts_the_photograph_and_wants_more_of_the_body() -> None:
    from amiro.robot.camera_feed import CameraFeed

    rt = Runtime(SimClock(), seed=1)
    feed = rt.add(CameraFeed())
    rt.add(PhotoCamera(photo_frame(), 1.0))
    camera = CameraSkeletons(rt, feed, locate=lambda person: None, place=lambda f, b: None)
    cfg = ActivityConfig(backend="camera-mediapipe")
    recognizer = create_recognizer(ActivityInputs(cfg, np.random.default_rng(0), camera=camera))
    source = rt.node("camera_skeletons")
    assert isinstance(source, CameraSkeletonSource)
    assert isinstance(source.estimator, MediaPipePoseEstimator)
    rt.start()
    rt.spin_for(2.2)
    window = source.window("anyone", 30)
    assert window is not None and source.stats.frames >= 30
    s = window[-1]
    seen = [JOINTS[j] for j in range(len(JOINTS)) if np.isfinite(s[j]).all()]
    assert {"Head", "Neck", "SpineShoulder", "ShoulderLeft", "ShoulderRight"} <= set(seen)
    assert not {"KneeLeft", "KneeRight", "AnkleLeft", "AnkleRight"} & set(seen)
    # A portrait fills the frame as a person 1 m away would: an adult's shoulders, 0.3-0.5 m.
    width = float(np.linalg.norm(s[J["ShoulderLeft"]] - s[J["ShoulderRight"]]))
    assert 0.3 < width < 0.55
    assert s[J["Head"], 1] - s[J["SpineShoulder"], 1] > 0.1
    # A head-and-shoulders view is too little of a body to name an activity.
    assert not recognizer.observe("anyone").skeleton_complete
