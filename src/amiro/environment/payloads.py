"""The contract's MQTT topics and JSON payloads, validated at the boundary.

``decode`` turns one MQTT message into one bus message or raises :class:`PayloadError` with a
one-line reason; ``encode_*`` build the outgoing payloads.  Nothing here touches the network.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass
from datetime import datetime
from typing import Any

from amiro.core.messages import Acknowledgement, Notification, SensorReading
from amiro.environment.messages import (
    DEVICE_STATES,
    DEVICES,
    HEALTH_METRICS,
    DeviceCommand,
    DeviceState,
    HealthMeasurement,
)
from amiro.environment.simulated import UNITS

NAME = re.compile(r"^[a-z0-9_]{1,40}$")
IDENT = re.compile(r"^[A-Za-z0-9_.:#-]{1,80}$")
MAX_PAYLOAD = 4096
METRIC_RANGES = {
    "blood_pressure": (30.0, 300.0),
    "heart_rate": (20.0, 250.0),
    "steps": (0.0, 200_000.0),
    "sleep": (0.0, 24.0),
}
SENSOR_RANGES = {"temperature": (-50.0, 80.0), "humidity": (0.0, 100.0), "luminosity": (0.0, 2e5)}


class PayloadError(ValueError):
    """A message that does not follow the contract; the text says why in one line."""


@dataclass(frozen=True, slots=True)
class Decoded:
    kind: str  # sensor | health | notification | command
    message: SensorReading | HealthMeasurement | Notification | DeviceCommand


def _json(payload: bytes) -> dict[str, Any]:
    if len(payload) > MAX_PAYLOAD:
        raise PayloadError(f"payload of {len(payload)} bytes exceeds {MAX_PAYLOAD}")
    try:
        data = json.loads(payload.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError) as exc:
        raise PayloadError(f"not UTF-8 JSON: {exc}") from None
    if not isinstance(data, dict):
        raise PayloadError("payload must be a JSON object")
    return data


def _number(data: dict[str, Any], key: str, low: float, high: float) -> float:
    value = data.get(key)
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise PayloadError(f"'{key}' must be a number")
    if not math.isfinite(value) or not low <= value <= high:
        raise PayloadError(f"'{key}' = {value} is outside [{low:g}, {high:g}]")
    return float(value)


def _name(value: str, what: str) -> str:
    if not NAME.match(value):
        raise PayloadError(f"{what} '{value[:40]}' must be 1-40 of a-z, 0-9, _")
    return value


def _timestamp(data: dict[str, Any], default: str) -> str:
    ts = data.get("ts", default)
    if not isinstance(ts, str):
        raise PayloadError("'ts' must be an ISO 8601 string")
    try:
        datetime.fromisoformat(ts)
    except ValueError:
        raise PayloadError(f"'ts' '{ts[:40]}' is not ISO 8601") from None
    return ts


def decode(topic: str, payload: bytes, home: str, now: float, now_iso: str) -> Decoded:
    """One inbound MQTT message of home ``home`` as a bus message."""
    parts = topic.split("/")
    if len(parts) < 3 or parts[0] != "amiro" or parts[1] != home:
        raise PayloadError(f"topic '{topic[:80]}' is not under amiro/{home}/")
    rest = parts[2:]
    data = _json(payload)
    if rest == ["notifications"]:
        return Decoded("notification", _notification(data))
    if len(rest) == 3 and rest[0] == "health":
        user, metric = _name(rest[1], "user"), rest[2]
        return Decoded("health", health_measurement(user, metric, data, now_iso))
    if len(rest) == 2 and rest[1] in UNITS:
        room, sensor = _name(rest[0], "room"), rest[1]
        low, high = SENSOR_RANGES[sensor]
        value = _number(data, "value", low, high)
        unit = data.get("unit", UNITS[sensor])
        if unit != UNITS[sensor]:
            raise PayloadError(f"{sensor} unit must be '{UNITS[sensor]}', got {unit!r}")
        return Decoded("sensor", SensorReading(home, room, sensor, value, UNITS[sensor], now))
    if len(rest) == 3 and rest[1] in DEVICES and rest[2] == "set":
        room, device = _name(rest[0], "room"), rest[1]
        state = data.get("state")
        if state not in DEVICE_STATES[device]:
            raise PayloadError(f"{device} state must be one of {DEVICE_STATES[device]}")
        return Decoded("command", DeviceCommand(home, room, device, str(state)))
    raise PayloadError(f"no such topic in the contract: '{topic[:80]}'")


def _notification(data: dict[str, Any]) -> Notification:
    ident, user, kind = data.get("id"), data.get("user", ""), data.get("kind")
    if not isinstance(ident, str) or not IDENT.match(ident):
        raise PayloadError("'id' must be 1-80 of letters, digits and _.:#-")
    if not isinstance(user, str) or (user and not NAME.match(user)):
        raise PayloadError("'user' must be 1-40 of a-z, 0-9, _")
    if not isinstance(kind, str) or not NAME.match(kind):
        raise PayloadError("'kind' must be 1-40 of a-z, 0-9, _")
    priority = data.get("priority", 5)
    if isinstance(priority, bool) or not isinstance(priority, int) or not -100 <= priority <= 100:
        raise PayloadError("'priority' must be an integer in [-100, 100]")
    reason = data.get("reason", "")
    if not isinstance(reason, str) or len(reason) > 500:
        raise PayloadError("'reason' must be a string of at most 500 characters")
    return Notification(ident, user, kind, priority, reason=reason)


def health_measurement(
    user: str, metric: str, data: dict[str, Any], now_iso: str
) -> HealthMeasurement:
    """A validated measurement from the contract's fields (MQTT, CSV and JSON imports)."""
    if metric not in HEALTH_METRICS:
        raise PayloadError(f"metric must be one of {HEALTH_METRICS}, got '{metric[:40]}'")
    low, high = METRIC_RANGES[metric]
    ts = _timestamp(data, now_iso)
    if metric == "blood_pressure":
        systolic = _number(data, "systolic", low, high)
        diastolic = _number(data, "diastolic", low, high)
        return HealthMeasurement(user, metric, systolic, ts, diastolic)
    return HealthMeasurement(user, metric, _number(data, "value", low, high), ts)


def sensor_topic(home: str, room: str, sensor: str) -> str:
    return f"amiro/{home}/{room}/{sensor}"


def device_topic(home: str, room: str, device: str, leaf: str) -> str:
    return f"amiro/{home}/{room}/{device}/{leaf}"


def encode_reading(reading: SensorReading) -> bytes:
    return json.dumps({"value": reading.value, "unit": reading.unit}).encode()


def encode_state(state: DeviceState) -> bytes:
    return json.dumps({"state": state.state}).encode()


def encode_ack(ack: Acknowledgement) -> bytes:
    return json.dumps({"id": ack.id, "status": ack.status, "ts": ack.ts}).encode()
