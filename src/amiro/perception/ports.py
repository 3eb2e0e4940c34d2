"""The perception port the behaviour tasks use."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from amiro.core.messages import Point


@dataclass(frozen=True)
class SeenPerson:
    """A person seen now: identity if the face was recognised, position in the map frame."""

    name: str | None
    position: Point
    confidence: float


class PeopleFinder(Protocol):
    def look(self) -> list[SeenPerson]:
        """Who the robot's camera sees at this moment."""
        ...
