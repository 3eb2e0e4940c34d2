"""Home Assistant MQTT discovery: the robot's sensors, actuators and status appear in HA.

One retained config message per entity under ``<prefix>/<component>/<object_id>/config``;
all entities share one device (the robot's home) and the robot's availability topic.
"""

from __future__ import annotations

import json
from typing import Any

from amiro.environment.messages import DEVICES
from amiro.environment.payloads import device_topic, sensor_topic
from amiro.environment.simulated import UNITS

DEVICE_CLASSES = {"temperature": "temperature", "humidity": "humidity", "luminosity": "illuminance"}
HA_UNITS = {"C": "°C", "%": "%", "lx": "lx"}


def availability_topic(home: str) -> str:
    return f"amiro/{home}/robot/availability"


def status_topic(home: str) -> str:
    return f"amiro/{home}/robot/status"


def _device(home: str) -> dict[str, Any]:
    return {
        "identifiers": [f"amiro_{home}"],
        "name": f"amiro robot ({home})",
        "manufacturer": "amiro",
        "model": "assistive social robot",
    }


def _common(home: str, object_id: str, name: str) -> dict[str, Any]:
    return {
        "name": name,
        "unique_id": object_id,
        "object_id": object_id,
        "device": _device(home),
        "availability_topic": availability_topic(home),
    }


def discovery_messages(home: str, rooms: list[str], prefix: str) -> list[tuple[str, bytes]]:
    """(topic, retained payload) for every sensor, light, blind and the robot's status."""
    out: list[tuple[str, dict[str, Any]]] = []
    for room in rooms:
        for sensor, unit in UNITS.items():
            oid = f"amiro_{home}_{room}_{sensor}"
            cfg = _common(home, oid, f"{room.replace('_', ' ')} {sensor}")
            cfg |= {
                "state_topic": sensor_topic(home, room, sensor),
                "unit_of_measurement": HA_UNITS[unit],
                "device_class": DEVICE_CLASSES[sensor],
                "state_class": "measurement",
                "value_template": "{{ value_json.value }}",
            }
            out.append((f"{prefix}/sensor/{oid}/config", cfg))
        for device in DEVICES:
            oid = f"amiro_{home}_{room}_{device}"
            cfg = _common(home, oid, f"{room.replace('_', ' ')} {device}")
            cfg["command_topic"] = device_topic(home, room, device, "set")
            cfg["state_topic"] = device_topic(home, room, device, "state")
            if device == "lights":
                cfg |= {
                    "payload_on": '{"state": "on"}',
                    "payload_off": '{"state": "off"}',
                    "state_value_template": "{{ value_json.state }}",
                    "state_on": "on",
                    "state_off": "off",
                }
                out.append((f"{prefix}/light/{oid}/config", cfg))
            else:
                cfg |= {
                    "payload_open": '{"state": "open"}',
                    "payload_close": '{"state": "close"}',
                    "payload_stop": None,
                    "value_template": "{{ value_json.state }}",
                    "state_open": "open",
                    "state_closed": "close",
                }
                out.append((f"{prefix}/cover/{oid}/config", cfg))
    oid = f"amiro_{home}_robot_activity"
    cfg = _common(home, oid, "robot activity")
    cfg |= {"state_topic": status_topic(home), "value_template": "{{ value_json.activity }}"}
    out.append((f"{prefix}/sensor/{oid}/config", cfg))
    return [(topic, json.dumps(cfg).encode()) for topic, cfg in out]
