"""Records health measurements from the bus (MQTT health topics, devices) in the store."""

from __future__ import annotations

from amiro.core import names
from amiro.core.node import Node
from amiro.environment.health_store import HealthStore
from amiro.environment.messages import HealthMeasurement


class HealthRecorderNode(Node):
    def __init__(self, store: HealthStore) -> None:
        super().__init__("health_recorder")
        self.store = store
        self.recorded = 0

    def on_start(self) -> None:
        self.create_subscription(names.HEALTH, HealthMeasurement, self._record, depth=10_000)

    def _record(self, m: HealthMeasurement) -> None:
        self.store.add(m)
        self.recorded += 1
