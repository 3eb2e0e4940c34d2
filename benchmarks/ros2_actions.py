"""Action round trip and feedback rate across two ROS 2 participants (loopback, one process).

    PYTHONPATH=src python benchmarks/ros2_actions.py [--goals 50] [--seconds 3] [--json]

Two runtimes, each with its own rclpy context, so every message goes through DDS: runtime A
calls ``/amiro/behavior/run`` through ``RemoteActionServer``, runtime B serves it through
``ActionExporter`` with a stand-in server.  Round trip: ``--goals`` goals one after the
other, each answered at once (send_goal to result, wall ms).  Feedback: one goal whose
server publishes a feedback on every 1 ms timer tick for ``--seconds``; feedback messages
received per second and their latency (the feedback carries its wall send time).  The same
script ran on the JSON-over-topics actions amiro used before (same class names and
constructor), which is how docs/ros2.md compares the two.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from typing import Any

from amiro.core import names
from amiro.core.bus import ActionServer, GoalHandle
from amiro.core.clock import SimClock
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.deploy.behaviors import BehaviorFeedback, BehaviorGoal, BehaviorResult
from amiro.deploy.interfaces import known_action
from amiro.ros2.actions import ActionExporter, RemoteActionServer
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.context import RosContext
from amiro.ros2.env import claimed_domain

Handle = GoalHandle[BehaviorGoal, BehaviorFeedback, BehaviorResult]


class EchoServer(Node, ActionServer[BehaviorGoal, BehaviorFeedback, BehaviorResult]):
    """``kind`` "now": succeed at once; "stream": a feedback per tick until canceled."""

    def __init__(self) -> None:
        super().__init__("echo")
        self.streaming: Handle | None = None
        self.count = 0

    def on_start(self) -> None:
        self.create_action_server(names.BEHAVIOR_RUN, self)
        self.create_timer(0.001, self._tick)

    def execute(self, handle: Handle) -> None:
        if handle.goal.kind == "now":
            handle.succeed(BehaviorResult(True, "completed", "r"))
        else:
            self.streaming = handle

    def _tick(self) -> None:
        h = self.streaming
        if h is not None and not h.done:
            self.count += 1
            h.publish_feedback(BehaviorFeedback(str(self.count), repr(time.perf_counter())))

    def canceled_result(self, handle: Handle) -> BehaviorResult:
        return BehaviorResult(False, "canceled")


def _stats(ms: list[float]) -> dict[str, float]:
    ordered = sorted(ms)
    return {
        "n": len(ms),
        "mean_ms": round(statistics.fmean(ms), 2),
        "p50_ms": round(ordered[len(ms) // 2], 2),
        "p95_ms": round(ordered[int(0.95 * (len(ms) - 1))], 2),
    }


def bench(goals: int, seconds: float, domain_id: int) -> dict[str, Any]:
    ros_a, ros_b = (
        RosContext("amiro_bench_caller", domain_id),
        RosContext("amiro_bench_server", domain_id),
    )
    a, b = Runtime(SimClock(speed=1.0)), Runtime(SimClock(speed=1.0))
    codec = known_action(names.BEHAVIOR_RUN)
    a.add(Ros2Bridge(ros_a))
    a.add(RemoteActionServer(ros_a, codec, 10.0))
    b.add(Ros2Bridge(ros_b))
    server = b.add(EchoServer())
    b.add(ActionExporter(ros_b, codec))
    a.start()
    b.start()

    def spin_until(done: Any, wall_s: float) -> bool:
        deadline = time.perf_counter() + wall_s
        while not done() and time.perf_counter() < deadline:
            a.spin_for(0.001)
            b.spin_for(0.001)
        return bool(done())

    try:
        ros_a.wait_for_nodes(["amiro_bench_server"], 10.0)
        first: Handle = a.bus.send_goal(names.BEHAVIOR_RUN, BehaviorGoal("now"))
        spin_until(lambda: first.done, 30.0)  # discovery done, not measured
        round_trips: list[float] = []
        for _ in range(goals):
            start = time.perf_counter()
            h: Handle = a.bus.send_goal(names.BEHAVIOR_RUN, BehaviorGoal("now"))
            if spin_until(lambda h=h: h.done, 10.0):
                round_trips.append((time.perf_counter() - start) * 1000.0)
        latencies: list[float] = []
        stream: Handle = a.bus.send_goal(names.BEHAVIOR_RUN, BehaviorGoal("stream"))
        stream.on_feedback(
            lambda fb: latencies.append((time.perf_counter() - float(fb.task)) * 1000.0)
        )
        spin_until(lambda: bool(latencies), 10.0)
        latencies.clear()
        start = time.perf_counter()
        published = server.count
        spin_until(lambda: False, seconds)
        received, sent = len(latencies), server.count - published
        elapsed = time.perf_counter() - start
        stream.cancel()
        spin_until(lambda: stream.done, 10.0)
    finally:
        a.stop()
        b.stop()
        ros_a.close()
        ros_b.close()
    return {
        "round_trip": _stats(round_trips),
        "feedback": {
            "published_per_s": round(sent / elapsed, 1),
            "received_per_s": round(received / elapsed, 1),
            "latency": _stats(latencies),
        },
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--goals", type=int, default=50)
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    with claimed_domain() as domain:
        result = bench(args.goals, args.seconds, domain)
    print(json.dumps(result, indent=None if args.json else 2))


if __name__ == "__main__":
    main()
