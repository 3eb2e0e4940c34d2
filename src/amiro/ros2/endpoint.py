"""The common part of every service and action bridge: JSON topics in and out of ROS 2.

ROS 2 callbacks only queue what arrived on a private bus topic; it is handled when the bus
spins.  So a blocking service call, which spins ROS 2 while it waits, never re-enters the
behaviour engine or an action server, and all bus-side work stays on the runtime's thread.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

from amiro.core.node import Node
from amiro.ros2.context import RosContext
from amiro.ros2.convert import STRING
from amiro.ros2.interfaces import WireError


@dataclass(frozen=True, slots=True)
class Inbound:
    """One message from ROS 2: which of the endpoint's topics (``kind``) and the message."""

    kind: str
    msg: Any


@dataclass
class EndpointStats:
    sent: int = 0
    received: int = 0
    errors: int = 0  # malformed or unexpected messages, dropped


class WireEndpoint(Node):
    """A node between rclpy and the bus: what rclpy's callbacks hand it is queued and acted
    on when the bus spins (services: JSON over ``<name>/<kind>`` std_msgs/String topics)."""

    def __init__(self, ros: RosContext, name: str, node_name: str) -> None:
        super().__init__(node_name)
        self.ros = ros
        self.interface = name
        self.stats = EndpointStats()
        self._pubs: dict[str, Any] = {}
        self._inbox = f"/amiro/ros2/inbox/{node_name}{name}"

    def ros_topic(self, kind: str) -> str:
        return f"{self.interface}/{kind}"

    def outgoing(self, kind: str, type_name: str = STRING, depth: int = 100) -> None:
        self._pubs[kind] = self.ros.publisher(type_name, self.ros_topic(kind), depth)

    def incoming(self, kind: str, type_name: str = STRING, depth: int = 100) -> None:
        self.ros.subscribe(
            type_name, self.ros_topic(kind), lambda msg: self._queue(kind, msg), depth
        )

    def _queue(self, kind: str, msg: Any) -> None:
        if self.running:
            self.runtime.bus.publish(self._inbox, Inbound(kind, msg))

    def on_start(self) -> None:
        self.create_subscription(self._inbox, Inbound, self._dispatch, depth=10_000)

    def _dispatch(self, msg: Inbound) -> None:
        self.stats.received += 1
        try:
            self.handle(msg.kind, msg.msg)
        except WireError as exc:
            self.stats.errors += 1
            self.log.warning("bad %s on %s dropped: %s", msg.kind, self.interface, exc)

    def handle(self, kind: str, msg: Any) -> None:
        """Act on one ROS 2 message; raise :class:`WireError` for a malformed one."""
        raise NotImplementedError

    def send(self, kind: str, data: dict[str, Any]) -> None:
        text = json.dumps(data, separators=(",", ":"))
        self.send_ros(kind, self.ros.types.make(STRING, data=text))

    def send_ros(self, kind: str, ros_msg: Any) -> None:
        self._pubs[kind].publish(ros_msg)
        self.stats.sent += 1
