"""Face identity in the camera people finder, on the real portraits amiro ships.

A portrait fills the upper half of a person's box in a 640 x 480 frame (a person close to
the robot); dlib's embeddings name them against a gallery enrolled from altered views of
the portrait, and a face no one enrolled stays unknown.  The enrolment views come from the
same photo, so this checks the wiring (box → head crop → gallery → track name), not
recognition across photos.
"""

from __future__ import annotations

import numpy as np
import pytest

from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import BoundingBox2D, CameraInfo, Detection2D, Header, Image, Pose2D
from amiro.core.runtime import Runtime
from amiro.perception.camera_finder import CameraPeopleFinder
from amiro.perception.config import PerceptionConfig
from amiro.perception.face_samples import in_scene, sample_face, views
from amiro.perception.faces import DlibFaceEmbedder, FaceGallery
from amiro.perception.ports import Frame
from amiro.robot.camera import Camera
from amiro.robot.camera_feed import CameraFeed

BOX = BoundingBox2D(412.0, 240.0, 224.0, 480.0)  # the portrait's columns, the whole height


class OnePerson:
    def detect(self, frame: Frame) -> list[Detection2D]:
        return [Detection2D("person", 0.9, BOX)]


@pytest.fixture(scope="module")
def gallery() -> FaceGallery:
    faces = FaceGallery(DlibFaceEmbedder(upsample=0), threshold=0.6)
    faces.enrol("hopper", views(sample_face("hopper"))[:2])
    return faces


@pytest.mark.parametrize(("face", "expected"), [("hopper", "hopper"), ("collins", None)])
def test_the_face_in_the_box_names_the_track(
    gallery: FaceGallery, face: str, expected: str | None
) -> None:
    rt = Runtime(SimClock(), seed=1)
    feed = rt.add(CameraFeed())
    rt.start()
    rgb = in_scene(sample_face(face), at=(300, 0))
    depth = np.full((480, 640), 1.2, dtype=np.float32)
    header = Header(0.0, "camera")
    rt.bus.publisher(names.IMAGE, Image).publish(Image(header, 480, 640, "rgb8", rgb))
    rt.bus.publisher(names.DEPTH, Image).publish(Image(header, 480, 640, "32FC1", depth))
    rt.bus.publisher(names.CAMERA_INFO, CameraInfo).publish(Camera().info(0.0))
    rt.spin_for(0.05)
    finder = CameraPeopleFinder(
        feed, OnePerson(), PerceptionConfig(backend="camera"), lambda: Pose2D(), gallery
    )
    seen = finder.look()
    if expected is None:
        assert seen == []  # unnamed and seen once: not yet confirmed
        assert finder.tracker.tracks[0].name is None
    else:
        (person,) = seen  # a recognised face confirms the track at once
        assert person.name == expected
        assert finder.locate("hopper") == person.position
        assert finder.people() == ["hopper"]
