"""The whole system: the dialogue answers from the environment and acts on it."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from amiro.core import names
from amiro.core.messages import SpeechHeard, SpeechRequest
from amiro.environment.messages import HealthMeasurement
from amiro.system import System, SystemConfig, build_system


@pytest.fixture
def system() -> Iterator[System]:
    built = build_system(SystemConfig())
    built.start()
    yield built
    built.stop()


def test_a_measurement_on_the_bus_is_the_answer_to_the_question(system: System) -> None:
    rt, manager = system.runtime, system.dialogue.manager
    before = manager.handle("what is my blood pressure", "en", "maria")
    assert "no measurement" in before.text
    now = rt.clock.iso(rt.clock.now())
    rt.bus.publish(names.HEALTH, HealthMeasurement("maria", "blood_pressure", 128.0, now, 83.0))
    rt.spin_for(1.0)
    after = manager.handle("what is my blood pressure", "en", "maria")
    assert after.text == "Today, your blood pressure is 128/83 mmHg."
    other = manager.handle("quelle est ma tension", "fr", "ion")
    assert other.action == "answer_health" and "pas encore de mesure" in other.text  # not Ion's


def test_a_spoken_command_switches_the_simulated_lights(system: System) -> None:
    rt, devices = system.runtime, system.environment.devices
    assert devices is not None and devices.states[("kitchen", "lights")] == "off"
    said: list[SpeechRequest] = []
    rt.bus.subscribe(names.SAY, SpeechRequest, said.append, 10)
    heard = SpeechHeard("turn on the lights in the kitchen", "en", speaker="maria")
    rt.bus.publish(names.HEARD, heard)
    rt.spin_for(1.0)
    assert devices.states[("kitchen", "lights")] == "on"
    assert devices.states[("bedroom", "lights")] == "off"
    assert [s.text for s in said] == ["Done: lights on in the kitchen."]
