"""Turns notifications (environment rules, health platform, reminders) into behaviours.

Each notification kind has a handler in the registry; the notification's priority becomes
the behaviour's priority, and its id, user and the user's language go to the blackboard.
A behaviour that ends without acknowledging (for example "person not found → stop")
still owes the carers an answer, so this node acknowledges it as ``failed``.

With ``checkpoints`` on (the edge of a split deployment), each task start of a
notification's behaviour is published as a ``behavior_checkpoint`` event for the cloud to
keep, with the robot's map pose and odometry of that moment.  A notification re-sent with
its checkpoint resumes at that checkpoint's task, after the localisation is re-seeded on
``/initialpose`` where the robot now is (a restarted edge's localisation would otherwise
start at the dock).  A notification whose behaviour is still running here is a duplicate
and is ignored.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from amiro.behavior.checkpoint import Checkpoint, CheckpointError, carried
from amiro.behavior.engine import BehaviorEngine, GraphRun
from amiro.behavior.handlers import HandlerError, HandlerRegistry
from amiro.behavior.task import TaskError
from amiro.core import names
from amiro.core.messages import (
    Acknowledgement,
    BehaviorEvent,
    Header,
    Notification,
    Odometry,
    Pose2D,
    PoseStamped,
)
from amiro.core.node import Node


@dataclass(frozen=True)
class UserProfile:
    """What the robot knows of a resident: how to address them and in which language."""

    name: str
    display_name: str
    lang: str = "en"


class NotificationHandlerNode(Node):
    def __init__(
        self,
        engine: BehaviorEngine,
        handlers: HandlerRegistry,
        profiles: dict[str, UserProfile],
        checkpoints: bool = False,
    ) -> None:
        super().__init__("notifications")
        self.engine = engine
        self.handlers = handlers
        self.profiles = profiles
        self.checkpoints = checkpoints
        self.runs: dict[str, GraphRun] = {}
        self.rejected = 0
        self.duplicates = 0
        self.bad_checkpoints = 0
        self._odom: Pose2D | None = None

    def on_start(self) -> None:
        self.ack_pub = self.create_publisher(names.ACK, Acknowledgement)
        self.events = self.create_publisher(names.EVENTS, BehaviorEvent)
        self.create_subscription(names.NOTIFICATIONS, Notification, self._on_notification, 1000)
        self.create_timer(0.5, self._check_runs)
        if self.checkpoints:
            self.create_subscription(names.EVENTS, BehaviorEvent, self._on_event, 1000)
            self.create_subscription(names.ODOM, Odometry, self._on_odom, 1)
            self.initial_pose = self.create_publisher(names.INITIAL_POSE, PoseStamped)

    def _on_notification(self, note: Notification) -> None:
        running = self.runs.get(note.id)
        if running is not None and not running.done:
            self.duplicates += 1
            self.log.info("notification %s already answered by %s", note.id, running.id)
            return
        user = note.user or next(iter(self.profiles), "")  # no name: the household's first
        profile = self.profiles.get(user) or UserProfile(user, user.title())
        payload = {
            "person": profile.name,
            "name": profile.display_name,
            "lang": profile.lang,
            "notification_id": note.id,
            "reason": note.reason,
        }
        try:
            graph = self.handlers.build(note.kind, payload)
        except (HandlerError, TaskError, ValueError) as exc:
            self.rejected += 1
            self.log.warning("notification %s rejected: %s", note.id, exc)
            self._ack(note.id, "failed")
            return
        graph.priority = note.priority
        detail = {"id": note.id, "kind": note.kind, "user": note.user, "reason": note.reason}
        self.events.publish(BehaviorEvent(self.now(), "notification", detail=detail))
        checkpoint = self._checkpoint_of(note)
        if checkpoint is not None:
            self._restore_pose(note.id, checkpoint)
        self.runs[note.id] = self.engine.submit(graph, resume=checkpoint)

    def _checkpoint_of(self, note: Notification) -> Checkpoint | None:
        """The checkpoint a re-sent notification carries; None (run from the entry) if bad."""
        wire = carried(note)
        if wire is None:
            return None
        try:
            checkpoint = Checkpoint.from_dict(wire)
            if checkpoint.notification_id != note.id:
                raise CheckpointError(f"checkpoint of notification {checkpoint.notification_id!r}")
        except CheckpointError as exc:
            self.bad_checkpoints += 1
            self.log.warning("notification %s runs from the start: %s", note.id, exc)
            detail = {"id": note.id, "reason": str(exc)}
            self.events.publish(BehaviorEvent(self.now(), "resume_rejected", detail=detail))
            return None
        return checkpoint

    def _restore_pose(self, ident: str, checkpoint: Checkpoint) -> None:
        pose = checkpoint.robot_pose_now(self._odom)
        if pose is None or not self.checkpoints:
            return
        self.initial_pose.publish(PoseStamped(Header(self.now(), "map"), pose.to_pose()))
        where = {"x": round(pose.x, 3), "y": round(pose.y, 3), "theta": round(pose.theta, 3)}
        self.events.publish(
            BehaviorEvent(self.now(), "pose_restored", detail={"id": ident, **where})
        )

    def _on_odom(self, odom: Odometry) -> None:
        self._odom = odom.pose.to_pose2d()

    def _on_event(self, event: BehaviorEvent) -> None:
        """After each task start of a notification's run, publish where that run stands."""
        if event.type != "task_started":
            return
        ident = next((i for i, r in self.runs.items() if r.id == event.graph), None)
        checkpoint = None if ident is None else self.engine.checkpoint(self.runs[ident].id)
        if checkpoint is None:
            return
        nav = self.engine.modules.navigation
        pose = nav.pose if nav is not None else None
        if isinstance(pose, Pose2D):
            checkpoint = replace(checkpoint, robot_pose=pose, robot_odom=self._odom)
        detail = {"id": ident, "checkpoint": checkpoint.to_dict()}
        self.events.publish(
            BehaviorEvent(
                self.now(), "behavior_checkpoint", checkpoint.run, checkpoint.task, detail
            )
        )

    def _check_runs(self) -> None:
        for ident, run in list(self.runs.items()):
            if not run.done:
                continue
            del self.runs[ident]
            if "acked" not in run.blackboard:
                self._ack(ident, "failed")

    def _ack(self, ident: str, status: str) -> None:
        clock = self.runtime.clock
        self.ack_pub.publish(Acknowledgement(ident, status, clock.iso(self.now())))
        self.events.publish(
            BehaviorEvent(self.now(), "ack", detail={"id": ident, "status": status})
        )
