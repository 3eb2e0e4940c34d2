"""Messages only the simulator speaks: ground truth for oracles and scoring, sim events."""

from __future__ import annotations

from dataclasses import dataclass

from amiro.core.messages import BoundingBox2D, Point


@dataclass(frozen=True, slots=True)
class Collision:
    """The base touched an obstacle (one per new contact, not one per tick)."""

    stamp: float
    x: float
    y: float
    theta: float
    count: int


@dataclass(frozen=True, slots=True)
class CameraObservation:
    """One resident as the head camera sees them, plus ground truth for oracles.

    ``bbox`` is in pixels of the RGB image, ``depth`` the noisy z-depth (metres along the
    optical axis) of the torso, ``position`` the true torso centre in the map frame.
    """

    name: str
    bbox: BoundingBox2D
    depth: float
    face_visible: bool
    backlit: bool
    position: Point
    posture: str
    activity: str
    skeleton_occluded: bool
