"""``perception.backend: hri``: people as another HRI stack sees them, over ROS4HRI.

A ROS 2 deployment's edge with this backend listens to ``/humans/persons/tracked`` and the
``person_<id>`` frames (:class:`amiro.ros2.hri.HriListener`) and puts them on the bus as
:class:`~amiro.core.messages.People` on ``/amiro/hri/people``; this finder answers ``look``
with the persons of the latest message, their recognised names and map positions.
"""

from __future__ import annotations

from amiro.core import names
from amiro.core.bus import Bus
from amiro.core.config import ConfigError
from amiro.core.messages import People
from amiro.perception.ports import PeopleFinder, SeenPerson
from amiro.perception.stack import PerceptionInputs


class HriPeopleFinder:
    """Who the HRI stack tracks now (the latest ``People``; empty before the first)."""

    def __init__(self, bus: Bus, topic: str = names.HRI_PEOPLE) -> None:
        self.latest: People | None = None
        bus.subscribe(topic, People, self._on_people, depth=1)

    def _on_people(self, msg: People) -> None:
        self.latest = msg

    def look(self) -> list[SeenPerson]:
        if self.latest is None:
            return []
        return [
            SeenPerson(p.name, p.position, p.confidence, track_id=p.id) for p in self.latest.people
        ]


def hri_people_finder(inputs: PerceptionInputs) -> PeopleFinder:
    if inputs.bus is None:
        raise ConfigError(
            "perception.backend: hri reads ROS4HRI through a ROS 2 deployment's edge "
            "(amiro node / amiro launch)"
        )
    return HriPeopleFinder(inputs.bus)
