"""Bridge benchmarks: latency and throughput over ROS 2 (loopback) beside the in-process bus.

Two participants in this process (two rclpy contexts, so traffic really goes through DDS):
runtime A exports a topic, runtime B imports it.  Latency is publish-to-delivery on B for a
message sent at a fixed rate (a 720-beam LaserScan at 10 Hz, a small String at
100 Hz); throughput is how
many messages B receives per second when A publishes as fast as it can.  Wall time here only
measures speed, never drives behaviour.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from amiro.core import names
from amiro.core.clock import SimClock, wall_seconds
from amiro.core.messages import Header, LaserScan, String
from amiro.core.runtime import Runtime
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.context import RosContext


def _scan(seq: int) -> LaserScan:
    ranges = np.full(720, 4.0) + 0.001 * seq
    return LaserScan(
        Header(float(seq), "laser"), -np.pi, np.pi, 2 * np.pi / 720, 0.0, 0.1, 0.05, 10.0, ranges
    )


def _string(seq: int) -> String:
    return String(f"{seq}")


def _stats(ms: list[float]) -> dict[str, float]:
    if not ms:
        return {"n": 0}
    ordered = sorted(ms)
    return {
        "n": len(ms),
        "mean_ms": round(statistics.fmean(ms), 3),
        "p50_ms": round(ordered[len(ms) // 2], 3),
        "p95_ms": round(ordered[int(0.95 * (len(ms) - 1))], 3),
    }


def _measure(
    a: Runtime,
    b: Runtime,
    topic: str,
    msg_type: type,
    make: Callable[[int], Any],
    seconds: float,
    rate_hz: float,
) -> dict[str, Any]:
    sent: dict[int, float] = {}
    latencies: list[float] = []
    received = 0

    def on_msg(msg: Any) -> None:
        nonlocal received
        received += 1
        seq = int(msg.header.stamp) if isinstance(msg, LaserScan) else int(msg.data)
        if seq in sent:
            latencies.append((wall_seconds() - sent.pop(seq)) * 1000.0)

    sub = b.bus.subscribe(topic, msg_type, on_msg, depth=10_000)

    def pump() -> None:
        a.bus.spin_some()
        b.bus.spin_some()
        b.nodes["ros2_bridge"].pump()  # type: ignore[attr-defined]
        b.bus.spin_some()

    seq = 0
    end = wall_seconds() + seconds
    while wall_seconds() < end:  # latency at the sensor's rate
        seq += 1
        sent[seq] = wall_seconds()
        a.bus.publish(topic, make(seq))
        tick = wall_seconds() + 1.0 / rate_hz
        while wall_seconds() < tick:
            pump()
    received = 0
    start = wall_seconds()
    end = start + seconds
    while wall_seconds() < end:  # throughput: publish flat out, count what arrives
        seq += 1
        a.bus.publish(topic, make(seq))
        pump()
    drain = wall_seconds() + 0.5
    while wall_seconds() < drain:
        pump()
    sub.destroy()
    return {"latency": _stats(latencies), "throughput_msgs_s": round(received / seconds, 1)}


def _in_process(make: Callable[[int], Any], msg_type: type, seconds: float) -> dict[str, Any]:
    rt = Runtime(SimClock())
    count = 0

    def on_msg(msg: Any) -> None:
        nonlocal count
        count += 1

    rt.bus.subscribe("/x", msg_type, on_msg, depth=10_000)
    start = wall_seconds()
    seq = 0
    while wall_seconds() - start < seconds:
        seq += 1
        rt.bus.publish("/x", make(seq))
        rt.bus.spin_some()
    per_msg_ms = 1000.0 * seconds / max(count, 1)  # publish + delivery, one at a time
    return {"latency_ms": round(per_msg_ms, 4), "throughput_msgs_s": round(count / seconds, 1)}


def bench_bridge(seconds: float = 3.0, domain_id: int | None = None) -> dict[str, Any]:
    topics = [names.SCAN, names.DISPLAY]
    ros_a, ros_b = RosContext("amiro_bench_a", domain_id), RosContext("amiro_bench_b", domain_id)
    a, b = Runtime(SimClock()), Runtime(SimClock())
    a.add(Ros2Bridge(ros_a, publish=topics))
    b.add(Ros2Bridge(ros_b, subscribe=topics))
    a.start()
    b.start()
    try:
        ros_b.wait_for_nodes(["amiro_bench_a"], 10.0)
        time.sleep(1.0)  # let the publishers and subscriptions match
        ros_b.spin(0.1)
        result = {
            "laser_scan_720": _measure(a, b, names.SCAN, LaserScan, _scan, seconds, 10.0),
            "string_small": _measure(a, b, names.DISPLAY, String, _string, seconds, 100.0),
            "in_process_bus": {
                "laser_scan_720": _in_process(_scan, LaserScan, seconds / 3),
                "string_small": _in_process(_string, String, seconds / 3),
            },
        }
    finally:
        a.stop()
        b.stop()
        ros_a.close()
        ros_b.close()
    return result
