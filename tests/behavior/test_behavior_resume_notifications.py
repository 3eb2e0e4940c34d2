"""A notification re-sent with its checkpoint resumes on a restarted edge; the cloud's ledger
keeps the latest checkpoint beside the pending notification and sends it back."""

from __future__ import annotations

import math
from typing import Any

from behavior_fakes import FakeWork, run_all

from amiro.behavior import BehaviorEngine, End, EngineConfig, HandlerRegistry, TaskGraph
from amiro.behavior.checkpoint import carried, with_checkpoint
from amiro.behavior.modules import Modules
from amiro.behavior.notifications import NotificationHandlerNode, UserProfile
from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import (
    Acknowledgement,
    BehaviorEvent,
    Header,
    Notification,
    Odometry,
    Point,
    Pose2D,
    PoseStamped,
    Twist,
)
from amiro.core.runtime import Runtime
from amiro.deploy.health import NotificationLedger


class FakeNavigation:
    """The edge's navigation module, as far as checkpoints look: its pose estimate."""

    pose: Pose2D | None = Pose2D(2.0, 1.0, math.pi / 2)


def visit(payload: dict[str, Any]) -> TaskGraph:
    return (
        TaskGraph("visit", 2, blackboard=payload)
        .add(
            "find",
            FakeWork(1.0, write="position", value=Point(1.0, 2.0, 0.9)),
            on_success="go",
            on_failure=End("not_found"),
        )
        .add("go", FakeWork(2.0, value="$position"), on_success="talk")
        .add("talk", FakeWork(1.0, value="$person"))
    )


class Edge:
    """One edge process: engine, notification handler with checkpoints, a record of events."""

    def __init__(self) -> None:
        self.runtime = Runtime(SimClock())
        self.engine = self.runtime.add(
            BehaviorEngine(config=EngineConfig(), modules=Modules(navigation=FakeNavigation()))
        )
        handlers = HandlerRegistry(self.engine)
        handlers.register("visit", visit)
        profiles = {"maria": UserProfile("maria", "Maria")}
        self.node = self.runtime.add(
            NotificationHandlerNode(self.engine, handlers, profiles, checkpoints=True)
        )
        self.events: list[BehaviorEvent] = []
        self.initial_poses: list[PoseStamped] = []
        bus = self.runtime.bus
        bus.subscribe(names.EVENTS, BehaviorEvent, self.events.append, depth=1000)
        bus.subscribe(names.INITIAL_POSE, PoseStamped, self.initial_poses.append)
        self.runtime.start()

    def odom(self, pose: Pose2D) -> None:
        msg = Odometry(
            Header(self.runtime.clock.now(), "odom"), "base_footprint", pose.to_pose(), Twist()
        )
        self.runtime.bus.publish("/odom", msg)

    def notify(self, checkpoint: dict[str, Any] | None = None, ident: str = "n1") -> None:
        note = Notification(ident, "maria", "visit", 2)
        if checkpoint is not None:
            note = with_checkpoint(note, checkpoint)
        self.runtime.bus.publish(names.NOTIFICATIONS, note)

    def finish(self) -> None:
        """Deliver what was published, then run until every behaviour has ended."""
        self.runtime.spin_for(0.1)
        run_all(self.runtime, self.engine)

    def of_type(self, kind: str) -> list[BehaviorEvent]:
        return [e for e in self.events if e.type == kind]

    def started(self) -> list[str | None]:
        return [e.task for e in self.of_type("task_started")]


def checkpoint_at_go() -> dict[str, Any]:
    """The checkpoint an edge publishes when "go" starts, the robot at odometry (1, 0, 0)."""
    edge = Edge()
    edge.odom(Pose2D(1.0, 0.0, 0.0))
    edge.notify()
    assert edge.runtime.spin_until(lambda: "go" in edge.started(), 10)
    edge.runtime.spin_for(0.1)
    published = edge.of_type("behavior_checkpoint")
    assert [e.task for e in published] == ["find", "go"]
    assert all(e.detail["id"] == "n1" for e in published)
    return dict(published[-1].detail["checkpoint"])


