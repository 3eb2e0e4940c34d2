"""Two real portraits shipped with amiro, and altered views of them, so the dlib face
backend can be checked and timed with no download (see data/perception/faces/README.md)."""

from __future__ import annotations

from importlib import resources

import numpy as np
import numpy.typing as npt

from amiro.perception.faces import load_image

Image = npt.NDArray[np.uint8]

SAMPLE_FACES = ("collins", "hopper")


def sample_face(name: str) -> Image:
    """The portrait of ``name`` (one of :data:`SAMPLE_FACES`), RGB."""
    if name not in SAMPLE_FACES:
        raise ValueError(f"no sample face {name!r}; choose from {', '.join(SAMPLE_FACES)}")
    with resources.as_file(
        resources.files("amiro").joinpath(f"data/perception/faces/{name}.jpg")
    ) as path:
        return load_image(path)


def views(image: Image) -> list[Image]:
    """Four altered views (mirrored, darker, shifted crop, brighter half-size) standing in
    for the few enrolment photos of one person."""
    h, w = image.shape[:2]
    mirrored = np.ascontiguousarray(image[:, ::-1])
    darker = (image.astype(np.float64) * 0.65).astype(np.uint8)
    shifted = np.ascontiguousarray(image[h // 12 :, : w - w // 12])
    brighter = np.clip(image[::2, ::2].astype(np.float64) * 1.2 + 10, 0, 255).astype(np.uint8)
    return [mirrored, darker, shifted, np.ascontiguousarray(brighter)]


def in_scene(
    face: Image, size: tuple[int, int] = (640, 480), at: tuple[int, int] = (300, 60)
) -> Image:
    """``face`` pasted into a plain grey camera frame of ``size`` (width, height) at pixel
    ``at`` (left, top): a face as the robot's camera would frame it."""
    frame = np.full((size[1], size[0], 3), 128, dtype=np.uint8)
    h, w = face.shape[:2]
    frame[at[1] : at[1] + h, at[0] : at[0] + w] = face
    return frame
