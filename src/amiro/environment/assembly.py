"""Adds the smart environment's nodes to a runtime: devices, health, ledger, reminders, MQTT.

The simulated sensors and the rules node are created by ``amiro.system.build_system``;
this completes them (health rules) and adds the rest.  The health store and the ledger
share one database; with an in-memory database they share one engine, so they see the
same tables.
"""

from __future__ import annotations

from dataclasses import dataclass

from amiro.core.runtime import Runtime
from amiro.environment.config import EnvironmentConfig
from amiro.environment.devices import SimulatedDevicesNode
from amiro.environment.health_node import HealthRecorderNode
from amiro.environment.health_store import HealthStore
from amiro.environment.ledger import LedgerNode, NotificationLedger
from amiro.environment.mqtt_bridge import MqttBridgeNode
from amiro.environment.reminders import RemindersNode
from amiro.environment.rules import RulesNode
from amiro.environment.simulated import SimulatedSensorsNode


@dataclass
class Environment:
    config: EnvironmentConfig
    health: HealthStore
    ledger: NotificationLedger
    devices: SimulatedDevicesNode | None
    reminders: RemindersNode
    bridge: MqttBridgeNode | None

    def close(self) -> None:
        self.health.close()
        self.ledger.engine.dispose()


def add_environment(
    runtime: Runtime,
    rooms: list[str],
    cfg: EnvironmentConfig,
    sensors: SimulatedSensorsNode | None = None,
    rules: RulesNode | None = None,
) -> Environment:
    health = HealthStore(cfg.database)
    ledger = NotificationLedger(cfg.database)
    if cfg.database is None:  # one in-memory database, not two
        ledger.engine = health.engine
    if rules is not None:
        rules.health_rules = list(cfg.health_rules)
    devices = None
    if cfg.simulated_devices:
        devices = runtime.add(SimulatedDevicesNode(rooms, cfg.home_id, sensors))
    runtime.add(HealthRecorderNode(health))
    runtime.add(LedgerNode(ledger))
    reminders = runtime.add(RemindersNode(cfg.reminders))
    bridge = None
    if cfg.mqtt is not None:
        bridge = runtime.add(MqttBridgeNode(cfg.mqtt, cfg.home_id, rooms))
    return Environment(cfg, health, ledger, devices, reminders, bridge)
