"""Turns notifications (environment rules, health platform, reminders) into behaviours.

Each notification kind has a handler in the registry; the notification's priority becomes
the behaviour's priority, and its id, user and the user's language go to the blackboard.
A behaviour that ends without acknowledging (for example "person not found → stop")
still owes the carers an answer, so this node acknowledges it as ``failed``.
"""

from __future__ import annotations

from dataclasses import dataclass

from amiro.behavior.engine import EVENTS_TOPIC, BehaviorEngine, GraphRun
from amiro.behavior.handlers import HandlerError, HandlerRegistry
from amiro.behavior.task import TaskError
from amiro.behavior.tasks.notify import ACK_TOPIC
from amiro.core.messages import Acknowledgement, BehaviorEvent, Notification
from amiro.core.node import Node
from amiro.environment.topics import NOTIFICATIONS_TOPIC


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
    ) -> None:
        super().__init__("notifications")
        self.engine = engine
        self.handlers = handlers
        self.profiles = profiles
        self.runs: dict[str, GraphRun] = {}
        self.rejected = 0

    def on_start(self) -> None:
        self.ack_pub = self.create_publisher(ACK_TOPIC, Acknowledgement)
        self.events = self.create_publisher(EVENTS_TOPIC, BehaviorEvent)
        self.create_subscription(NOTIFICATIONS_TOPIC, Notification, self._on_notification, 1000)
        self.create_timer(0.5, self._check_runs)

    def _on_notification(self, note: Notification) -> None:
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
        self.runs[note.id] = self.engine.submit(graph)

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
