"""Actions across two runtimes as real ROS 2 actions over DDS (two rclpy participants,
loopback): amiro's MoveTo as ``amiro_interfaces/action/MoveTo``."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

from amiro.core import names
from amiro.core.bus import ActionServer, GoalHandle, GoalStatus
from amiro.core.clock import SimClock
from amiro.core.messages import Point, Pose2D
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.deploy.codecs import MoveToCodec
from amiro.navigation.move_to import MoveToFeedback, MoveToGoal, MoveToResult
from amiro.ros2.actions import ActionExporter, RemoteActionServer
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.context import RosContext
from amiro.ros2.env import ros_environment

Handle = GoalHandle[MoveToGoal, MoveToFeedback, MoveToResult]


class StepServer(Node, ActionServer[MoveToGoal, MoveToFeedback, MoveToResult]):
    """A stand-in MoveTo: one step per tick along x, ``steps`` = the goal pose's x."""

    def __init__(self) -> None:
        super().__init__("steps")
        self.active: Handle | None = None
        self.step = 0

    def on_start(self) -> None:
        self.create_action_server(names.MOVE_TO, self)
        self.create_timer(0.05, self._tick)

    def accept(self, goal: MoveToGoal) -> bool:
        return goal.pose is not None and goal.pose.x > 0

    def execute(self, handle: Handle) -> None:
        self.active, self.step = handle, 0
        assert handle.goal.pose is not None
        # at once, before rclpy has accepted the goal: it must still reach the client
        handle.publish_feedback(MoveToFeedback(Pose2D(0.0, 0.0, 0.0), handle.goal.pose.x))

    def _tick(self) -> None:
        h = self.active
        if h is None or h.done or h.goal.pose is None:
            return
        self.step += 1
        remaining = h.goal.pose.x - self.step
        h.publish_feedback(MoveToFeedback(Pose2D(float(self.step), 0.0, 0.0), remaining))
        if remaining <= 0:
            via = h.goal.person
            reason = "arrived" if via is None else f"arrived via {via.x:g},{via.y:g}"
            h.succeed(MoveToResult(True, reason, float(self.step), h.goal.pose))

    def canceled_result(self, handle: Handle) -> MoveToResult:
        return MoveToResult(False, "canceled", float(self.step))


@dataclass
class Split:
    client: Runtime
    server: Runtime
    remote: RemoteActionServer
    exporter: ActionExporter
    client_ros: RosContext
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
    remote = client.add(RemoteActionServer(a, MoveToCodec(), timeout_s=1.5))
    server.add(Ros2Bridge(b))
    server.add(StepServer())
    exporter = server.add(ActionExporter(b, MoveToCodec()))
    client.start()
    server.start()
    assert not a.wait_for_nodes(["amiro_test_server"], 10.0)
    split = Split(client, server, remote, exporter, a, b)
    yield split
    client.stop()
    if not split.crashed:
        server.stop()
    a.close()
    b.close()


def test_a_remote_goal_gets_feedback_and_its_result(split: Split) -> None:
    goal = MoveToGoal(pose=Pose2D(3.0, 1.0, 0.5), person=Point(1.0, 2.0))
    handle: Handle = split.client.bus.send_goal(names.MOVE_TO, goal)
    feedback: list[MoveToFeedback] = []
    handle.on_feedback(feedback.append)
    assert split.spin_until(lambda: handle.done, 20.0)
    assert handle.status is GoalStatus.SUCCEEDED
    assert handle.result == MoveToResult(True, "arrived via 1,2", 3.0, Pose2D(3.0, 1.0, 0.5))
    assert [f.remaining_m for f in feedback] == [3.0, 2.0, 1.0, 0.0]
    assert feedback[-1].pose == Pose2D(3.0, 0.0, 0.0)
    assert split.remote.pending == {} and split.exporter.active == {}


def test_a_remote_goal_can_be_canceled(split: Split) -> None:
    handle: Handle = split.client.bus.send_goal(names.MOVE_TO, MoveToGoal(Pose2D(10_000, 0, 0)))
    moved = lambda: handle.feedback is not None and handle.feedback.remaining_m < 10_000  # noqa: E731
    assert split.spin_until(moved, 20.0)
    handle.cancel()
    assert split.spin_until(lambda: handle.done, 20.0)
    assert handle.status is GoalStatus.CANCELED
    assert handle.result is not None and handle.result.reason == "canceled"
    assert handle.result.travelled_m >= 1.0  # the server's own canceled result crossed over


def test_a_goal_the_server_refuses_is_rejected(split: Split) -> None:
    handle: Handle = split.client.bus.send_goal(names.MOVE_TO, MoveToGoal(place="kitchen"))
    assert split.spin_until(lambda: handle.done, 20.0)
    assert handle.status is GoalStatus.REJECTED
    assert handle.result == MoveToResult(False, "rejected")


