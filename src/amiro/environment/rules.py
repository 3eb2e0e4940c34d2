"""Rules that turn sensor readings into notifications (temperature above 28 °C → hydration).

Each rule fires when its condition becomes true and re-arms only after the value has come
back past the threshold by ``hysteresis`` or after ``cooldown_s``, so a room hovering
around the threshold does not flood the robot with reminders.
"""

from __future__ import annotations

from dataclasses import dataclass

from amiro.core.config import Section
from amiro.core.messages import Notification, SensorReading
from amiro.core.node import Node
from amiro.environment.topics import NOTIFICATIONS_TOPIC, SENSORS_TOPIC


class ThresholdRule(Section):
    name: str
    sensor: str
    above: float | None = None
    below: float | None = None
    room: str | None = None
    kind: str = "hydration"
    user: str = ""
    priority: int = 5
    hysteresis: float = 0.5
    cooldown_s: float = 7200.0

    def triggered(self, value: float) -> bool:
        if self.above is not None and value > self.above:
            return True
        return self.below is not None and value < self.below

    def cleared(self, value: float) -> bool:
        if self.above is not None and value > self.above - self.hysteresis:
            return False
        return not (self.below is not None and value < self.below + self.hysteresis)


@dataclass
class _RuleState:
    armed: bool = True
    last_fired: float = -1e18


class RulesNode(Node):
    """Watches sensor readings and publishes a Notification when a rule fires."""

    def __init__(self, rules: list[ThresholdRule], home: str = "home") -> None:
        super().__init__("rules")
        self.rules = rules
        self.home = home
        self.fired = 0
        self._state: dict[tuple[str, str], _RuleState] = {}

    def on_start(self) -> None:
        self.pub = self.create_publisher(NOTIFICATIONS_TOPIC, Notification)
        self.create_subscription(SENSORS_TOPIC, SensorReading, self._on_reading, depth=100)

    def _on_reading(self, reading: SensorReading) -> None:
        for rule in self.rules:
            if rule.sensor != reading.sensor or rule.room not in (None, reading.room):
                continue
            state = self._state.setdefault((rule.name, reading.room), _RuleState())
            now = self.now()
            if not state.armed:
                if rule.cleared(reading.value) or now - state.last_fired >= rule.cooldown_s:
                    state.armed = True
                else:
                    continue
            if rule.triggered(reading.value):
                state.armed = False
                state.last_fired = now
                self.fired += 1
                ident = f"{rule.name}-{reading.room}-{self.fired}"
                reason = (
                    f"{reading.sensor} in {reading.room} is {reading.value:g} {reading.unit}"
                    f" (rule {rule.name})"
                )
                self.log.info("rule %s fired: %s", rule.name, reason)
                self.pub.publish(
                    Notification(ident, rule.user, rule.kind, rule.priority, reason=reason)
                )
