"""Face identity with the real dlib backend on two shipped public-domain portraits, and the
gallery's rules on hand-made embeddings.

The enrolment images are altered views of the same photos the queries come from, so this
checks the plumbing and the "unknown" rule on real faces, not recognition across photos.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest
from PIL import Image

from amiro.core.config import ConfigError
from amiro.perception.face_samples import in_scene, sample_face, views
from amiro.perception.faces import DlibFaceEmbedder, FaceGallery, dlib_gallery

Rgb = npt.NDArray[np.uint8]


@pytest.fixture(scope="module")
def embedder() -> DlibFaceEmbedder:
    return DlibFaceEmbedder()


@pytest.fixture(scope="module")
def gallery(embedder: DlibFaceEmbedder) -> FaceGallery:
    faces = FaceGallery(embedder, threshold=0.6)
    for name in ("collins", "hopper"):
        assert faces.enrol(name, views(sample_face(name))) == 4
    return faces


@pytest.mark.parametrize("name", ["collins", "hopper"])
def test_identifies_each_enrolled_person(gallery: FaceGallery, name: str) -> None:
    (who,) = gallery.identify(sample_face(name))
    assert who.name == name and who.distance < 0.4
    (in_frame,) = gallery.identify(in_scene(sample_face(name)))
    assert in_frame.name == name


def test_a_stranger_is_unknown_not_a_guess(embedder: DlibFaceEmbedder) -> None:
    faces = FaceGallery(embedder, threshold=0.6)
    faces.enrol("hopper", views(sample_face("hopper"))[:2])
    (who,) = faces.identify(sample_face("collins"))
    assert who.name is None and who.distance > 0.6


def test_no_face_means_nothing_to_enrol_or_identify(gallery: FaceGallery) -> None:
    blank: Rgb = np.full((240, 320, 3), 128, dtype=np.uint8)
    assert gallery.enrol("nobody", [blank]) == 0
    assert gallery.identify(blank) == []
    assert gallery.names == ["collins", "hopper"]


def test_gallery_from_files(tmp_path: Path) -> None:
    paths = []
    for i, view in enumerate(views(sample_face("collins"))[:2]):
        paths.append(tmp_path / f"collins_{i}.png")
        Image.fromarray(view).save(paths[-1])
    faces = dlib_gallery({"collins": paths}, threshold=0.6)
    assert [w.name for w in faces.identify(sample_face("collins"))] == ["collins"]
    with pytest.raises(ConfigError, match="cannot read image"):
        dlib_gallery({"collins": [tmp_path / "missing.png"]}, 0.6)
    Image.fromarray(np.zeros((100, 100, 3), dtype=np.uint8)).save(tmp_path / "dark.png")
    with pytest.raises(ConfigError, match=r"gallery\.ion: no single face"):
        dlib_gallery({"ion": [tmp_path / "dark.png"]}, 0.6)


def test_unknown_sample_name_is_a_clear_error() -> None:
    with pytest.raises(ValueError, match="no sample face 'ada'"):
        sample_face("ada")


class ListedEmbedder:
    """Embeddings given per image by its first pixel, to test the gallery's rules alone."""

    def __init__(self, table: dict[int, list[list[float]]]) -> None:
        self.table = table

    def embed(self, rgb: Rgb) -> list[npt.NDArray[np.float64]]:
        return [np.array(v, dtype=np.float64) for v in self.table[int(rgb[0, 0, 0])]]


def image(key: int) -> Rgb:
    return np.full((2, 2, 3), key, dtype=np.uint8)


def test_gallery_rules_on_embeddings() -> None:
    embedder = ListedEmbedder(
        {1: [[0.0, 0.0]], 2: [[1.0, 0.0]], 3: [[0.0, 0.0], [1.0, 0.0]], 4: [[0.0, 0.55]]}
    )
    faces = FaceGallery(embedder, threshold=0.5)
    assert faces.identify(image(1))[0].name is None  # nobody enrolled yet
    assert faces.enrol("ana", [image(1), image(3)]) == 1  # two faces: ambiguous, skipped
    assert faces.enrol("ion", [image(2)]) == 1
    assert [w.name for w in faces.identify(image(3))] == ["ana", "ion"]
    (near_ana,) = faces.identify(image(4))
    assert near_ana.name is None and near_ana.distance == pytest.approx(0.55)
