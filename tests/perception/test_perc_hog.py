"""OpenCV's HOG people detector on drawn images.

A real photo library cannot ship with the tests, so a person is drawn: a dark, upright
human silhouette (head, neck, torso, arms, legs) on a light background, blurred like a
camera image.  HOG fires on it from about 200 to 300 pixels tall in a 640 x 480 frame;
it does not fire on blank or noise images.  It only knows upright people: a silhouette
turned on its side (someone lying down) is not found.
"""

from __future__ import annotations

import cv2
import numpy as np
import numpy.typing as npt
import pytest

from amiro.perception.hog import HogPeopleDetector
from amiro.perception.ports import Frame
from amiro.perception.synthetic_scene import silhouette

Rgb = npt.NDArray[np.uint8]


def scene(*people: tuple[int, int, int]) -> Rgb:
    image: Rgb = np.full((480, 640, 3), 200, dtype=np.uint8)
    for cx, top, height in people:
        silhouette(image, cx, top, height)
    return np.asarray(cv2.GaussianBlur(image, (5, 5), 0), dtype=np.uint8)


@pytest.fixture(scope="module")
def hog() -> HogPeopleDetector:
    return HogPeopleDetector()


@pytest.mark.parametrize("height", [200, 250, 300])
def test_finds_a_drawn_person(hog: HogPeopleDetector, height: int) -> None:
    (found,) = hog.detect(Frame(rgb=scene((320, 90, height))))
    assert found.label == "person" and 0.5 < found.score <= 1.0
    box = found.bbox
    # the box (centre and size, pixels) covers the silhouette, with HOG's usual margin
    assert abs(box.cx - 320) < 0.1 * height
    assert box.cy - box.height / 2 <= 90 + 0.1 * height
    assert box.cy + box.height / 2 >= 90 + 0.9 * height
    assert box.height < 1.5 * height and box.width < box.height


def test_boxes_follow_the_people(hog: HogPeopleDetector) -> None:
    found = hog.detect(Frame(rgb=scene((170, 100, 250), (470, 100, 250))))
    assert sorted(round(d.bbox.cx / 100) for d in found) == [2, 5]


def test_nothing_in_blank_noise_or_a_person_lying_down(hog: HogPeopleDetector) -> None:
    blank: Rgb = np.full((480, 640, 3), 128, dtype=np.uint8)
    noise = np.random.default_rng(0).integers(0, 256, (480, 640, 3), dtype=np.uint8)
    lying = np.ascontiguousarray(np.rot90(scene((240, 40, 250)))[80:560])
    for image in (blank, noise, lying):
        assert hog.detect(Frame(rgb=image)) == []


def test_bad_input_is_a_clear_error(hog: HogPeopleDetector) -> None:
    with pytest.raises(ValueError, match="needs an RGB image"):
        hog.detect(Frame())
    with pytest.raises(ValueError, match=r"expected an \(H, W, 3\) image"):
        hog.detect(Frame(rgb=np.zeros((48, 64), dtype=np.uint8)))
