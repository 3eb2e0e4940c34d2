"""RecognizeActivity: watch the person until the expected activity is seen, or time runs out.

As section 5 of the paper proposes, the robot frames the person the way the model's
training data did: it drives the base backwards (box too big or cut by the image edge) or
forwards (box too small) until the person's box fills the trained share of the image, and
it gives up early, for a spoken confirmation, when the skeleton stays too incomplete.
It decides from several sightings, not one: ``confirmations`` of the last ``of_last``
readings that named an activity must be the expected one, so a real sensor's flicker
(a drink read as a cough now and then) does not reset the count, and a reading of no
activity (``unknown``, unsure, too few joints) counts neither way.
The base moves through navigation's forward action (``names.FORWARD``), never on
``/cmd_vel`` itself, so the velocity multiplexer and its emergency stop govern it.
"""

from __future__ import annotations

import math
from collections import deque
from typing import Any, Self

from pydantic import Field, model_validator

from amiro.behavior.task import Task, TaskContext, TaskParams, TaskStatus, log
from amiro.behavior.tasks.gaze import look_at
from amiro.core import names
from amiro.core.bus import GoalHandle
from amiro.core.messages import Point
from amiro.navigation.primitives import ForwardGoal


class RecognizeActivity(Task):
    """params: ``person``, ``activity`` (e.g. drink_water), ``timeout_s`` (default 30),
    ``confirmations`` (sightings needed, default 3) among the last ``of_last`` readings
    that named an activity (default 5), ``period_s`` (default 0.5),
    ``look_at`` (a map point: the head turns to it, e.g. ``$person_position``),
    ``incomplete_timeout_s`` (give up this long without a usable skeleton, default 10),
    ``reframe`` (move the base to the trained framing, default true), ``reframe_speed``
    (m/s, default 0.15, at most the forward action's speed), ``max_reframe_m`` (default 1.0).
    Fails with ``skeleton_incomplete`` when the skeleton was never usable, else
    ``not_recognised``.  ``detail["reframed_m"]``: how far the base went (odometry)."""

    type_name = "RecognizeActivity"
    cancellable = True

    class Params(TaskParams):
        person: str
        activity: str = "drink_water"
        timeout_s: float = Field(30.0, ge=0)
        confirmations: int = Field(3, ge=1)
        of_last: int = Field(5, ge=1)
        period_s: float = Field(0.5, gt=0)
        look_at: Point | None = None
        incomplete_timeout_s: float = Field(10.0, ge=0)
        reframe: bool = True
        reframe_speed: float = Field(0.15, ge=0)
        max_reframe_m: float = Field(1.0, ge=0)

        @model_validator(mode="after")
        def _enough_readings(self) -> Self:
            if self.of_last < self.confirmations:
                raise ValueError(
                    f"of_last ({self.of_last}) must be at least confirmations "
                    f"({self.confirmations})"
                )
            return self

    def start(self, ctx: TaskContext) -> None:
        p = self.bind(ctx, self.Params)
        self.person = p.person
        self.activity = p.activity
        self.deadline = ctx.now() + p.timeout_s
        self.incomplete_deadline = ctx.now() + p.incomplete_timeout_s
        self.needed = p.confirmations
        self.period = p.period_s
        self.reframe = p.reframe
        self.speed = p.reframe_speed
        self.budget = p.max_reframe_m
        self.next_look = ctx.now()
        self.recent: deque[str] = deque(maxlen=p.of_last)  # the last labelled readings
        self.current = ""  # the label the recogniser gave last (for feedback)
        self.complete_seen = False
        self.labels: dict[str, int] = {}
        self.direction = 0  # +1 forwards, -1 backwards, 0 still
        self.motion: GoalHandle[ForwardGoal, Any, Any] | None = None  # the forward goal
        self.commanded = 0.0  # m of reframing asked for so far (the budget counts this)
        self.travelled = 0.0  # m the base went, from odometry (0 when blocked)
        self.last_tick = ctx.now()
        self.target = p.look_at
        if self.reframe and not ctx.bus.has_action(names.FORWARD):
            log.warning(
                "%s: no %s action here: watching without reframing", self.type_name, names.FORWARD
            )
            self.reframe = False
        if self.target is not None:
            look_at(ctx, self.target)

    def update(self, ctx: TaskContext) -> TaskStatus:
        now = ctx.now()
        self._drive(ctx, now)
        if now >= self.next_look:
            self.next_look = now + self.period
            reading = ctx.need(ctx.modules.activity, "activity").observe(self.person)
            self.complete_seen |= reading.skeleton_complete
            self.current = reading.label or ""
            if reading.label is not None:
                self.labels[reading.label] = self.labels.get(reading.label, 0) + 1
                self.recent.append(reading.label)
            if self.recent.count(self.activity) >= self.needed:
                self._stop(ctx)
                self.detail = {
                    "activity": self.activity,
                    "confidence": round(reading.confidence, 3),
                    "reframed_m": round(self.travelled, 2),
                }
                ctx.event("activity_recognised", activity=self.activity, person=self.person)
                return TaskStatus.SUCCESS
            self._steer(
                ctx, self._framing_direction(ctx, reading.box_height_fraction, reading.clipped)
            )
        gave_up = not self.complete_seen and now >= self.incomplete_deadline
        if now >= self.deadline or gave_up:
            self._stop(ctx)
            reason = "not_recognised" if self.complete_seen else "skeleton_incomplete"
            self.detail = {
                "reason": reason,
                "seen": self.labels,
                "reframed_m": round(self.travelled, 2),
            }
            return TaskStatus.FAILURE
        return TaskStatus.RUNNING

    def cancel(self, ctx: TaskContext) -> None:
        self._stop(ctx)

    # --- framing --------------------------------------------------------------------------
    def _framing_direction(self, ctx: TaskContext, box: float | None, clipped: bool) -> int:
        """Backwards when the box is too big or cut, forwards when too small, else still."""
        box_range = getattr(ctx.need(ctx.modules.activity, "activity"), "box_range", None)
        if not self.reframe or box_range is None or box is None or self.commanded >= self.budget:
            return 0
        low, high = box_range
        want = -1 if (clipped or box > high) else (1 if box < low else 0)
        return want if want != 0 and self._free_ahead(ctx, want) else 0

    def _free_ahead(self, ctx: TaskContext, direction: int, look: float = 0.3) -> bool:
        pose = ctx.need(ctx.modules.navigation, "navigation").pose
        world = ctx.modules.world
        if pose is None or world is None:
            return False
        x = pose.x + direction * look * math.cos(pose.theta)
        y = pose.y + direction * look * math.sin(pose.theta)
        return bool(world.is_free(x, y, 0.3))

    def _steer(self, ctx: TaskContext, direction: int) -> None:
        """Keep the running forward goal, or end it and send one the new way (for what is
        left of the budget: the goal ends by itself at the budget on odometry)."""
        if direction == self.direction:
            return
        self._stop(ctx)
        if direction != 0:
            goal = ForwardGoal(direction * (self.budget - self.commanded), self.speed)
            self.motion = ctx.bus.send_goal(names.FORWARD, goal)
            self.direction = direction

    def _drive(self, ctx: TaskContext, now: float) -> None:
        dt, self.last_tick = now - self.last_tick, now
        # the navigation module's odometry velocity (vx, vy, wz): what the wheels did
        nav = ctx.modules.navigation
        velocity = nav.velocity if nav is not None else (0.0, 0.0, 0.0)
        self.travelled += abs(float(velocity[0])) * dt
        if self.direction == 0:
            return
        if self.motion is None or self.motion.done:  # ended (blocked, rejected): still
            self.direction, self.motion = 0, None
            return
        self.commanded += self.speed * dt
        if self.commanded >= self.budget:
            self._stop(ctx)
            return
        if self.target is not None:
            look_at(ctx, self.target)

    def _stop(self, ctx: TaskContext) -> None:
        if self.motion is not None:
            self.motion.cancel()  # the primitive stops the base at once
        self.motion = None
        self.direction = 0
