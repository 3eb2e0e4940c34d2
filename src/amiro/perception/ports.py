"""The perception ports: what behaviour tasks consume and what detectors and faces provide."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np
import numpy.typing as npt

from amiro.core.messages import Detection2D, Point
from amiro.perception.sim_objects import ObjectObservation
from amiro.robot.camera import CameraObservation


@dataclass(frozen=True)
class SeenPerson:
    """A person seen now: identity if the face was recognised, position in the map frame.

    ``track_id`` stays the same while the tracker follows the person; ``face_backlit`` says
    the face could not be recognised because the camera faces a light source, so a task
    can move to change the viewing angle (the paper's proposed fix).
    """

    name: str | None
    position: Point
    confidence: float
    track_id: str | None = None
    face_backlit: bool = False


@dataclass(frozen=True)
class SeenObject:
    """A household object seen now (COCO label) and its centre in the map frame."""

    label: str
    position: Point
    confidence: float


class ObjectFinder(Protocol):
    def look(self) -> list[SeenObject]:
        """The household objects the robot's camera sees at this moment."""
        ...


class PeopleFinder(Protocol):
    def look(self) -> list[SeenPerson]:
        """Who the robot's camera sees at this moment."""
        ...


@runtime_checkable
class TracksPeople(Protocol):
    """A people finder that knows whom it tracks (a real camera's), so the fall monitor
    watches them; the simulator's finders leave that to the residents' names."""

    def people(self) -> list[str]: ...


@dataclass(frozen=True, eq=False)
class Frame:
    """One camera frame for a detector: the RGB pixels (H, W, 3 uint8) when a real camera
    or renderer gives them, and the simulator's observations (people, objects) when it
    does not."""

    rgb: npt.NDArray[np.uint8] | None = None
    observations: Sequence[CameraObservation] = field(default_factory=tuple)
    objects: Sequence[ObjectObservation] = field(default_factory=tuple)


class Detector(Protocol):
    def detect(self, frame: Frame) -> list[Detection2D]:
        """Labelled boxes (pixels of the RGB image) with scores in [0, 1]."""
        ...


class FaceEmbedder(Protocol):
    def embed(self, rgb: npt.NDArray[np.uint8]) -> list[npt.NDArray[np.float64]]:
        """One embedding per face found in the image."""
        ...


def require_rgb(frame: Frame, who: str) -> npt.NDArray[Any]:
    """The frame's RGB image, or a clear error for a detector that needs pixels."""
    if frame.rgb is None:
        raise ValueError(f"{who} needs an RGB image; this frame has none")
    rgb = np.asarray(frame.rgb)
    if rgb.ndim != 3 or rgb.shape[2] != 3:
        raise ValueError(f"{who}: expected an (H, W, 3) image, got shape {rgb.shape}")
    return rgb
