"""The fall monitor: confirmed "falling" readings preempt the running behaviour."""

from typing import Any

import amiro.behavior.tasks  # noqa: F401 - registers the task types
from amiro.activity.fall import FallMonitorNode
from amiro.activity.ports import ActivityReading
from amiro.behavior.engine import BehaviorEngine, EngineConfig
from amiro.behavior.handlers import HandlerRegistry
from amiro.behavior.loader import load_behavior_data
from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import BehaviorEvent
from amiro.core.runtime import Runtime


class ScriptedRecognizer:
    box_range: tuple[float, float] | None = None

    def __init__(self) -> None:
        self.labels: dict[str, str] = {}
        self.asked: list[str] = []

    def observe(self, person: str) -> ActivityReading:
        self.asked.append(person)
        label = self.labels.get(person)
        return ActivityReading(label, 0.9, label is not None)


def _waiting(name: str, priority: int, seconds: float) -> dict[str, Any]:
    return {
        "name": name,
        "priority": priority,
        "blackboard": {"person": ""},
        "entry": "wait",
        "tasks": {"wait": {"type": "Wait", "params": {"seconds": seconds}}},
    }


def _home() -> tuple[Runtime, BehaviorEngine, FallMonitorNode, ScriptedRecognizer]:
    runtime = Runtime(SimClock())
    engine = runtime.add(BehaviorEngine(config=EngineConfig(), modules={}))
    handlers = HandlerRegistry(engine)
    handlers.register("fall", lambda p: load_behavior_data(_waiting("fall", 100, 3.0), overrides=p))
    recognizer = ScriptedRecognizer()
    monitor = runtime.add(
        FallMonitorNode(recognizer, handlers, lambda: ["maria", "ion"], period_s=0.5)
    )
    runtime.start()
    return runtime, engine, monitor, recognizer


def test_a_confirmed_fall_preempts_the_chore_once_and_the_chore_resumes() -> None:
    runtime, engine, monitor, recognizer = _home()
    events: list[BehaviorEvent] = []
    runtime.bus.subscribe(names.EVENTS, BehaviorEvent, events.append)
    chore = engine.submit(load_behavior_data(_waiting("chore", 1, 20.0)))
    runtime.spin_for(2.0)
    assert set(recognizer.asked) == {"maria", "ion"} and monitor.alerts == []
    recognizer.labels["maria"] = "falling"
    runtime.spin_for(0.5)
    assert monitor.alerts == []  # one reading is not enough: two in a row are
    runtime.spin_until(lambda: bool(monitor.alerts), 1.0)
    runtime.spin_for(0.2)
    current = engine.current()
    assert current is not None and current["name"] == "fall"
    fall = next(r for r in engine.runs.values() if r.name == "fall")
    assert fall.blackboard["person"] == "maria"
    runtime.spin_for(2.0)  # still falling, but the fall behaviour is already running
    assert monitor.alerts == ["maria"]
    detected = [e for e in events if e.type == "fall_detected"]
    assert len(detected) == 1 and detected[0].detail["person"] == "maria"
    recognizer.labels.clear()
    runtime.spin_until(lambda: chore.done, 30.0)
    assert fall.outcome == "completed" and chore.outcome == "completed"
    assert chore.records[0].result == "preempted"
    assert monitor.alerts == ["maria"]


def test_a_single_falling_blip_raises_nothing() -> None:
    runtime, engine, monitor, recognizer = _home()
    for label in ("falling", "typing", "falling", "drink_water"):
        recognizer.labels["ion"] = label
        runtime.spin_for(0.5)
    assert monitor.alerts == [] and not engine.runs
