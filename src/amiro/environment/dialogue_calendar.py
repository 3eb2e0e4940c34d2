"""The dialogue's agenda from the reminders configuration (the dialogue's ``CalendarSource``).

A day's agenda is its calendar events plus the daily reminders, for the user asking or for
the whole household, in the home's time zone and ordered by time.
"""

from __future__ import annotations

from datetime import datetime
from zoneinfo import ZoneInfo

from amiro.core.clock import Clock
from amiro.environment.days import clock_datetime, resolve_day
from amiro.environment.reminders import RemindersConfig


class ConfiguredCalendar:
    def __init__(self, config: RemindersConfig, clock: Clock) -> None:
        self.config = config
        self.clock = clock
        self.zone = ZoneInfo(config.timezone)

    def events(self, user: str, day: str) -> list[dict[str, str]]:
        when = resolve_day(day, clock_datetime(self.clock).astimezone(self.zone).date())
        if when is None:
            return []
        found = [
            {"time": f"{at:%H:%M}", "title": event.title}
            for event in self.config.calendar
            if event.user in ("", user) and (at := self._local(event.at)).date() == when
        ]
        found += [
            {"time": f"{r.daily_at:%H:%M}", "title": r.reason or r.name.replace("_", " ")}
            for r in self.config.reminders
            if r.daily_at is not None and r.user in ("", user)
        ]
        return sorted(found, key=lambda e: e["time"])

    def _local(self, moment: datetime) -> datetime:
        if moment.tzinfo is None:
            return moment.replace(tzinfo=self.zone)
        return moment.astimezone(self.zone)