def test_a_restarted_edge_resumes_the_checkpoint_task_where_the_robot_now_is() -> None:
    checkpoint = checkpoint_at_go()
    assert checkpoint["finished"] == [{"task": "find", "result": "success"}]
    assert checkpoint["robot_pose"] == {"x": 2.0, "y": 1.0, "theta": math.pi / 2}
    assert checkpoint["robot_odom"] == {"x": 1.0, "y": 0.0, "theta": 0.0}

    edge = Edge()  # restarted: a new engine, knowing nothing of the first run
    edge.odom(Pose2D(1.5, 0.0, 0.0))  # the base rolled 0.5 m on after the checkpoint
    edge.runtime.spin_for(0.1)
    edge.notify(checkpoint)
    edge.finish()
    assert edge.started() == ["go", "talk"]
    run = edge.node.runs["n1"]
    assert run.outcome == "completed" and run.records[0].detail == {"value": Point(1.0, 2.0, 0.9)}
    assert edge.of_type("behavior_resumed")[0].detail["finished"] == ["find"]
    # 0.5 m forward in odometry is 0.5 m along +y in the map, where the robot faced.
    (seed,) = edge.initial_poses
    assert seed.header.frame_id == "map"
    assert math.isclose(seed.pose.position.x, 2.0, abs_tol=1e-9)
    assert math.isclose(seed.pose.position.y, 1.5, abs_tol=1e-9)
    assert math.isclose(seed.pose.to_pose2d().theta, math.pi / 2, abs_tol=1e-9)
    assert edge.of_type("pose_restored")[0].detail == {
        "id": "n1",
        "x": 2.0,
        "y": 1.5,
        "theta": 1.571,
    }


def test_a_checkpoint_of_another_notification_or_a_corrupt_one_runs_from_the_start() -> None:
    checkpoint = checkpoint_at_go()
    for bad in ({**checkpoint, "blackboard": {"notification_id": "n9"}}, {"task": 3}):
        edge = Edge()
        edge.notify(bad)
        edge.finish()
        assert edge.started() == ["find", "go", "talk"]
        assert edge.node.bad_checkpoints == 1 and not edge.initial_poses
        assert len(edge.of_type("resume_rejected")) == 1


def test_a_notification_whose_behaviour_still_runs_is_not_run_twice() -> None:
    edge = Edge()
    edge.notify()
    assert edge.runtime.spin_until(lambda: "go" in edge.started(), 10)
    edge.notify()  # re-sent after a missed heartbeat, though this edge never stopped
    edge.finish()
    assert edge.node.duplicates == 1 and len(edge.engine.runs) == 1
    assert edge.started() == ["find", "go", "talk"]


def test_the_ledger_sends_the_latest_checkpoint_back_with_the_pending_notification() -> None:
    runtime = Runtime(SimClock())
    ledger = runtime.add(NotificationLedger(edge="edge", resend_delay_s=1.0))
    sent: list[Notification] = []
    events: list[BehaviorEvent] = []
    runtime.bus.subscribe(names.NOTIFICATIONS, Notification, sent.append, depth=100)
    runtime.bus.subscribe(names.EVENTS, BehaviorEvent, events.append, depth=100)
    runtime.start()
    bus = runtime.bus

    def checkpoint_event(ident: str, task: str) -> BehaviorEvent:
        detail = {"id": ident, "checkpoint": {"task": task}}
        return BehaviorEvent(runtime.clock.now(), "behavior_checkpoint", "visit#1", task, detail)

    bus.publish(names.NOTIFICATIONS, Notification("n1", "maria", "visit", 2))
    runtime.spin_for(0.1)
    bus.publish(names.EVENTS, checkpoint_event("n1", "find"))
    bus.publish(names.EVENTS, checkpoint_event("n1", "go"))
    bus.publish(names.EVENTS, checkpoint_event("n7", "go"))  # not pending: not kept
    bus.publish(
        names.EVENTS, BehaviorEvent(runtime.clock.now(), "node_back", detail={"node": "edge"})
    )
    runtime.spin_for(1.5)
    assert ledger.checkpoints == {"n1": {"task": "go"}}
    resent = sent[1:]
    assert [(n.id, carried(n)) for n in resent] == [("n1", {"task": "go"})]
    redelivered = [e for e in events if e.type == "notification_redelivered"]
    assert [e.detail for e in redelivered] == [{"id": "n1", "resume_task": "go"}]

    bus.publish(names.ACK, Acknowledgement("n1", "done", "2026-01-01T00:00:00"))
    runtime.spin_for(0.1)
    assert ledger.pending == {} and ledger.checkpoints == {}
