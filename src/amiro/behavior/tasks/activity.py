"""RecognizeActivity: watch the person until the expected activity is seen, or time runs out."""

from __future__ import annotations

from amiro.behavior.task import Task, TaskContext, TaskStatus
from amiro.behavior.tasks.gaze import look_at
from amiro.core.messages import Point


class RecognizeActivity(Task):
    """params: ``person``, ``activity`` (e.g. drink_water), ``timeout_s`` (default 30),
    ``confirmations`` (consecutive sightings needed, default 3), ``period_s`` (default 0.5),
    ``look_at`` (a map point: the head turns to it first, e.g. ``$person_position``).
    Fails with ``skeleton_incomplete`` when the skeleton was never usable, else
    ``not_recognised``."""

    type_name = "RecognizeActivity"

    def start(self, ctx: TaskContext) -> None:
        p = self.resolved(ctx)
        self.person = str(p["person"])
        self.activity = str(p.get("activity", "drink_water"))
        self.deadline = ctx.now() + float(p.get("timeout_s", 30.0))
        self.needed = int(p.get("confirmations", 3))
        self.period = float(p.get("period_s", 0.5))
        self.next_look = ctx.now()
        self.streak = 0
        self.complete_seen = False
        self.labels: dict[str, int] = {}
        if isinstance(p.get("look_at"), Point):
            look_at(ctx, p["look_at"])

    def update(self, ctx: TaskContext) -> TaskStatus:
        now = ctx.now()
        if now >= self.next_look:
            self.next_look = now + self.period
            reading = ctx.module("activity").observe(self.person)
            self.complete_seen |= reading.skeleton_complete
            if reading.label is not None:
                self.labels[reading.label] = self.labels.get(reading.label, 0) + 1
            self.streak = self.streak + 1 if reading.label == self.activity else 0
            if self.streak >= self.needed:
                self.detail = {"activity": self.activity, "confidence": reading.confidence}
                ctx.event("activity_recognised", activity=self.activity, person=self.person)
                return TaskStatus.SUCCESS
        if now >= self.deadline:
            reason = "not_recognised" if self.complete_seen else "skeleton_incomplete"
            self.detail = {"reason": reason, "seen": self.labels}
            return TaskStatus.FAILURE
        return TaskStatus.RUNNING
