"""The bridge: bus topics out to ROS 2 and ROS 2 topics in to the bus.

Each topic crosses in one direction per process, which rules out echo loops: a process
exports what it produces (``publish``) and imports what it consumes (``subscribe``).
``remap`` renames topics on the ROS side only (a robot profile's driver names).
A message that fails to convert is counted and logged, never fatal.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import partial
from typing import Any

from amiro.core.config import ConfigError
from amiro.core.node import Node
from amiro.ros2.context import RosContext
from amiro.ros2.routes import Route, route


@dataclass
class BridgeStats:
    out: int = 0
    inbound: int = 0
    errors: int = 0


class Ros2Bridge(Node):
    def __init__(
        self,
        ros: RosContext,
        publish: Iterable[str] = (),
        subscribe: Iterable[str] = (),
        remap: Mapping[str, str] | None = None,
        pump_period: float = 0.01,
        name: str = "ros2_bridge",
    ) -> None:
        super().__init__(name)
        self.ros = ros
        self.outbound = [route(t) for t in publish]
        self.inbound = [route(t) for t in subscribe]
        both = {r.topic for r in self.outbound} & {r.topic for r in self.inbound}
        if both:
            raise ConfigError(f"topics both published and subscribed: {', '.join(sorted(both))}")
        self.remap = dict(remap or {})
        self.pump_period = pump_period
        self.stats = BridgeStats()
        self.skipped: list[str] = []  # routes whose ROS type is not installed (e.g. tf2_msgs)
        self._ros_pubs: dict[str, Any] = {}
        for r in self.outbound:
            if self._usable(r):
                self._ros_pubs[r.topic] = ros.publisher(
                    r.codec.ros_type, self.ros_name(r.topic), r.depth, r.latched
                )
        for r in self.inbound:
            if self._usable(r):
                ros.subscribe(
                    r.codec.ros_type,
                    self.ros_name(r.topic),
                    partial(self._from_ros, r),
                    r.depth,
                    r.latched,
                )

    def ros_name(self, topic: str) -> str:
        return self.remap.get(topic, topic)

    def _usable(self, r: Route) -> bool:
        if self.ros.types.available(r.codec.ros_type):
            return True
        self.skipped.append(r.topic)
        self.log.warning("%s not bridged: %s is not installed", r.topic, r.codec.ros_type)
        return False

    def on_start(self) -> None:
        for r in self.outbound:
            if r.topic in self._ros_pubs:
                self.create_subscription(
                    r.topic, r.codec.bus_type, partial(self._to_ros, r), r.depth
                )
        self.create_timer(self.pump_period, self.pump)

    def pump(self) -> None:
        """Deliver what arrived from ROS 2 (also done while a followed clock waits)."""
        self.ros.spin(0.0)

    def _to_ros(self, r: Route, msg: Any) -> None:
        try:
            ros_msg = r.codec.encode(self.ros.types, msg, self.now())
        except (ValueError, TypeError, AttributeError, AssertionError) as exc:
            self.stats.errors += 1
            self.log.warning("cannot send %s to ROS 2: %s", r.topic, exc)
            return
        self._ros_pubs[r.topic].publish(ros_msg)
        self.stats.out += 1

    def _from_ros(self, r: Route, ros_msg: Any) -> None:
        if not self.running:
            return
        try:
            msg = r.codec.decode(ros_msg)
        except (ValueError, TypeError, AttributeError, IndexError) as exc:
            self.stats.errors += 1
            self.log.warning("bad %s from ROS 2 dropped: %s", r.topic, exc)
            return
        self.stats.inbound += 1
        self.runtime.bus.publish(r.topic, msg)
