"""The fall monitor: confirmed "falling" readings raise a fall notification, whose
behaviour preempts the running one."""

import subprocess
import sys
from typing import Any

import pytest

import amiro.behavior.tasks  # noqa: F401 - registers the task types
from amiro.activity.fall import FALL_KIND, FALL_PRIORITY, FallMonitorNode
from amiro.activity.ports import ActivityReading
from amiro.behavior.engine import BehaviorEngine, EngineConfig
from amiro.behavior.handlers import HandlerRegistry
from amiro.behavior.loader import load_behavior, load_behavior_data, loads_behavior
from amiro.behavior.modules import Modules
from amiro.behavior.notifications import NotificationHandlerNode
from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import Acknowledgement, BehaviorEvent, Notification, SpeechHeard
from amiro.core.runtime import Runtime
from amiro.system import shipped_behavior


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


def _home(
    handler: bool = True,
) -> tuple[Runtime, BehaviorEngine, FallMonitorNode, ScriptedRecognizer]:
    """The monitor, and (``handler``) the notification handler turning its notifications
    into a 3 s fall behaviour on the engine."""
    runtime = Runtime(SimClock())
    engine = runtime.add(BehaviorEngine(config=EngineConfig(), modules=Modules()))
    handlers = HandlerRegistry(engine)
    handlers.register("fall", lambda p: load_behavior_data(_waiting("fall", 1, 3.0), overrides=p))
    if handler:
        runtime.add(NotificationHandlerNode(engine, handlers, {}))
    recognizer = ScriptedRecognizer()
    monitor = runtime.add(
        FallMonitorNode(recognizer, lambda: ["maria", "ion"], period_s=0.5, realert_s=60.0)
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


def _bus_log(runtime: Runtime) -> tuple[list[Notification], list[Acknowledgement]]:
    notes: list[Notification] = []
    acks: list[Acknowledgement] = []
    runtime.bus.subscribe(names.NOTIFICATIONS, Notification, notes.append, depth=100)
    runtime.bus.subscribe(names.ACK, Acknowledgement, acks.append, depth=100)
    return notes, acks


def test_a_fall_is_a_notification_and_its_acknowledgement_rearms_the_alert() -> None:
    runtime, engine, monitor, recognizer = _home()
    notes, acks = _bus_log(runtime)
    recognizer.labels["maria"] = "falling"  # and she stays down
    runtime.spin_until(lambda: bool(notes), 2.0)
    first = notes[0]
    assert (first.kind, first.user, first.priority) == (FALL_KIND, "maria", FALL_PRIORITY)
    fall = next(r for r in engine.runs.values() if r.name == "fall")
    assert fall.priority == FALL_PRIORITY and fall.blackboard["notification_id"] == first.id
    runtime.spin_until(lambda: fall.done, 5.0)
    assert len(notes) == 1  # no second alert while her fall behaviour ran
    runtime.spin_until(lambda: len(notes) == 2, 3.0)  # answered (acknowledged): alert again
    assert [a.id for a in acks] == [first.id]
    assert notes[1].user == "maria" and notes[1].id != first.id
    assert monitor.alerts == ["maria", "maria"]


def test_without_an_answer_the_alert_is_held_back_for_realert_s_only() -> None:
    runtime, engine, monitor, recognizer = _home(handler=False)
    notes, _ = _bus_log(runtime)
    recognizer.labels["ion"] = "falling"
    runtime.spin_until(lambda: bool(notes), 2.0)
    raised = runtime.clock.now()
    runtime.spin_until(lambda: len(notes) == 2, 70.0)
    assert 60.0 <= runtime.clock.now() - raised <= 62.0
    assert not engine.runs and [n.user for n in notes] == monitor.alerts == ["ion", "ion"]


def test_a_resent_fall_notification_holds_the_alert_back_too() -> None:
    runtime, _, monitor, recognizer = _home(handler=False)
    notes, _ = _bus_log(runtime)
    resent = Notification("fall-maria-before-restart", "maria", FALL_KIND, FALL_PRIORITY)
    runtime.bus.publish(names.NOTIFICATIONS, resent)
    recognizer.labels["maria"] = "falling"
    runtime.spin_for(5.0)
    assert notes == [resent] and monitor.alerts == []
    runtime.bus.publish(names.ACK, Acknowledgement(resent.id, "done", "t"))
    runtime.spin_until(lambda: len(notes) == 2, 2.0)
    assert notes[1].user == "maria"


def test_the_notification_priority_is_the_shipped_fall_behaviours() -> None:
    assert load_behavior(shipped_behavior("fall")).priority == FALL_PRIORITY


def test_the_fall_monitor_does_not_import_the_behaviour_layer() -> None:
    code = (
        "import sys, amiro.activity.fall; "
        "print([m for m in sys.modules if m.startswith('amiro.behavior')])"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


class AffirmNLU:
    def intent(self, heard: SpeechHeard) -> tuple[str, float]:
        return ("affirm" if heard.text == "yes" else "deny"), 1.0


class OneSecondSpeech:
    def say(self, text: str, lang: str, act: str, to: str) -> float:
        return 1.0


@pytest.mark.parametrize(
    ("answer", "outcome", "status"),
    [("yes", "resident_ok", "done"), ("no", "help_called", "failed")],
)
def test_the_fall_behaviour_acknowledges_its_notification(
    answer: str, outcome: str, status: str
) -> None:
    """From its question on, the shipped fall behaviour answers the notification it runs for."""
    runtime = Runtime(SimClock())
    modules = Modules(clock=runtime.clock, nlu=AffirmNLU(), speech=OneSecondSpeech())
    engine = runtime.add(BehaviorEngine(config=EngineConfig(), modules=modules))
    handlers = HandlerRegistry(engine)
    text = shipped_behavior("fall").read_text(encoding="utf-8")
    handlers.register(
        FALL_KIND, lambda p: loads_behavior(text.replace("entry: search", "entry: ask"), "f", p)
    )
    runtime.add(NotificationHandlerNode(engine, handlers, {}))
    _, acks = _bus_log(runtime)
    runtime.start()
    runtime.bus.publish(names.NOTIFICATIONS, Notification("f-1", "maria", FALL_KIND, 100))
    runtime.spin_for(2.0)
    runtime.bus.publish(names.HEARD, SpeechHeard(answer, "en", "maria"))
    runtime.spin_until(lambda: bool(engine.runs) and engine.idle, 20.0)
    runtime.spin_for(1.0)
    (run,) = engine.runs.values()
    assert run.outcome == outcome
    assert [(a.id, a.status) for a in acks] == [("f-1", status)]
