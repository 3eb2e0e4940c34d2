"""Where the dialogue's answers come from: health data, calendar, weather and devices.

Small ports, with offline fixtures (data/dialogue/fixtures.yaml) as defaults so that the
dialogue works without the environment module or a network; real adapters replace them."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any, Protocol

import yaml


class HealthSource(Protocol):
    def latest(self, user: str, metric: str, day: str) -> dict[str, Any] | None:
        """The metric's value on ``day`` (today, tomorrow, yesterday or ISO date)."""
        ...


class CalendarSource(Protocol):
    def events(self, user: str, day: str) -> list[dict[str, str]]:
        """Events as ``{"time": "10:00", "title": "..."}``."""
        ...


class WeatherProvider(Protocol):
    def forecast(self, location: str, day: str) -> dict[str, Any] | None:
        """``{"condition": "sunny", "temp_c": 24}``, or None when unknown."""
        ...


class DeviceControl(Protocol):
    def set(self, room: str, device: str, state: str) -> bool:
        """Actuate a device; False when there is no such device."""
        ...


@cache
def _fixtures() -> dict[str, Any]:
    text = resources.files("amiro").joinpath("data/dialogue/fixtures.yaml").read_text("utf-8")
    data: dict[str, Any] = yaml.safe_load(text)
    return data


class FixtureHealth:
    def latest(self, user: str, metric: str, day: str) -> dict[str, Any] | None:
        values: dict[str, Any] | None = _fixtures()["health"].get(day, {}).get(metric)
        return values


class FixtureCalendar:
    def events(self, user: str, day: str) -> list[dict[str, str]]:
        events: list[dict[str, str]] = _fixtures()["calendar"].get(day, [])
        return events


class OfflineWeather:
    """A fixed forecast; the default location is the home's."""

    def forecast(self, location: str, day: str) -> dict[str, Any] | None:
        found: dict[str, Any] | None = _fixtures()["weather"].get(day)
        return found


@dataclass
class RecordingDevices:
    """Remembers commanded states; the environment module's bridge replaces it."""

    rooms: tuple[str, ...] = ("kitchen", "bedroom", "living_room", "bathroom", "hallway")

    def __post_init__(self) -> None:
        self.states: dict[tuple[str, str], str] = {}

    def set(self, room: str, device: str, state: str) -> bool:
        if room not in self.rooms:
            return False
        self.states[(room, device)] = state
        return True


@dataclass
class Sources:
    health: HealthSource
    calendar: CalendarSource
    weather: WeatherProvider
    devices: DeviceControl
    home_location: str = "Bucharest"


def offline_sources() -> Sources:
    return Sources(FixtureHealth(), FixtureCalendar(), OfflineWeather(), RecordingDevices())
