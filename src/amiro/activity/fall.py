"""Fall detection: an urgent behaviour when the activity model sees someone fall.

The monitor looks at every resident in view on a timer; ``confirmations`` consecutive
"falling" readings submit the ``fall`` behaviour (data/behaviors/fall.yaml, priority 100)
through the handler registry, so the engine preempts whatever the robot is doing, and
publish a ``fall_detected`` event.  One alert per person until their fall run ends.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterable

from amiro.activity.ports import ActivityRecognizer
from amiro.behavior.engine import GraphRun
from amiro.behavior.handlers import HandlerRegistry
from amiro.core import names
from amiro.core.messages import BehaviorEvent
from amiro.core.node import Node

log = logging.getLogger("amiro.activity.fall")

FALL_KIND = "fall"
FALL_LABEL = "falling"


class FallMonitorNode(Node):
    def __init__(
        self,
        recognizer: ActivityRecognizer,
        handlers: HandlerRegistry,
        people: Callable[[], Iterable[str]],
        period_s: float = 0.5,
        confirmations: int = 2,
        name: str = "fall_monitor",
    ) -> None:
        super().__init__(name)
        self.recognizer = recognizer
        self.handlers = handlers
        self.people = people
        self.period_s = period_s
        self.confirmations = confirmations
        self.streaks: dict[str, int] = {}
        self.active: dict[str, GraphRun] = {}
        self.alerts: list[str] = []  # people a fall was raised for, in order

    def on_start(self) -> None:
        self.pub_events = self.create_publisher(names.EVENTS, BehaviorEvent)
        self.create_timer(self.period_s, self._check)

    def _check(self) -> None:
        for person in self.people():
            run = self.active.get(person)
            if run is not None and not run.done:
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
        self.pub_events.publish(
            BehaviorEvent(
                self.now(),
                "fall_detected",
                FALL_KIND,
                "",
                {"person": person, "confidence": confidence},
            )
        )
        self.active[person] = self.handlers.handle(FALL_KIND, {"person": person})
