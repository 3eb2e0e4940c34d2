"""The dialogue's actions: each turns filled slots into an answer (a phrase key and its
fields) using the health store, calendar, weather, devices or the behaviour engine."""

from __future__ import annotations

from collections.abc import Callable
from datetime import date
from typing import Any

from amiro.core.clock import Clock, SimClock
from amiro.dialogue.devices import coherent_device
from amiro.dialogue.phrases import local_name, phrase
from amiro.dialogue.sources import Sources
from amiro.dialogue.when import duration_seconds

Submit = Callable[[str, dict[str, Any]], object]
Answer = tuple[str, dict[str, Any]]


def day_phrase(day: str, lang: str) -> str:
    """ "Tomorrow", or a date said the language's way ("Le 20 juillet 2026")."""
    if day in ("today", "tomorrow", "yesterday"):
        return phrase(f"day_{day}", lang)
    try:
        when = date.fromisoformat(day)
    except ValueError:
        return day
    month = phrase(f"month_{when.month}", lang)
    return phrase("day_date", lang, {"day": when.day, "month": month, "year": when.year})


class Actions:
    """``clock``: the runtime's, on which "in two hours" becomes a time of day (a simulated
    clock at its epoch when none is given)."""

    def __init__(
        self, sources: Sources, submit: Submit | None = None, clock: Clock | None = None
    ) -> None:
        self.sources = sources
        self.submit = submit
        self.clock: Clock = clock or SimClock()

    def run(self, name: str, slots: dict[str, str], user: str, lang: str) -> Answer:
        if name.startswith("utter_"):
            return name, {}
        handler: Callable[[dict[str, str], str, str], Answer] = getattr(self, name)
        return handler(slots, user, lang)

    def answer_health(self, slots: dict[str, str], user: str, lang: str) -> Answer:
        metric, day = slots["health_entity"], slots["dateandtime_entity"]
        value = self.sources.health.latest(user, metric, day)
        if value is None:
            return "answer_no_data", {}
        key = f"answer_{metric}"
        if value.get("status") == "attention":  # health_status with a reading out of range
            key = f"answer_attention_{value['metric']}"
        return key, {"day_phrase": day_phrase(day, lang), **value}

    def answer_info(self, slots: dict[str, str], user: str, lang: str) -> Answer:
        return f"answer_info_{slots['info_entity']}", {}

    def answer_weather(self, slots: dict[str, str], user: str, lang: str) -> Answer:
        day = slots["dateandtime_entity"]
        location = slots.get("location_entity", "").title() or self.sources.home_location
        found = self.sources.weather.forecast(location, day)
        if found is None:
            return "answer_no_weather", {}
        condition = phrase(f"weather_{found['condition']}", lang)
        place = local_name("place", location, lang)
        fields = {"day_phrase": day_phrase(day, lang), "location": place}
        return "answer_weather", {**found, **fields, "condition": condition}

    def answer_calendar(self, slots: dict[str, str], user: str, lang: str) -> Answer:
        day = slots["dateandtime_entity"]
        events = self.sources.calendar.events(user, day)
        fields = {"day_phrase": day_phrase(day, lang)}
        if not events:
            return "answer_calendar_empty", fields
        listed = ", ".join(f"{e['time']} {e['title']}" for e in events)
        return "answer_calendar", {**fields, "events": listed}

    def control_device(self, slots: dict[str, str], user: str, lang: str) -> Answer:
        said = coherent_device(slots)  # "open" the lights, answered to "on or off?": on
        room, device, state = said["room_entity"], said["device_entity"], said["device_state"]
        if not self.sources.devices.set(room, device, state):
            return "answer_device_unknown", {}
        done = local_name("device", f"{device}_{state}", lang)
        return "answer_device_done", {"device_state": done, "room": local_name("room", room, lang)}

    def answer_postpone(self, slots: dict[str, str], user: str, lang: str) -> Answer:
        """ "Later": when it comes with a duration, the clock time it ends (UTC, the clock's),
        with its date when that is not today."""
        seconds = duration_seconds(slots.get("duration", ""))
        if seconds is None:
            return "utter_ok", {}
        now = self.clock.now()
        today, due = self.clock.iso(now), self.clock.iso(now + seconds)
        time = due[11:16] if due[:10] == today[:10] else f"{due[:10]} {due[11:16]}"
        return "answer_postpone", {"time": time}

    def go_to(self, slots: dict[str, str], user: str, lang: str) -> Answer:
        if self.submit is None:
            return "answer_go_to_unavailable", {}
        target = slots.get("person_entity") or slots["room_entity"]
        payload = {k: v for k, v in slots.items() if k in ("person_entity", "room_entity")}
        self.submit("go_to", {**payload, "requested_by": user, "lang": lang})
        said = target.title() if "person_entity" in slots else local_name("room", target, lang)
        return "answer_go_to", {"target": said}
