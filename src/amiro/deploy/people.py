"""The people the edge tracks, for the cloud's dashboard.

Only the edge's perception knows where people are: :class:`TrackedPeoplePublisher` sends
its tracker's confirmed tracks (map frame, people_msgs/People-like) on ``/amiro/people``
every ``period_s``, an empty list once they are forgotten, and :func:`dashboard_people`
turns the message into the dashboard's ``people`` entries, the embedded system's shape.
The tracker is read, not driven: people appear as the robot's behaviours look at them.
"""

from __future__ import annotations

from typing import Any

from amiro.core import names
from amiro.core.messages import Header, People, Person
from amiro.core.node import Node
from amiro.perception.camera_finder import CameraPeopleFinder
from amiro.perception.ports import PeopleFinder
from amiro.perception.stack import SimPeopleFinder
from amiro.perception.tracking import PeopleTracker


def finder_tracker(finder: PeopleFinder) -> PeopleTracker | None:
    """The tracker behind a people finder; None for a finder without one (the oracle)."""
    if isinstance(finder, SimPeopleFinder | CameraPeopleFinder):
        return finder.tracker
    return None


class TrackedPeoplePublisher(Node):
    def __init__(self, tracker: PeopleTracker, period_s: float = 1.0) -> None:
        super().__init__("tracked_people")
        self.tracker = tracker
        self.period_s = period_s

    def on_start(self) -> None:
        self.pub = self.create_publisher(names.PEOPLE, People)
        self.create_timer(self.period_s, self._publish)

    def _publish(self) -> None:
        now, forget_s = self.now(), self.tracker.cfg.forget_s
        people = tuple(
            Person(t.id, t.name, t.position, round(t.score, 3))
            for t in self.tracker.tracks
            if t.confirmed and now - t.last_seen <= forget_s
        )
        self.pub.publish(People(Header(now, "map"), people))


def dashboard_people(people: People | None) -> list[dict[str, Any]]:
    """``people`` as the dashboard shows them (:class:`~amiro.web.robot.SystemRobot`'s
    entries; the activity is not known across processes)."""
    if people is None:
        return []
    return [
        {
            "name": p.name or p.id,
            "x": round(p.position.x, 2),
            "y": round(p.position.y, 2),
            "activity": "",
        }
        for p in people.people
    ]
