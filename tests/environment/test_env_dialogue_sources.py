"""The dialogue's answer sources backed by the environment: health store, calendar, devices."""

from __future__ import annotations

from dataclasses import replace
from datetime import date

import pytest

from amiro.core import names
from amiro.core.bus import Bus
from amiro.core.clock import SimClock
from amiro.core.config import parse
from amiro.dialogue.actions import Actions
from amiro.dialogue.phrases import phrase
from amiro.dialogue.sources import offline_sources
from amiro.environment.days import clock_date, resolve_day
from amiro.environment.dialogue_calendar import ConfiguredCalendar
from amiro.environment.dialogue_devices import BusDeviceControl
from amiro.environment.dialogue_health import StoreHealth
from amiro.environment.health_store import HealthStore
from amiro.environment.messages import DeviceCommand, HealthMeasurement
from amiro.environment.reminders import RemindersConfig
from amiro.environment.rules import HealthRule

TODAY = date(2026, 7, 15)  # the simulated clock's first day


def test_days_follow_the_runtime_clock() -> None:
    assert clock_date(SimClock()) == TODAY
    assert clock_date(SimClock(start=86_400.0)) == date(2026, 7, 16)
    assert resolve_day("yesterday", TODAY) == date(2026, 7, 14)
    assert resolve_day("tomorrow", TODAY) == date(2026, 7, 16)
    assert resolve_day("2026-07-01", TODAY) == date(2026, 7, 1)
    assert resolve_day("next week", TODAY) is None


@pytest.fixture
def health() -> StoreHealth:
    store = HealthStore()
    store.add_many(
        [
            HealthMeasurement("maria", "blood_pressure", 130.0, "2026-07-14T08:00:00+00:00", 80.0),
            HealthMeasurement("maria", "blood_pressure", 134.0, "2026-07-14T20:00:00+00:00", 84.0),
            HealthMeasurement("maria", "blood_pressure", 121.4, "2026-07-15T08:00:00+00:00", 77.6),
            HealthMeasurement("maria", "blood_pressure", 124.0, "2026-07-15T09:30:00+00:00", 78.0),
            HealthMeasurement("maria", "steps", 1200.0, "2026-07-15T09:00:00+00:00"),
            HealthMeasurement("maria", "steps", 800.0, "2026-07-15T09:40:00+00:00"),
            HealthMeasurement("maria", "sleep", 6.25, "2026-07-14T07:00:00+00:00"),
            HealthMeasurement("ion", "heart_rate", 70.0, "2026-07-14T08:00:00+00:00"),
        ]
    )
    return StoreHealth(store, lambda: TODAY)


def test_today_is_the_latest_reading_or_the_day_total(health: StoreHealth) -> None:
    assert health.latest("maria", "blood_pressure", "today") == {"systolic": 124, "diastolic": 78}
    assert health.latest("maria", "steps", "today") == {"value": 2000}


def test_past_days_are_daily_means_or_totals(health: StoreHealth) -> None:
    assert health.latest("maria", "blood_pressure", "yesterday") == {
        "systolic": 132,
        "diastolic": 82,
    }
    assert health.latest("maria", "sleep", "2026-07-14") == {"value": 6.2}


def test_no_answer_rather_than_a_wrong_one(health: StoreHealth) -> None:
    assert health.latest("ion", "heart_rate", "today") is None  # only yesterday's reading
    assert health.latest("maria", "heart_rate", "today") is None  # never measured
    assert health.latest("maria", "steps", "tomorrow") is None
    assert health.latest("maria", "blood_pressure", "someday") is None


def test_health_status_checks_the_day_against_the_users_rules(health: StoreHealth) -> None:
    assert health.latest("maria", "health_status", "today") == {"status": "ok"}  # 124/78
    assert health.latest("ion", "health_status", "today") is None  # no reading today
    assert health.latest("ion", "health_status", "yesterday") == {"status": "ok"}  # 70 bpm
    strict = StoreHealth(
        health.store,
        lambda: TODAY,
        [
            HealthRule(name="maria_bp", metric="blood_pressure", above=120, user="maria"),
            HealthRule(name="ion_hr", metric="heart_rate", above=60, user="ion"),
        ],
    )
    assert strict.latest("maria", "health_status", "today") == {
        "status": "attention",
        "metric": "blood_pressure",
        "systolic": 124,
        "diastolic": 78,
    }
    assert strict.latest("ion", "health_status", "yesterday") == {
        "status": "attention",
        "metric": "heart_rate",
        "value": 70,
    }


