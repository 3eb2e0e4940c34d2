"""Simulated room sensors: temperature, humidity and luminosity per room, on the bus.

Values follow a scripted timeline (``changes``) and can be set at run time (the dashboard's
"raise the temperature" button), so scenarios can be triggered like the paper's section 5.
"""

from __future__ import annotations

from functools import partial

from amiro.core import names
from amiro.core.config import Section
from amiro.core.messages import SensorReading
from amiro.core.node import Node

UNITS = {"temperature": "C", "humidity": "%", "luminosity": "lx"}
DEFAULTS = {"temperature": 23.0, "humidity": 45.0, "luminosity": 300.0}


class SensorChange(Section):
    at_s: float
    room: str
    sensor: str = "temperature"
    value: float


class SimulatedSensorsConfig(Section):
    period_s: float = 5.0
    changes: tuple[SensorChange, ...] = ()


class SimulatedSensorsNode(Node):
    def __init__(
        self, rooms: list[str], config: SimulatedSensorsConfig, home: str = "home"
    ) -> None:
        super().__init__("sensors")
        self.home = home
        self.config = config
        self.values = {(room, s): v for room in rooms for s, v in DEFAULTS.items()}
        self._pending = sorted(config.changes, key=lambda c: c.at_s)

    def on_start(self) -> None:
        self.pub = self.create_publisher(names.SENSORS, SensorReading)
        self.create_timer(self.config.period_s, self._publish_all)
        for change in self._pending:
            self.call_later(max(0.0, change.at_s - self.now()), partial(self._apply, change))
        self._pending = []

    def _apply(self, change: SensorChange) -> None:
        self.set(change.room, change.sensor, change.value)

    def set(self, room: str, sensor: str, value: float) -> None:
        """Change a reading now and publish it at once."""
        if (room, sensor) not in self.values:
            raise ValueError(f"no {sensor} sensor in room '{room}'")
        self.values[(room, sensor)] = value
        self._publish(room, sensor)

    def _publish(self, room: str, sensor: str) -> None:
        value = self.values[(room, sensor)]
        self.pub.publish(SensorReading(self.home, room, sensor, value, UNITS[sensor], self.now()))

    def _publish_all(self) -> None:
        for room, sensor in self.values:
            self._publish(room, sensor)
