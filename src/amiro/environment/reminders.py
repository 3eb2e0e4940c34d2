"""Calendar events and recurring reminders, each raised as a Notification at its time.

Times in the config are wall-clock times of the home's time zone; the runtime clock gives
"now" (``clock.iso``), so the simulated home replays a day in seconds.  A conditional
reminder ("hydration every two hours while the living room is above 28 °C") fires when its
condition holds and ``every_s`` has passed since it last fired.
"""

from __future__ import annotations

from datetime import datetime, time, timedelta
from functools import partial
from zoneinfo import ZoneInfo, ZoneInfoNotFoundError

from pydantic import ConfigDict, Field, field_validator, model_validator

from amiro.core import names
from amiro.core.config import Section
from amiro.core.messages import Notification, SensorReading
from amiro.core.node import Node


class CalendarEvent(Section):
    title: str
    at: datetime = Field(description="ISO 8601; without an offset, the home's time zone")
    user: str = ""
    kind: str = "calendar"
    priority: int = 4
    remind_before_s: float = Field(default=0.0, ge=0.0)


class SensorCondition(Section):
    sensor: str = "temperature"
    room: str
    above: float


class Reminder(Section):
    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)

    name: str
    kind: str
    user: str = ""
    priority: int = 5
    reason: str = ""
    daily_at: time | None = Field(default=None, description="HH:MM every day")
    every_s: float | None = Field(default=None, gt=0.0)
    while_: SensorCondition | None = Field(default=None, alias="while")

    @field_validator("every_s")
    @classmethod
    def _not_too_often(cls, v: float | None) -> float | None:
        if v is not None and v < 60.0:
            raise ValueError("a reminder more often than every minute is a flood, not a reminder")
        return v

    @model_validator(mode="after")
    def _one_schedule(self) -> Reminder:
        if (self.daily_at is None) == (self.every_s is None):
            raise ValueError(f"reminder {self.name}: give exactly one of daily_at, every_s")
        return self


class RemindersConfig(Section):
    timezone: str = "UTC"
    reminders: tuple[Reminder, ...] = ()
    calendar: tuple[CalendarEvent, ...] = ()

    @field_validator("timezone")
    @classmethod
    def _known_zone(cls, v: str) -> str:
        try:
            ZoneInfo(v)
        except (ZoneInfoNotFoundError, ValueError):
            raise ValueError(f"unknown time zone '{v}'") from None
        return v


class RemindersNode(Node):
    def __init__(self, config: RemindersConfig) -> None:
        super().__init__("reminders")
        self.config = config
        self.zone = ZoneInfo(config.timezone)
        self.fired: list[Notification] = []
        self._last: dict[str, float] = {}
        self._readings: dict[tuple[str, str], float] = {}

    def on_start(self) -> None:
        self.pub = self.create_publisher(names.NOTIFICATIONS, Notification)
        self.create_subscription(names.SENSORS, SensorReading, self._on_reading, depth=1000)
        now = self.local_now()
        for reminder in self.config.reminders:
            if reminder.daily_at is not None:
                self._schedule_daily(reminder)
            else:
                self.create_timer(60.0, partial(self._check_interval, reminder))
        for event in self.config.calendar:
            due = self._localise(event.at) - timedelta(seconds=event.remind_before_s)
            if due >= now:
                self.call_later((due - now).total_seconds(), partial(self._fire_event, event))

    def local_now(self) -> datetime:
        return datetime.fromisoformat(self.runtime.clock.iso(self.now())).astimezone(self.zone)

    def _localise(self, moment: datetime) -> datetime:
        return moment.replace(tzinfo=self.zone) if moment.tzinfo is None else moment

    def _schedule_daily(self, reminder: Reminder) -> None:
        assert reminder.daily_at is not None
        now = self.local_now()
        due = datetime.combine(now.date(), reminder.daily_at, self.zone)
        if due <= now:
            due += timedelta(days=1)
        self.call_later((due - now).total_seconds(), partial(self._fire_daily, reminder))

    def _fire_daily(self, reminder: Reminder) -> None:
        self._fire(reminder.name, reminder.user, reminder.kind, reminder.priority, reminder.reason)
        self._schedule_daily(reminder)

    def _on_reading(self, reading: SensorReading) -> None:
        self._readings[(reading.room, reading.sensor)] = reading.value
        for reminder in self.config.reminders:
            if reminder.while_ is not None and reminder.every_s is not None:
                self._check_interval(reminder)

    def _check_interval(self, reminder: Reminder) -> None:
        assert reminder.every_s is not None
        cond = reminder.while_
        if cond is not None:
            value = self._readings.get((cond.room, cond.sensor))
            if value is None or value <= cond.above:
                return
        last = self._last.get(reminder.name)
        if last is not None and self.now() - last < reminder.every_s:
            return
        self._last[reminder.name] = self.now()
        reason = reminder.reason
        if cond is not None and not reason:
            value = self._readings[(cond.room, cond.sensor)]
            reason = f"{cond.sensor} in {cond.room} is {value:g} (reminder {reminder.name})"
        self._fire(reminder.name, reminder.user, reminder.kind, reminder.priority, reason)

    def _fire_event(self, event: CalendarEvent) -> None:
        self._fire("calendar", event.user, event.kind, event.priority, event.title)

    def _fire(self, name: str, user: str, kind: str, priority: int, reason: str) -> None:
        stamp = self.local_now().strftime("%Y%m%dT%H%M%S")
        note = Notification(f"{name}-{stamp}", user, kind, priority, reason=reason or name)
        self.fired.append(note)
        self.log.info("reminder %s: %s for %s", name, kind, user or "the household")
        self.pub.publish(note)
