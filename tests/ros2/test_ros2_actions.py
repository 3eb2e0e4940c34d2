"""Actions across two runtimes over real DDS (two rclpy participants, loopback)."""

from __future__ import annotations

import enum
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

import pytest

from amiro.core.bus import ActionServer, GoalHandle, GoalStatus
from amiro.core.clock import SimClock
from amiro.core.messages import Point, Pose2D
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.ros2.actions import ActionExporter, RemoteActionServer
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.context import RosContext
from amiro.ros2.interfaces import action_spec

TRIP = "/test/trip"


class Pace(enum.Enum):
    SLOW = "slow"
    FAST = "fast"


@dataclass(frozen=True)
class TripGoal:
    target: Pose2D
    steps: int
    pace: Pace = Pace.FAST
    via: Point | None = None


@dataclass(frozen=True)
class TripFeedback:
    step: int
    pose: Pose2D


@dataclass(frozen=True)
class TripResult:
    success: bool
    reason: str
    final: Pose2D | None = None


SPEC = action_spec(TRIP, TripGoal, TripFeedback, TripResult, lambda r: TripResult(False, r))
Handle = GoalHandle[TripGoal, TripFeedback, TripResult]


class TripServer(Node, ActionServer[TripGoal, TripFeedback, TripResult]):
    """Moves one step per tick, reports each step, arrives after ``goal.steps``."""

    def __init__(self) -> None:
        super().__init__("trip")
        self.active: Handle | None = None
        self.step = 0

    def on_start(self) -> None:
        self.create_action_server(TRIP, self)
        self.create_timer(0.05, self._tick)

    def accept(self, goal: TripGoal) -> bool:
        return goal.steps > 0

    def execute(self, handle: Handle) -> None:
        self.active, self.step = handle, 0

    def _tick(self) -> None:
        h = self.active
        if h is None or h.done:
            return
        self.step += 1
        h.publish_feedback(TripFeedback(self.step, Pose2D(float(self.step), 0.0, 0.0)))
        if self.step >= h.goal.steps:
            h.succeed(TripResult(True, f"arrived {h.goal.pace.value}", h.goal.target))

    def canceled_result(self, handle: Handle) -> TripResult:
        return TripResult(False, "canceled")


@dataclass
class Split:
    client: Runtime
    server: Runtime
    remote: RemoteActionServer
    exporter: ActionExporter
    server_ros: RosContext
    crashed: bool = False

    def spin_until(self, done: Callable[[], bool], wall_s: float, both: bool = True) -> bool:
        deadline = time.monotonic() + wall_s
        while not done() and time.monotonic() < deadline:
            self.client.spin_for(0.01)
            if both:
                self.server.spin_for(0.01)
        return done()


@pytest.fixture
def split(domain_id: int) -> Iterator[Split]:
    a, b = RosContext("amiro_test_caller", domain_id), RosContext("amiro_test_server", domain_id)
    client, server = Runtime(SimClock(speed=1.0)), Runtime(SimClock(speed=1.0))
    client.add(Ros2Bridge(a))  # an empty bridge only pumps ROS 2
    remote = client.add(RemoteActionServer(a, SPEC, timeout_s=1.5))
    server.add(Ros2Bridge(b))
    server.add(TripServer())
    exporter = server.add(ActionExporter(b, SPEC, status_period=0.2))
    client.start()
    server.start()
    assert not a.wait_for_nodes(["amiro_test_server"], 10.0)
    split = Split(client, server, remote, exporter, b)
    yield split
    client.stop()
    if not split.crashed:
        server.stop()
    a.close()
    b.close()


def test_a_remote_goal_gets_feedback_and_its_result(split: Split) -> None:
    goal = TripGoal(Pose2D(3.0, 1.0, 0.5), steps=3, pace=Pace.SLOW, via=Point(1.0, 2.0))
    handle: Handle = split.client.bus.send_goal(TRIP, goal)
    feedback: list[TripFeedback] = []
    handle.on_feedback(feedback.append)
    assert split.spin_until(lambda: handle.done, 10.0)
    assert handle.status is GoalStatus.SUCCEEDED
    assert handle.result == TripResult(True, "arrived slow", Pose2D(3.0, 1.0, 0.5))
    assert [f.step for f in feedback] == [1, 2, 3]
    assert feedback[-1].pose == Pose2D(3.0, 0.0, 0.0)
    assert split.remote.pending == {} and split.exporter.active == {}


def test_a_remote_goal_can_be_canceled(split: Split) -> None:
    handle: Handle = split.client.bus.send_goal(TRIP, TripGoal(Pose2D(), steps=10_000))
    assert split.spin_until(lambda: handle.feedback is not None, 10.0)
    handle.cancel()
    assert split.spin_until(lambda: handle.done, 10.0)
    assert handle.status is GoalStatus.CANCELED
    assert handle.result == TripResult(False, "canceled")


def test_a_goal_the_server_refuses_is_rejected(split: Split) -> None:
    handle: Handle = split.client.bus.send_goal(TRIP, TripGoal(Pose2D(), steps=0))
    assert split.spin_until(lambda: handle.done, 10.0)
    assert handle.status is GoalStatus.REJECTED
    assert handle.result == TripResult(False, "rejected")


def test_a_goal_aborts_with_a_reason_when_the_server_disappears(split: Split) -> None:
    handle: Handle = split.client.bus.send_goal(TRIP, TripGoal(Pose2D(), steps=10_000))
    assert split.spin_until(lambda: handle.feedback is not None, 10.0)
    split.crashed = True  # the server process dies: no status, no result, no goodbye
    split.server_ros.close()
    assert split.spin_until(lambda: handle.done, 10.0, both=False)
    assert handle.status is GoalStatus.ABORTED
    assert handle.result is not None
    assert handle.result.reason.startswith("server_lost: no answer from /test/trip")


def test_malformed_messages_are_counted_and_dropped(split: Split) -> None:
    ros = split.server_ros
    junk = ros.publisher("std_msgs/msg/String", f"{TRIP}/goal")
    bad_results = ros.publisher("std_msgs/msg/String", f"{TRIP}/result")
    bad: list[dict[str, Any]] = [
        {"goal_id": "not-a-uuid", "goal": {}},
        {"goal_id": "0b7a0d3c-5f59-4a43-9f39-5ae2d8a39f1b", "goal": {"steps": "many"}},
    ]
    split.spin_until(lambda: False, 0.3)
    handle: Handle = split.client.bus.send_goal(TRIP, TripGoal(Pose2D(), steps=200))
    assert split.spin_until(lambda: handle.feedback is not None, 10.0)
    (goal_id,) = split.remote.pending
    for text in ["not json", "[1, 2]", *map(_json, bad)]:
        junk.publish(ros.types.make("std_msgs/msg/String", data=text))
    bad_results.publish(
        ros.types.make("std_msgs/msg/String", data=_json({"goal_id": goal_id, "status": "x"}))
    )
    assert split.spin_until(lambda: split.remote.stats.errors >= 1, 5.0)
    assert split.spin_until(lambda: split.exporter.stats.errors >= 4, 5.0)
    assert not handle.done  # the bad result did not end the goal
    handle.cancel()
    assert split.spin_until(lambda: handle.done, 10.0)
    assert handle.status is GoalStatus.CANCELED


def _json(data: object) -> str:
    import json

    return json.dumps(data)
