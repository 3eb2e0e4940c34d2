"""Face identity: enrol residents from a few images, then identify or answer "unknown".

The gallery is backend-neutral (it stores embeddings); :class:`DlibFaceEmbedder` computes
dlib's 128-d embeddings through face_recognition, imported only when used.  A face matches
the nearest enrolled person only within ``threshold``: an unknown face is never forced onto
a resident.
"""

from __future__ import annotations

import importlib
import warnings
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from amiro.core.config import ConfigError
from amiro.perception.ports import FaceEmbedder

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class Identity:
    """The answer for one face: a name (None: unknown) and the embedding distance."""

    name: str | None
    distance: float


class FaceGallery:
    """Enrolled embeddings per name; nearest-neighbour identification with a threshold."""

    def __init__(self, embedder: FaceEmbedder, threshold: float = 0.6) -> None:
        self.embedder = embedder
        self.threshold = threshold
        self._names: list[str] = []
        self._vectors: list[FloatArray] = []

    @property
    def names(self) -> list[str]:
        return sorted(set(self._names))

    def enrol(self, name: str, images: Iterable[npt.NDArray[np.uint8]]) -> int:
        """Add the single face of each image under ``name``; returns how many were used.
        Images with no face or several faces are skipped (ambiguous for enrolment)."""
        used = 0
        for image in images:
            faces = self.embedder.embed(image)
            if len(faces) == 1:
                self._names.append(name)
                self._vectors.append(np.asarray(faces[0], dtype=np.float64))
                used += 1
        return used

    def match(self, embedding: FloatArray) -> Identity:
        if not self._vectors:
            return Identity(None, float("inf"))
        dists = np.linalg.norm(np.stack(self._vectors) - embedding, axis=1)
        best = int(np.argmin(dists))
        d = float(dists[best])
        return Identity(self._names[best] if d <= self.threshold else None, d)

    def identify(self, image: npt.NDArray[np.uint8]) -> list[Identity]:
        """One identity per face in the image."""
        return [self.match(np.asarray(e, dtype=np.float64)) for e in self.embedder.embed(image)]


class DlibFaceEmbedder:
    """dlib's ResNet face embeddings (face_recognition), HOG face detector by default."""

    def __init__(self, model: str = "hog", upsample: int = 1) -> None:
        try:
            with warnings.catch_warnings():  # face_recognition_models still uses pkg_resources
                warnings.filterwarnings("ignore", "pkg_resources is deprecated", UserWarning)
                face_recognition = importlib.import_module("face_recognition")
        except ImportError as exc:  # the message the registry gives a missing extra
            raise ConfigError(
                "faces backend 'dlib' needs the extra amiro[faces] "
                f"(missing module: {exc.name or exc})"
            ) from None
        self._fr: Any = face_recognition
        self.model = model
        self.upsample = upsample

    def embed(self, rgb: npt.NDArray[np.uint8]) -> list[FloatArray]:
        image = np.ascontiguousarray(rgb, dtype=np.uint8)
        boxes = self._fr.face_locations(image, self.upsample, self.model)
        return [np.asarray(e, dtype=np.float64) for e in self._fr.face_encodings(image, boxes)]


def load_image(path: Path) -> npt.NDArray[np.uint8]:
    """An RGB image from a file, or a one-line error."""
    from PIL import Image, UnidentifiedImageError

    try:
        with Image.open(path) as img:
            return np.asarray(img.convert("RGB"), dtype=np.uint8)
    except (OSError, UnidentifiedImageError) as exc:
        raise ConfigError(f"{path}: cannot read image: {exc}") from None


def dlib_gallery(gallery: dict[str, list[Path]], threshold: float) -> FaceGallery:
    """A gallery enrolled from image files with the dlib backend."""
    faces = FaceGallery(DlibFaceEmbedder(), threshold)
    for name, paths in gallery.items():
        if faces.enrol(name, (load_image(p) for p in paths)) == 0:
            raise ConfigError(f"perception.faces.gallery.{name}: no single face in its images")
    return faces
