"""Reliability over a real broker: 10,000 malformed payloads are counted and crash nothing;
a burst of 1,000 notifications is handled in priority order with none lost."""

from __future__ import annotations

import json
from collections.abc import Callable

import numpy as np
from env_broker import Peer, wait_for

from amiro.behavior.engine import BehaviorEngine
from amiro.behavior.graph import TaskGraph
from amiro.behavior.handlers import HandlerRegistry
from amiro.behavior.modules import Modules
from amiro.behavior.notifications import NotificationHandlerNode
from amiro.behavior.tasks.notify import NotifyEnvironment
from amiro.core.clock import SimClock
from amiro.core.runtime import Runtime
from amiro.environment.mqtt_bridge import MqttBridgeNode, MqttConfig

TOPICS = [
    "amiro/home/living_room/temperature",
    "amiro/home/kitchen/humidity",
    "amiro/home/health/maria/blood_pressure",
    "amiro/home/health/maria/steps",
    "amiro/home/notifications",
    "amiro/home/kitchen/lights/set",
    "amiro/home/kitchen/oven",
    "amiro/home/../../x",
    "amiro/home/health/maria/mood",
]


def malformed(rng: np.random.Generator, i: int) -> bytes:
    kind = i % 6
    if kind == 0:
        return bytes(rng.integers(0, 256, size=int(rng.integers(0, 40)), dtype=np.uint8))
    if kind == 1:
        return b'{"value": '
    if kind == 2:
        return json.dumps({"value": "hot", "systolic": None, "state": "maybe"}).encode()
    if kind == 3:
        return (
            json.dumps({"value": float(rng.choice([1e9, -1e9]))})
            .encode()
            .replace(b"1000000000.0", b"1e999")
        )
    if kind == 4:
        return json.dumps([1, 2, 3]).encode()
    return json.dumps({"id": "", "kind": "x y", "priority": "high"}).encode()


def bridge_runtime(broker: str) -> tuple[Runtime, MqttBridgeNode]:
    rt = Runtime(SimClock())
    bridge = rt.add(
        MqttBridgeNode(MqttConfig(url=broker, client_id="amiro-rel"), "home", ["kitchen"])
    )
    rt.start()
    assert wait_for(lambda: bridge.connected, 10, lambda: rt.spin_for(0.05))
    return rt, bridge


def test_ten_thousand_malformed_payloads_are_counted_not_fatal(
    broker: str, peer_factory: Callable[[list[str]], Peer]
) -> None:
    rt, bridge = bridge_runtime(broker)
    peer = peer_factory([])
    rng = np.random.default_rng(11)
    n = 10_000
    for i in range(n):
        peer.client.publish(TOPICS[i % len(TOPICS)], malformed(rng, i), qos=0)
    peer.publish("amiro/home/kitchen/temperature", {"value": 22.5, "unit": "C"})  # qos 1, last
    assert wait_for(lambda: bridge.counts["sensor"] == 1, 30, lambda: rt.spin_for(0.05))
    assert bridge.counts["malformed"] == n
    assert bridge.counts["received"] == n + 1
    assert bridge.running and not rt.supervisor.health
    rt.stop()


def test_burst_of_1000_notifications_runs_in_priority_order_none_lost(
    broker: str, peer_factory: Callable[[list[str]], Peer]
) -> None:
    rt, bridge = bridge_runtime(broker)
    engine = rt.add(BehaviorEngine(modules=Modules(clock=rt.clock)))
    handlers = HandlerRegistry(engine)
    handlers.register(
        "check",
        lambda p: TaskGraph("check", blackboard=p).add("ack", NotifyEnvironment(status="done")),
    )
    rt.add(NotificationHandlerNode(engine, handlers, {}))
    peer = peer_factory(["amiro/home/notifications/ack"])
    rng = np.random.default_rng(5)
    priorities = rng.integers(0, 10, size=1000)
    for i, prio in enumerate(priorities):
        peer.client.publish(
            "amiro/home/notifications",
            json.dumps({"id": f"n{i}", "user": "maria", "kind": "check", "priority": int(prio)}),
            qos=1,
        )
    # the burst lands while the robot is busy elsewhere: wait until all are in the bridge
    assert wait_for(lambda: bridge.inbox.pending() >= 1000, 30, lambda: None)
    assert wait_for(
        lambda: len(peer.received(lambda t: t.endswith("/ack"))) == 1000,
        60,
        lambda: rt.spin_for(0.5),
    )
    acks = [json.loads(p) for _t, p in peer.received(lambda t: t.endswith("/ack"))]
    order = [int(a["id"][1:]) for a in acks]
    assert sorted(order) == list(range(1000))  # none lost, none twice
    assert all(a["status"] == "done" for a in acks)
    acked_prios = [int(priorities[i]) for i in order]
    assert acked_prios == sorted(acked_prios, reverse=True)  # most urgent first
    for prio in set(acked_prios):  # equal priorities keep their arrival order
        same = [i for i in order if priorities[i] == prio]
        assert same == sorted(same)
    rt.stop()
