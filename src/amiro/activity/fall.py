"""Fall detection: a ``fall`` notification when the activity model sees someone fall.

The monitor looks at every resident in view on a timer; ``confirmations`` consecutive
"falling" readings publish a :class:`Notification` of kind ``fall`` (priority
:data:`FALL_PRIORITY`, that of data/behaviors/fall.yaml), as the environment's rules do, and
a ``fall_detected`` event.  The notification handler turns it into the fall behaviour, which
preempts whatever the robot is doing; a ledger keeps it until it is acknowledged.

One alert per person while a fall notification for them is open: seen on the bus (raised
here, or re-sent by a ledger after a restart) and not yet acknowledged.  The handler
acknowledges when the fall behaviour ends, so the bus alone says when a run is over and
this capability needs no behaviour engine.  A notification left unacknowledged for
``realert_s`` (no handler running, a lost message) no longer holds alerts back, so a missing
answer cannot silence the monitor for good.
"""

from __future__ import annotations

import itertools
import logging
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from amiro.activity.ports import ActivityRecognizer
from amiro.core import names
from amiro.core.messages import Acknowledgement, BehaviorEvent, Notification
from amiro.core.node import Node

log = logging.getLogger("amiro.activity.fall")

FALL_KIND = "fall"
FALL_LABEL = "falling"
FALL_PRIORITY = 100  # the fall behaviour's: above every other, so it preempts them


@dataclass(frozen=True, slots=True)
class _OpenAlert:
    person: str
    since: float


class FallMonitorNode(Node):
    def __init__(
        self,
        recognizer: ActivityRecognizer,
        people: Callable[[], Iterable[str]],
        period_s: float = 0.5,
        confirmations: int = 2,
        realert_s: float = 300.0,
        name: str = "fall_monitor",
    ) -> None:
        super().__init__(name)
        self.recognizer = recognizer
        self.people = people
        self.period_s = period_s
        self.confirmations = confirmations
        self.realert_s = realert_s
        self.streaks: dict[str, int] = {}
        self.open: dict[str, _OpenAlert] = {}  # unacknowledged fall notifications by id
        self.alerts: list[str] = []  # people a fall was raised for, in order
        self._count = itertools.count(1)

    def on_start(self) -> None:
        self.pub_events = self.create_publisher(names.EVENTS, BehaviorEvent)
        self.pub_notes = self.create_publisher(names.NOTIFICATIONS, Notification)
        self.create_subscription(names.NOTIFICATIONS, Notification, self._on_notification, 100)
        self.create_subscription(names.ACK, Acknowledgement, self._on_ack, 1000)
        self.create_timer(self.period_s, self._check)

    def _on_notification(self, note: Notification) -> None:
        if note.kind == FALL_KIND and note.id not in self.open:
            self.open[note.id] = _OpenAlert(note.user, self.now())

    def _on_ack(self, ack: Acknowledgement) -> None:
        self.open.pop(ack.id, None)

    def _check(self) -> None:
        now = self.now()
        for ident, alert in list(self.open.items()):
            if now - alert.since >= self.realert_s:
                log.warning(
                    "fall notification %s unanswered: alerts for %s re-armed", ident, alert.person
                )
                del self.open[ident]
        alerted = {alert.person for alert in self.open.values()}
        for person in self.people():
            if person in alerted:
                continue
            reading = self.recognizer.observe(person)
            streak = self.streaks.get(person, 0) + 1 if reading.label == FALL_LABEL else 0
            self.streaks[person] = streak
            if streak >= self.confirmations:
                self._raise(person, reading.confidence)

    def _raise(self, person: str, confidence: float) -> None:
        self.streaks[person] = 0
        self.alerts.append(person)
        log.warning("fall detected: %s (confidence %.2f)", person, confidence)
        # unique across restarts too (a ledger keys on it): the clock time and a count
        ident = f"{FALL_KIND}-{person}-{self.runtime.clock.iso(self.now())}-{next(self._count)}"
        self.open[ident] = _OpenAlert(person, self.now())
        self.pub_events.publish(
            BehaviorEvent(
                self.now(),
                "fall_detected",
                FALL_KIND,
                "",
                {"person": person, "confidence": confidence, "notification": ident},
            )
        )
        reason = f"{person} fell (confidence {confidence:.2f})"
        self.pub_notes.publish(Notification(ident, person, FALL_KIND, FALL_PRIORITY, reason))