def test_reference_ranges_cover_metrics_without_a_rule(health: StoreHealth) -> None:
    health.store.add_many(
        [HealthMeasurement("ion", "heart_rate", 112.0, "2026-07-15T10:00:00+00:00")]
    )
    only_bp = StoreHealth(
        health.store, lambda: TODAY, [HealthRule(name="bp", metric="blood_pressure", above=170)]
    )
    assert only_bp.latest("ion", "health_status", "today") == {
        "status": "attention",
        "metric": "heart_rate",
        "value": 112,
    }


def test_health_status_is_answered_in_the_listeners_language(health: StoreHealth) -> None:
    rule = HealthRule(name="maria_bp", metric="blood_pressure", above=120)
    sources = replace(offline_sources(), health=StoreHealth(health.store, lambda: TODAY, [rule]))
    slots = {"health_entity": "health_status", "dateandtime_entity": "today"}
    key, fields = Actions(sources).answer_health(slots, "maria", "fr")
    assert key == "answer_attention_blood_pressure"
    assert "124/78 mmHg" in phrase(key, "fr", fields)
    calm = Actions(replace(offline_sources(), health=health)).answer_health(slots, "maria", "en")
    assert calm[0] == "answer_health_status"
    assert "within your usual range" in phrase(calm[0], "en", calm[1])


CALENDAR = {
    "timezone": "Europe/Bucharest",
    "reminders": [
        {"name": "medication", "kind": "medication", "user": "maria", "daily_at": "08:00"},
        {"name": "evening_walk", "kind": "walk", "daily_at": "19:00"},
        {"name": "ion_pills", "kind": "medication", "user": "ion", "daily_at": "09:00"},
        {"name": "drink", "kind": "hydration", "every_s": 7200},
    ],
    "calendar": [
        {"title": "physiotherapy", "at": "2026-07-15T16:30:00", "user": "maria"},
        {"title": "family dinner", "at": "2026-07-15T12:00:00+00:00"},
        {"title": "doctor", "at": "2026-07-16T00:30:00", "user": "maria"},
        {"title": "dentist", "at": "2026-07-15T11:00:00", "user": "ion"},
    ],
}


def test_the_agenda_of_a_day_in_the_homes_time_zone() -> None:
    calendar = ConfiguredCalendar(parse(RemindersConfig, CALENDAR, "reminders"), SimClock())
    assert calendar.events("maria", "today") == [
        {"time": "08:00", "title": "medication"},
        {"time": "15:00", "title": "family dinner"},  # 12:00 UTC is 15:00 in Bucharest
        {"time": "16:30", "title": "physiotherapy"},
        {"time": "19:00", "title": "evening walk"},
    ]
    tomorrow = calendar.events("maria", "tomorrow")
    assert {"time": "00:30", "title": "doctor"} in tomorrow
    assert "dentist" not in str(calendar.events("maria", "today"))
    assert calendar.events("maria", "in a while") == []


def test_device_commands_go_on_the_bus_and_unknown_ones_are_refused() -> None:
    bus = Bus()
    sent = bus.subscribe(names.DEVICE_COMMAND, DeviceCommand, lambda _: None)
    control = BusDeviceControl(
        bus.publisher(names.DEVICE_COMMAND, DeviceCommand), "flat", ["kitchen"]
    )
    assert control.set("kitchen", "lights", "on")
    assert not control.set("garage", "lights", "on")
    assert not control.set("kitchen", "blinds", "on")  # blinds open or close
    assert not control.set("kitchen", "oven", "on")
    assert list(sent.queue) == [DeviceCommand("flat", "kitchen", "lights", "on")]