def test_a_goal_aborts_with_a_reason_when_the_server_disappears(split: Split) -> None:
    handle: Handle = split.client.bus.send_goal(names.MOVE_TO, MoveToGoal(Pose2D(10_000, 0, 0)))
    assert split.spin_until(lambda: handle.feedback is not None, 20.0)
    split.crashed = True  # the server's participant goes: no result, no goodbye to the goal
    split.server.stop()
    split.server_ros.close()
    assert split.spin_until(lambda: handle.done, 30.0, both=False)
    assert handle.status is GoalStatus.ABORTED
    assert handle.result is not None
    assert handle.result.reason.startswith(f"server_lost: no answer from {names.MOVE_TO}")


def test_a_plain_rclpy_client_sees_the_standard_status_codes(split: Split) -> None:
    """Any ROS 2 client of the type drives amiro's action: accepted, executing, succeeded."""
    from action_msgs.msg import GoalStatus as RosStatus
    from action_msgs.msg import GoalStatusArray
    from amiro_interfaces.action import MoveTo
    from rclpy.action import ActionClient

    node = split.client_ros.node
    client = ActionClient(node, MoveTo, names.MOVE_TO)
    statuses: list[int] = []
    node.create_subscription(
        GoalStatusArray,
        f"{names.MOVE_TO}/_action/status",
        lambda msg: statuses.extend(s.status for s in msg.status_list),
        10,
    )
    assert split.spin_until(client.server_is_ready, 20.0)
    goal = MoveTo.Goal(to_pose=True)
    goal.pose.x = 2.0
    sent = client.send_goal_async(goal)
    assert split.spin_until(sent.done, 20.0)
    goal_handle: Any = sent.result()
    assert goal_handle.accepted
    result = goal_handle.get_result_async()
    assert split.spin_until(result.done, 20.0)
    assert result.result().status == RosStatus.STATUS_SUCCEEDED
    assert result.result().result.success and result.result().result.reason == "arrived"
    assert split.spin_until(lambda: RosStatus.STATUS_SUCCEEDED in statuses, 10.0)
    assert RosStatus.STATUS_EXECUTING in statuses
    refused = client.send_goal_async(MoveTo.Goal(place="nowhere"))
    assert split.spin_until(refused.done, 20.0)
    assert not refused.result().accepted
    client.destroy()


def test_a_goal_request_never_starves_the_servers_ros_messages(split: Split) -> None:
    """A process following /clock spins ROS 2 alone until the clock moves; a goal request
    arriving then must not keep the clock's message from being taken (it stalled an edge)."""
    heard: list[Any] = []
    split.server_ros.subscribe("std_msgs/msg/String", "/test/tick", heard.append)
    tick = split.client_ros.publisher("std_msgs/msg/String", "/test/tick")
    handle: Handle = split.client.bus.send_goal(names.MOVE_TO, MoveToGoal(Pose2D(3.0, 0, 0)))
    deadline = time.monotonic() + 20.0
    while not heard and time.monotonic() < deadline:
        split.client.spin_for(0.01)  # the goal request goes out; the server's bus is idle
        tick.publish(split.client_ros.types.make("std_msgs/msg/String", data="t"))
        split.server_ros.spin(0.05)  # as FollowedClock.advance_to waits for /clock
    assert heard, "the server's ROS 2 messages were starved"
    assert split.spin_until(lambda: handle.done, 20.0)
    assert handle.status is GoalStatus.SUCCEEDED


def test_a_killed_server_is_noticed_by_its_liveliness(domain_id: int) -> None:
    """SIGKILL leaves no goodbye; DDS drops the participant only when its lease ends, but the
    exporter's status writer offers a short liveliness lease: the goal aborts on that, well
    before the caller's own timeout (60 s here) could end it."""
    script = Path(__file__).parent / "scripts" / "endless_move_to.py"
    server = subprocess.Popen(
        [sys.executable, str(script), str(domain_id)],
        env={**os.environ, **ros_environment(domain_id)},
        stdout=subprocess.PIPE,
        text=True,
    )
    ros = RosContext("amiro_test_caller", domain_id)
    runtime = Runtime(SimClock(speed=1.0))
    runtime.add(Ros2Bridge(ros))
    remote = runtime.add(RemoteActionServer(ros, MoveToCodec(), timeout_s=60.0))
    runtime.start()
    try:
        assert server.stdout is not None and server.stdout.readline().strip() == "serving"
        handle: Handle = runtime.bus.send_goal(names.MOVE_TO, MoveToGoal(Pose2D(5.0, 0, 0)))
        deadline = time.monotonic() + 60.0
        while handle.feedback is None and time.monotonic() < deadline:
            runtime.spin_for(0.02)
        assert handle.feedback is not None
        server.kill()
        server.wait(timeout=30)
        deadline = time.monotonic() + 50.0
        while not handle.done and time.monotonic() < deadline:
            runtime.spin_for(0.02)
    finally:
        if server.poll() is None:
            server.kill()
        runtime.stop()
        ros.close()
    assert handle.status is GoalStatus.ABORTED
    assert handle.result is not None
    assert handle.result.reason.startswith("server_lost")
    assert "stopped asserting liveliness" in handle.result.reason
    assert remote.lost and remote.pending == {}
