"""What the robot believes about its home: door states, where people are, who helps.

Beliefs start from the map (every door open, as the map shows it) and what the household
profile says (the rooms people are usually in), then change only with what the robot finds
out: a door seen closed by the lidar, a crossing that failed, a person seen in a room, a request
for help refused.  Every change bumps :attr:`KnowledgeBase.version` and is kept in
:attr:`KnowledgeBase.changes`, so the executive can tell whether its plan still holds.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field

from amiro.behavior.planning.topology import Topology
from amiro.core.config import ConfigError
from amiro.core.messages import Point


class DoorState(enum.StrEnum):
    OPEN = "open"
    CLOSED = "closed"  # a person can open it
    LOCKED = "locked"  # nobody at home can


@dataclass(frozen=True, slots=True)
class Change:
    t: float
    fact: str
    value: str
    source: str

    def to_dict(self) -> dict[str, object]:
        return {
            "t": round(self.t, 3),
            "fact": self.fact,
            "value": self.value,
            "source": self.source,
        }


@dataclass
class PersonBelief:
    room: str | None = None  # None: whereabouts unknown
    position: Point | None = None
    not_in: set[str] = field(default_factory=set)  # rooms searched in vain
    willing: bool = True  # may be asked for help


class KnowledgeBase:
    """Beliefs over one :class:`Topology`; every update says where it came from."""

    def __init__(self, topology: Topology, people: dict[str, str | None] | None = None) -> None:
        self.topology = topology
        self.doors: dict[str, DoorState] = dict.fromkeys(topology.doors, DoorState.OPEN)
        self.people: dict[str, PersonBelief] = {}
        self.blocked: set[str] = set()
        self.changes: list[Change] = []
        self.version = 0
        for name, room in (people or {}).items():
            self._check_room(room)
            self.people[name] = PersonBelief(room)

    def _check_room(self, room: str | None) -> None:
        if room is not None and room not in self.topology.rooms:
            raise ConfigError(f"unknown room {room!r} (rooms: {', '.join(self.topology.rooms)})")

    def _changed(self, t: float, fact: str, value: str, source: str) -> None:
        self.version += 1
        self.changes.append(Change(t, fact, value, source))

    def set_door(self, door: str, state: DoorState, t: float, source: str) -> bool:
        """Record a door's state; True when the belief changed."""
        if door not in self.doors:
            raise ConfigError(f"unknown door {door!r} (doors: {', '.join(self.doors)})")
        if self.doors[door] is state:
            return False
        self.doors[door] = state
        self._changed(t, f"door {door}", str(state), source)
        return True

    def person(self, name: str) -> PersonBelief:
        return self.people.setdefault(name, PersonBelief())

    def person_seen(
        self, name: str, room: str | None, t: float, position: Point | None = None
    ) -> bool:
        self._check_room(room)
        belief = self.person(name)
        moved = belief.room != room
        belief.position = position
        if room is not None:
            belief.not_in.discard(room)
        if moved:
            belief.room = room
            self._changed(t, f"person {name}", room or "unknown", "seen")
        return moved

    def person_not_found(self, name: str, room: str, t: float) -> None:
        """A search of ``room`` failed: the person is elsewhere, nobody knows where."""
        self._check_room(room)
        belief = self.person(name)
        belief.not_in.add(room)
        belief.room, belief.position = None, None
        self._changed(t, f"person {name}", f"not in {room}", "search")

    def declined(self, name: str, t: float) -> None:
        belief = self.person(name)
        if belief.willing:
            belief.willing = False
            self._changed(t, f"person {name}", "will not help", "dialogue")

    def set_blocked(self, waypoint: str, blocked: bool, t: float, source: str) -> None:
        if (waypoint in self.blocked) == blocked:
            return
        (self.blocked.add if blocked else self.blocked.discard)(waypoint)
        self._changed(t, f"waypoint {waypoint}", "blocked" if blocked else "clear", source)

    def candidate_rooms(self, name: str) -> list[str]:
        """Rooms the person may be in: their known room, else every room not yet searched."""
        belief = self.person(name)
        if belief.room is not None:
            return [belief.room]
        return [r for r in self.topology.rooms if r not in belief.not_in]

    def snapshot(self) -> dict[str, object]:
        return {
            "doors": {d: str(s) for d, s in self.doors.items()},
            "people": {n: b.room for n, b in self.people.items()},
            "blocked": sorted(self.blocked),
        }
