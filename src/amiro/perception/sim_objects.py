"""Household objects in the simulated home and how the head camera sees them.

Furniture a COCO-trained detector knows (couch, chair, bed, tables) comes from the home's
description; small objects (cups, bottles) are placed on furniture by a YAML file per home
(``data/perception/household_objects.yaml``).  Like :meth:`amiro.sim.camera.Camera.observe`
for people, observation projects each object's box into the image and reports its depth.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Literal

import numpy as np
from pydantic import Field

from amiro.core.config import ConfigError, Section, load
from amiro.core.messages import BoundingBox2D, Point, Pose2D
from amiro.home.world import World
from amiro.robot.camera import Camera

# COCO's name for each furniture kind a detector trained on it can find.
FURNITURE_LABELS = {
    "couch": "couch",
    "chair": "chair",
    "bed": "bed",
    "table": "dining table",
    "desk": "dining table",
}
# Width, depth, height (m) of the small objects.
OBJECT_SIZES = {"cup": (0.08, 0.08, 0.10), "bottle": (0.08, 0.08, 0.25)}


class PlacedObject(Section):
    label: Literal["cup", "bottle"]
    furniture: str = Field(description="what it stands on")
    dx: float = 0.0
    dy: float = 0.0


class HouseholdObjects(Section):
    homes: dict[str, list[PlacedObject]] = Field(default_factory=dict)


@dataclass(frozen=True, slots=True)
class SimObject:
    """An object as an axis-aligned box in the map frame."""

    label: str
    lo: tuple[float, float, float]
    hi: tuple[float, float, float]

    @property
    def centre(self) -> Point:
        return Point(*((a + b) / 2.0 for a, b in zip(self.lo, self.hi, strict=True)))

    def corners(self) -> np.ndarray[tuple[int, int], np.dtype[np.float64]]:
        xs, ys, zs = zip(self.lo, self.hi, strict=True)
        return np.array([[x, y, z] for x in xs for y in ys for z in zs], dtype=np.float64)


@dataclass(frozen=True, slots=True)
class ObjectObservation:
    """One object as the camera sees it: box (RGB pixels), noisy z-depth of its centre,
    and the true centre for scoring."""

    label: str
    bbox: BoundingBox2D
    depth: float
    position: Point


def default_objects_path() -> Path:
    return Path(str(resources.files("amiro").joinpath("data/perception/household_objects.yaml")))


def household_objects(world: World, path: Path | None = None) -> list[SimObject]:
    """The home's detectable furniture and the small objects placed for this home."""
    footprints = {}
    found: list[SimObject] = []
    for item in world.home.furniture:
        xy = np.asarray(item.polygon, dtype=np.float64)
        (x0, y0), (x1, y1) = xy.min(axis=0), xy.max(axis=0)
        footprints[item.name] = (float(x0 + x1) / 2, float(y0 + y1) / 2, item.height)
        if item.kind in FURNITURE_LABELS:
            box = SimObject(FURNITURE_LABELS[item.kind], (x0, y0, 0.0), (x1, y1, item.height))
            found.append(box)
    source = path or default_objects_path()
    for placed in load(HouseholdObjects, source).homes.get(world.name, []):
        if placed.furniture not in footprints:
            raise ConfigError(f"{source}: {placed.label} on unknown furniture {placed.furniture!r}")
        cx, cy, top = footprints[placed.furniture]
        w, d, h = OBJECT_SIZES[placed.label]
        x, y = cx + placed.dx, cy + placed.dy
        found.append(
            SimObject(placed.label, (x - w / 2, y - d / 2, top), (x + w / 2, y + d / 2, top + h))
        )
    return found


def observe_objects(
    camera: Camera,
    world: World,
    robot_pose: Pose2D,
    head_yaw: float,
    head_pitch: float,
    objects: Iterable[SimObject],
    rng: np.random.Generator,
) -> list[ObjectObservation]:
    """One observation per object whose centre is in view and in line of sight."""
    seen: list[ObjectObservation] = []
    for obj in objects:
        c = obj.centre
        sight = camera.sight(
            world,
            robot_pose,
            head_yaw,
            head_pitch,
            np.vstack([[c.x, c.y, c.z], obj.corners()]),
            obj.hi[2],
            rng,
        )
        if sight is not None:
            box, depth = sight
            seen.append(ObjectObservation(obj.label, box, depth, c))
    return seen
