"""Rules that turn sensor readings and health data into notifications.

Temperature above 28 °C → hydration; systolic blood pressure above 160 → a measurement
request.  Rules are config sections, so they are written in YAML.

Each rule fires when its condition becomes true and re-arms only after the value has come
back past the threshold by ``hysteresis`` or after ``cooldown_s``, so a room hovering
around the threshold does not flood the robot with reminders.
"""

from __future__ import annotations

from dataclasses import dataclass

from amiro.core import names
from amiro.core.config import Section
from amiro.core.messages import Notification, SensorReading
from amiro.core.node import Node
from amiro.environment.messages import HealthMeasurement


class _Threshold(Section):
    name: str
    above: float | None = None
    below: float | None = None
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


class ThresholdRule(_Threshold):
    """A condition on a room sensor; ``room`` None means any room."""

    sensor: str
    room: str | None = None
    kind: str = "hydration"


class HealthRule(_Threshold):
    """A condition on a health metric (blood pressure: the systolic value, or the diastolic
    with ``diastolic: true``); ``user`` empty means any user, and the alert goes to them."""

    metric: str
    diastolic: bool = False
    kind: str = "measurement"


@dataclass
class _RuleState:
    armed: bool = True
    last_fired: float = -1e18


class RulesNode(Node):
    """Watches sensor readings and publishes a Notification when a rule fires."""

    def __init__(
        self,
        rules: list[ThresholdRule],
        home: str = "home",
        health_rules: list[HealthRule] | None = None,
    ) -> None:
        super().__init__("rules")
        self.rules = rules
        self.health_rules = health_rules or []
        self.home = home
        self.fired = 0
        self._state: dict[tuple[str, str], _RuleState] = {}

    def on_start(self) -> None:
        self.pub = self.create_publisher(names.NOTIFICATIONS, Notification)
        self.create_subscription(names.SENSORS, SensorReading, self._on_reading, depth=100)
        self.create_subscription(names.HEALTH, HealthMeasurement, self._on_health, depth=1000)

    def _on_reading(self, reading: SensorReading) -> None:
        for rule in self.rules:
            if rule.sensor != reading.sensor or rule.room not in (None, reading.room):
                continue
            reason = (
                f"{reading.sensor} in {reading.room} is {reading.value:g} {reading.unit}"
                f" (rule {rule.name})"
            )
            self._evaluate(rule, reading.room, reading.value, rule.user, rule.kind, reason)

    def _on_health(self, m: HealthMeasurement) -> None:
        for rule in self.health_rules:
            if rule.metric != m.metric or rule.user not in ("", m.user):
                continue
            value = m.value2 if rule.diastolic else m.value
            if value is None:
                continue
            reason = f"{m.metric} of {m.user} is {value:g} (rule {rule.name})"
            self._evaluate(rule, m.user, value, m.user, rule.kind, reason)

    def _evaluate(
        self, rule: _Threshold, where: str, value: float, user: str, kind: str, reason: str
    ) -> None:
        """Fire ``rule`` for ``where`` (a room or a user) once per crossing or cooldown."""
        state = self._state.setdefault((rule.name, where), _RuleState())
        now = self.now()
        if not state.armed:
            if rule.cleared(value) or now - state.last_fired >= rule.cooldown_s:
                state.armed = True
            else:
                return
        if rule.triggered(value):
            state.armed = False
            state.last_fired = now
            self.fired += 1
            ident = f"{rule.name}-{where}-{self.fired}"
            self.log.info("rule %s fired: %s", rule.name, reason)
            self.pub.publish(Notification(ident, user, kind, rule.priority, reason=reason))
