"""The bridge between two runtimes over real DDS (two rclpy participants, loopback)."""

from __future__ import annotations

import time
from collections.abc import Iterator

import numpy as np
import pytest

from amiro.core.clock import SimClock
from amiro.core.config import ConfigError
from amiro.core.messages import Header, LaserScan, Notification, String
from amiro.core.runtime import Runtime
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.context import RosContext


@pytest.fixture
def pair(domain_id: int) -> Iterator[tuple[RosContext, RosContext]]:
    a, b = RosContext("amiro_test_a", domain_id), RosContext("amiro_test_b", domain_id)
    yield a, b
    a.close()
    b.close()


def _spin(runtimes: list[Runtime], until: float) -> None:
    deadline = time.monotonic() + until
    while time.monotonic() < deadline:
        for rt in runtimes:
            rt.spin_for(0.01)


def test_topics_cross_with_remapping_and_bad_messages_are_counted(
    pair: tuple[RosContext, RosContext],
) -> None:
    a, b = pair
    ra, rb = Runtime(SimClock(speed=1.0)), Runtime(SimClock(speed=1.0))
    ra.add(Ros2Bridge(a, publish=["/scan", "/amiro/notifications"], remap={"/scan": "/base/laser"}))
    bridge_b = rb.add(
        Ros2Bridge(b, subscribe=["/scan", "/amiro/notifications"], remap={"/scan": "/base/laser"})
    )
    scans: list[LaserScan] = []
    notes: list[Notification] = []
    rb.bus.subscribe("/scan", LaserScan, scans.append)
    rb.bus.subscribe("/amiro/notifications", Notification, notes.append)
    ra.start()
    rb.start()
    assert not b.wait_for_nodes(["amiro_test_a"], 10.0)
    _spin([ra, rb], 0.5)
    ranges = np.linspace(0.5, 3.0, 50)
    ra.bus.publish(
        "/scan", LaserScan(Header(1.0, "laser"), -1.0, 1.0, 0.04, 0.0, 0.1, 0.1, 5.0, ranges)
    )
    ra.bus.publish("/amiro/notifications", Notification("n1", "maria", "hydration", 5))
    raw = a.publisher("std_msgs/msg/String", "/amiro/notifications")
    raw.publish(a.types.make("std_msgs/msg/String", data="not json"))
    _spin([ra, rb], 1.0)
    ra.stop()
    rb.stop()
    assert len(scans) == 1 and np.allclose(scans[0].ranges, ranges, atol=1e-6)
    assert scans[0].header.frame_id == "laser"
    assert notes == [Notification("n1", "maria", "hydration", 5)]
    assert bridge_b.stats.errors == 1 and bridge_b.stats.inbound == 2


def test_a_topic_cannot_cross_both_ways(pair: tuple[RosContext, RosContext]) -> None:
    with pytest.raises(ConfigError, match="both published and subscribed"):
        Ros2Bridge(pair[0], publish=["/amiro/display"], subscribe=["/amiro/display"])
    with pytest.raises(ConfigError, match="no ROS 2 route"):
        Ros2Bridge(pair[0], publish=["/nowhere"])
    assert String("x").data == "x"
