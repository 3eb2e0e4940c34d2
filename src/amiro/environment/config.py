"""The ``environment:`` config section: sensors, rules, health store, reminders, MQTT.

A superset of the section ``system.py`` started with (``home_id``, ``sensors``, ``rules``),
so existing configs keep working.
"""

from __future__ import annotations

from pydantic import Field

from amiro.core.config import Section
from amiro.environment.mqtt_bridge import MqttConfig
from amiro.environment.payloads import NAME
from amiro.environment.reminders import RemindersConfig
from amiro.environment.rules import HealthRule, ThresholdRule
from amiro.environment.simulated import SimulatedSensorsConfig

HOT_ROOM = ThresholdRule(
    name="hot_room", sensor="temperature", above=28.0, kind="hydration", priority=5
)


class EnvironmentConfig(Section):
    home_id: str = Field(default="home", pattern=NAME.pattern)
    sensors: SimulatedSensorsConfig = Field(default_factory=SimulatedSensorsConfig)
    rules: tuple[ThresholdRule, ...] = (HOT_ROOM,)
    health_rules: tuple[HealthRule, ...] = ()
    database: str | None = Field(
        default=None,
        description="SQLAlchemy URL of the health store and notification ledger "
        "(sqlite:///amiro.db, postgresql://...); none: in memory, nothing persisted",
    )
    simulated_devices: bool = True
    reminders: RemindersConfig = Field(default_factory=RemindersConfig)
    mqtt: MqttConfig | None = None
