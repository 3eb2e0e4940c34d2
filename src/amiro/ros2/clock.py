"""Shared simulated time across processes: the robot process owns it, the others follow.

The simulator publishes ``/clock`` (rosgraph_msgs/Clock, as ``use_sim_time`` expects);
the edge and cloud run on a :class:`FollowedClock` whose ``advance_to`` waits for that time
to arrive, spinning rclpy meanwhile so bridged messages keep flowing.
"""

from __future__ import annotations

import time
from datetime import datetime, timedelta

from amiro.core import names
from amiro.core.clock import SIM_EPOCH
from amiro.core.node import Node
from amiro.ros2.context import RosContext
from amiro.ros2.convert import ros_time, seconds

CLOCK_TYPE = "rosgraph_msgs/msg/Clock"


class ClockPublisher(Node):
    """Publishes the runtime's time on ``/clock`` every ``period`` seconds of it."""

    def __init__(self, ros: RosContext, period: float = 0.02) -> None:
        super().__init__("clock")
        self.ros = ros
        self.period = period
        self.pub = ros.publisher(CLOCK_TYPE, names.CLOCK, depth=1)

    def on_start(self) -> None:
        self.publish()
        self.create_timer(self.period, self.publish)

    def publish(self) -> None:
        types = self.ros.types
        self.pub.publish(types.make(CLOCK_TYPE, clock=ros_time(types, self.now())))


class ClockStoppedError(RuntimeError):
    """The followed clock was told to stop (shutdown) while waiting."""


class FollowedClock:
    """The time of another process's ``/clock``; implements amiro's Clock protocol."""

    def __init__(self, ros: RosContext, epoch: datetime = SIM_EPOCH) -> None:
        self.ros = ros
        self.epoch = epoch
        self._now = 0.0
        self.received = 0
        self.stopping = False
        ros.subscribe(CLOCK_TYPE, names.CLOCK, self._on_clock, depth=1)

    def _on_clock(self, msg: object) -> None:
        self._now = max(self._now, seconds(msg.clock))  # type: ignore[attr-defined]
        self.received += 1

    def now(self) -> float:
        return self._now

    def iso(self, t: float) -> str:
        return (self.epoch + timedelta(seconds=t)).isoformat(timespec="seconds")

    def advance_to(self, t: float) -> None:
        while self._now < t:
            if self.stopping:
                raise ClockStoppedError("clock stopped")
            self.ros.spin(0.05)

    def wait_first(self, timeout_s: float) -> bool:
        """Wait (wall time) for the first ``/clock``; False if none came."""
        deadline = time.monotonic() + timeout_s
        while self.received == 0 and time.monotonic() < deadline and not self.stopping:
            self.ros.spin(0.1)
        return self.received > 0
