"""Keeps the knowledge base current from the bus: the lidar for doors, events for people."""

from __future__ import annotations

from collections.abc import Callable

from amiro.behavior.planning.door_sensing import door_state_from_scan
from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.core import names
from amiro.core.messages import BehaviorEvent, LaserScan, Pose2D
from amiro.core.node import Node


class KnowledgeNode(Node):
    """Doors seen open or closed in each scan; people seen by a Search (``person_found``).

    The lidar cannot tell a locked door from a closed one, so a door believed locked stays
    locked until it is seen open.
    """

    def __init__(
        self,
        kb: KnowledgeBase,
        pose: Callable[[], Pose2D | None],
        max_range_m: float = 6.0,
        name: str = "knowledge",
    ) -> None:
        super().__init__(name)
        self.kb = kb
        self.pose = pose
        self.max_range_m = max_range_m

    def on_start(self) -> None:
        self.create_subscription(names.SCAN, LaserScan, self._on_scan, depth=1)
        self.create_subscription(names.EVENTS, BehaviorEvent, self._on_event, depth=1000)

    def _on_scan(self, scan: LaserScan) -> None:
        pose = self.pose()
        if pose is None:
            return
        for name, door in self.kb.topology.doors.items():
            state = door_state_from_scan(scan, pose, door.a, door.b, self.max_range_m)
            if state is None or (
                state is DoorState.CLOSED and self.kb.doors[name] is DoorState.LOCKED
            ):
                continue
            self.kb.set_door(name, state, self.now(), "lidar")

    def _on_event(self, ev: BehaviorEvent) -> None:
        if ev.type == "person_found":
            room = ev.detail.get("room")
            if isinstance(room, str) and room in self.kb.topology.rooms:
                self.kb.person_seen(str(ev.detail.get("person")), room, self.now())
