"""Bus messages of the smart environment beyond the core vocabulary (readings, notifications)."""

from __future__ import annotations

from dataclasses import dataclass

HEALTH_METRICS = ("blood_pressure", "heart_rate", "steps", "sleep")
DEVICES = ("lights", "blinds")
DEVICE_STATES = {"lights": ("on", "off"), "blinds": ("open", "close")}


@dataclass(frozen=True, slots=True)
class HealthMeasurement:
    """One health value of a user; ``value2`` is the diastolic pressure, else None.

    ``ts`` is an ISO 8601 timestamp: health data outlives a simulation run.
    """

    user: str
    metric: str
    value: float
    ts: str
    value2: float | None = None


@dataclass(frozen=True, slots=True)
class DeviceCommand:
    home: str
    room: str
    device: str
    state: str


@dataclass(frozen=True, slots=True)
class DeviceState:
    home: str
    room: str
    device: str
    state: str
    stamp: float
