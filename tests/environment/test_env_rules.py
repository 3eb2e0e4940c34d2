"""Environment rules and simulated sensors: readings become notifications, once."""

from __future__ import annotations

import pytest

from amiro.core import names
from amiro.core.messages import Notification, SensorReading
from amiro.core.runtime import Runtime
from amiro.environment.rules import RulesNode, ThresholdRule
from amiro.environment.simulated import (
    SensorChange,
    SimulatedSensorsConfig,
    SimulatedSensorsNode,
)


def setup(rule: ThresholdRule) -> tuple[Runtime, list[Notification]]:
    rt = Runtime()
    rt.add(RulesNode([rule]))
    notes: list[Notification] = []
    rt.bus.subscribe(names.NOTIFICATIONS, Notification, notes.append, depth=100)
    rt.start()
    return rt, notes


def reading(rt: Runtime, value: float, room: str = "living_room", sensor: str = "temperature"):
    rt.bus.publish(names.SENSORS, SensorReading("home", room, sensor, value, "C", rt.clock.now()))
    rt.spin_for(1.0)


HOT = ThresholdRule(name="hot", sensor="temperature", above=28.0, user="maria", priority=7)


def test_fires_once_when_crossing_and_rearms_after_cooling_down() -> None:
    rt, notes = setup(HOT)
    for value in (25.0, 27.9, 28.5, 31.0, 30.0):
        reading(rt, value)
    assert len(notes) == 1
    note = notes[0]
    assert (note.kind, note.user, note.priority) == ("hydration", "maria", 7)
    assert "28.5" in note.reason and "living_room" in note.reason
    reading(rt, 27.8)  # within the hysteresis band: still disarmed
    reading(rt, 29.0)
    assert len(notes) == 1
    reading(rt, 27.0)  # cooled down past the band: re-armed
    reading(rt, 29.0)
    assert len(notes) == 2
    assert notes[0].id != notes[1].id


def test_cooldown_rearms_a_room_that_stays_hot() -> None:
    rule = HOT.model_copy(update={"cooldown_s": 60.0})
    rt, notes = setup(rule)
    reading(rt, 30.0)
    rt.spin_for(30.0)
    reading(rt, 30.0)
    assert len(notes) == 1
    rt.spin_for(40.0)
    reading(rt, 30.0)
    assert len(notes) == 2


def test_rules_filter_by_room_and_sensor_and_support_below() -> None:
    cold = ThresholdRule(
        name="dark", sensor="luminosity", below=50.0, room="bedroom", kind="lights"
    )
    rt, notes = setup(cold)
    reading(rt, 10.0, room="kitchen", sensor="luminosity")
    reading(rt, 10.0, room="bedroom", sensor="temperature")
    assert notes == []
    reading(rt, 10.0, room="bedroom", sensor="luminosity")
    assert [n.kind for n in notes] == ["lights"]


def test_simulated_sensors_follow_their_timeline() -> None:
    rt = Runtime()
    cfg = SimulatedSensorsConfig(
        period_s=5.0, changes=(SensorChange(at_s=12.0, room="kitchen", value=33.0),)
    )
    node = rt.add(SimulatedSensorsNode(["kitchen", "bedroom"], cfg))
    got: list[SensorReading] = []
    rt.bus.subscribe(names.SENSORS, SensorReading, got.append, depth=1000)
    rt.start()
    rt.spin_for(11.0)
    assert {(r.room, r.sensor) for r in got} == {
        (room, s)
        for room in ("kitchen", "bedroom")
        for s in ("temperature", "humidity", "luminosity")
    }
    assert all(r.value < 30 for r in got if r.sensor == "temperature")
    rt.spin_for(1.5)
    hot = [r for r in got if r.room == "kitchen" and r.sensor == "temperature" and r.value == 33]
    assert hot and hot[0].stamp == pytest.approx(12.0)
    with pytest.raises(ValueError, match="no temperature sensor in room 'attic'"):
        node.set("attic", "temperature", 40.0)
