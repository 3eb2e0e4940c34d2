"""Against a real mosquitto broker: a hot reading on MQTT makes the robot run the hydration
behaviour in the simulated home and acknowledge on the contract's ack topic."""

from __future__ import annotations

import json
from collections.abc import Callable

from env_broker import Peer, wait_for

from amiro.environment.mqtt_bridge import MqttConfig
from amiro.scenarios.hydration import HydrationOptions, scenario_config
from amiro.system import build_system


def test_hot_reading_over_mqtt_runs_hydration_and_acks_over_mqtt(
    broker: str, peer_factory: Callable[[list[str]], Peer]
) -> None:
    base = scenario_config(HydrationOptions(seed=3))
    sensors = base.environment.sensors.model_copy(update={"changes": ()})
    mqtt = MqttConfig(url=broker, client_id="amiro-test")
    env_cfg = base.environment.model_copy(update={"sensors": sensors, "mqtt": mqtt})
    system = build_system(base.model_copy(update={"environment": env_cfg}))
    env = system.environment
    assert env.bridge is not None
    peer = peer_factory(["amiro/home/notifications/ack", "homeassistant/#"])
    system.start()
    rt = system.runtime
    assert wait_for(
        lambda: env.bridge is not None and env.bridge.connected, 10, lambda: rt.spin_for(0.05)
    )
    rt.spin_for(20.0)  # normal temperatures first: nothing happens
    assert not any(r.name == "hydration" for r in system.engine.runs.values())

    peer.publish("amiro/home/living_room/temperature", {"value": 31.5, "unit": "C"})
    # Hold the simulated clock until the reading is in the bridge's inbox, so the behaviour
    # starts at the same simulated moment whatever the broker's wall-clock latency.
    assert wait_for(
        lambda: env.bridge is not None and env.bridge.inbox.pending() > 0, 10, lambda: None
    )
    assert wait_for(
        lambda: any(r.name == "hydration" for r in system.engine.runs.values()),
        10,
        lambda: rt.spin_for(0.05),
    )
    run = next(r for r in system.engine.runs.values() if r.name == "hydration")
    rt.spin_until(lambda: run.done, 900)
    assert run.outcome == "completed"
    types = [rec.type for rec in run.records]
    assert types[:2] == ["Search", "MoveTo"] and "RecognizeActivity" in types

    def acks() -> list[dict[str, object]]:
        return [json.loads(p) for _t, p in peer.received(lambda t: t.endswith("/ack"))]

    assert wait_for(lambda: bool(acks()), 10, lambda: rt.spin_for(0.05))
    ack = acks()[0]
    assert ack["status"] == "done" and str(ack["id"]).startswith("hot_room-living_room")
    assert str(ack["ts"]).startswith("2026-07-15T")
    discovery = peer.received(lambda t: t.startswith("homeassistant/"))
    assert any("living_room_temperature" in t for t, _ in discovery)
    assert env.bridge.counts["sensor"] == 1 and env.bridge.counts["malformed"] == 0
    system.stop()
