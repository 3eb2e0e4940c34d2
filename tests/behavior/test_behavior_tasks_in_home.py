"""The task types working on the simulated home, and preemption inside the real system."""

from __future__ import annotations

from pathlib import Path

import pytest

from amiro.behavior.engine import GraphRun
from amiro.behavior.graph import TaskGraph
from amiro.behavior.handlers import yaml_handler
from amiro.behavior.task import TaskError, make_task
from amiro.core import names
from amiro.core.messages import (
    Acknowledgement,
    Notification,
    Point,
    SpeechHeard,
    SpeechRequest,
)
from amiro.scenarios.hydration import HydrationOptions, scenario_config
from amiro.system import System, SystemConfig, build_system

ANNOUNCE = """
name: announce
priority: 1
blackboard: {}
entry: say
tasks:
  say: {type: Say, params: {text: "Someone is at the door."}}
"""


def home(branch: str | None = None, trigger: bool = True) -> System:
    cfg = scenario_config(HydrationOptions(seed=3, branch=branch))
    if not trigger:
        cfg = cfg.model_copy(
            update={"environment": cfg.environment.model_copy(update={"rules": ()})}
        )
    system = build_system(cfg)
    system.start()
    return system


def run_graph(system: System, graph: TaskGraph, timeout: float = 300.0) -> GraphRun:
    run = system.engine.submit(graph)
    system.runtime.spin_until(lambda: run.done, timeout)
    return run


def test_urgent_behaviour_preempts_search_and_hydration_resumes(tmp_path: Path) -> None:
    behaviour = tmp_path / "announce.yaml"
    behaviour.write_text(ANNOUNCE)
    system = home()
    system.handlers.register("doorbell", yaml_handler(behaviour))
    rt = system.runtime
    said: list[tuple[float, str]] = []
    rt.bus.subscribe("/amiro/say", SpeechRequest, lambda m: said.append((rt.clock.now(), m.text)))
    rt.spin_until(lambda: bool(system.engine.current()), 20.0)  # hydration is searching
    rt.spin_for(4.0)
    assert system.engine.current()["type"] == "Search"  # type: ignore[index]
    sent = rt.clock.now()
    rt.bus.publish("/amiro/notifications", Notification("bell-1", "maria", "doorbell", 9))
    rt.spin_until(lambda: any(t for t, text in said if "door" in text), 5.0)
    door_at = next(t for t, text in said if "door" in text)
    assert door_at - sent <= 0.2  # within a couple of control ticks, not after the search
    hydration = next(r for r in system.engine.runs.values() if r.name == "hydration")
    rt.spin_until(lambda: hydration.done, 300.0)
    results = [(r.task_id, r.result) for r in hydration.records]
    assert results[0] == ("search", "preempted")
    assert results[1] == ("search", "success")  # resumed from the same task, afresh
    assert hydration.outcome == "completed"


def test_a_denied_reminder_takes_the_listen_failure_edge() -> None:
    data = scenario_config(HydrationOptions(seed=2)).model_dump()
    data["sim"]["residents"][0]["script"] = {
        "hydration_reminder": {"reply": "deny"},
        "postpone_question": {"reply": "deny"},
    }
    system = build_system(SystemConfig.model_validate(data))
    system.start()
    system.runtime.spin_until(lambda: any(r.done for r in system.engine.runs.values()), 300.0)
    run = next(iter(system.engine.runs.values()))
    assert run.outcome == "not_confirmed"
    listens = [r for r in run.records if r.type == "Listen"]
    assert [r.detail["intent"] for r in listens] == ["deny", "deny"]


def test_notify_environment_publishes_the_contract_ack() -> None:
    system = home(trigger=False)
    acks: list[Acknowledgement] = []
    system.runtime.bus.subscribe("/amiro/notifications/ack", Acknowledgement, acks.append)
    graph = TaskGraph("ack", 1, blackboard={"notification_id": "n-42"})
    graph.add("ack", make_task("NotifyEnvironment", {"status": "postponed"}))
    run = run_graph(system, graph)
    assert run.outcome == "completed"
    assert [(a.id, a.status) for a in acks] == [("n-42", "postponed")]
    assert acks[0].ts.startswith("2026-") and acks[0].ts.endswith("+00:00")
    with pytest.raises(TaskError, match="parameter 'status'"):
        make_task("NotifyEnvironment", {"status": "maybe"})  # refused as written ...
    bad = TaskGraph("bad", 1, blackboard={"s": "maybe"})
    bad.add("ack", make_task("NotifyEnvironment", {"status": "$s"}))
    assert run_graph(system, bad).outcome == "failed"  # ... and as read from the blackboard


def test_move_to_a_place_and_to_a_person() -> None:
    system = home(trigger=False)
    graph = TaskGraph("go", 1).add("go", make_task("MoveTo", {"target": "kitchen"}))
    run = run_graph(system, graph)
    assert run.outcome == "completed"
    assert system.sim.robot.true_pose.distance_to(system.sim.world.place("kitchen")) < 0.15
    person = Point(6.5, 0.6, 0.6)
    graph = TaskGraph("near", 1).add("go", make_task("MoveTo", {"target": person, "approach": 1.2}))
    assert run_graph(system, graph).outcome == "completed"
    assert abs(system.sim.robot.true_pose.distance_to(person) - 1.2) < 0.3
    assert system.sim.robot.collisions == 0


def test_search_fails_cleanly_when_nobody_is_home() -> None:
    system = home(branch="person_absent", trigger=False)
    graph = TaskGraph("find", 1).add("find", make_task("Search", {"person": "maria"}))
    run = run_graph(system, graph, timeout=600.0)
    assert run.outcome == "failed"
    detail = run.records[0].detail
    assert detail["reason"] == "not_found"
    assert sorted(detail["rooms"]) == ["bathroom", "bedroom", "kitchen", "living_room"]


def _listen_for_affirm(system: System, reprompts: int) -> tuple[GraphRun, list[SpeechRequest]]:
    rt = system.runtime
    said: list[SpeechRequest] = []
    rt.bus.subscribe(names.SAY, SpeechRequest, said.append)
    graph = TaskGraph("ask", 1, blackboard={"lang": "en", "person": "nobody"})
    listen = {"expect": ["affirm"], "timeout_s": 5, "reprompts": reprompts}
    graph.add("listen", make_task("Listen", listen))
    run = system.engine.submit(graph)
    rt.spin_for(0.5)
    # a recogniser's result (no oracle intent): not an answer to a yes/no question
    rt.bus.publish(names.HEARD, SpeechHeard("what is the weather tomorrow", "en", "maria"))
    rt.spin_for(1.0)
    return run, said


def test_listen_asks_again_after_a_non_answer() -> None:
    system = home(trigger=False)
    run, said = _listen_for_affirm(system, reprompts=1)
    assert [s.act for s in said if s.act == "answer_reprompt"] == ["answer_reprompt"]
    assert not run.done
    system.runtime.bus.publish(names.HEARD, SpeechHeard("yes please", "en", "maria"))
    system.runtime.spin_until(lambda: run.done, 30.0)
    assert run.outcome == "completed"
    assert [r.detail["intent"] for r in run.records] == ["affirm"]


def test_listen_gives_up_on_non_answers_once_it_asked_again() -> None:
    system = home(trigger=False)
    run, said = _listen_for_affirm(system, reprompts=0)
    assert "answer_reprompt" not in [s.act for s in said]
    assert run.done and run.outcome == "failed"
    assert run.records[-1].detail["reason"] == "no_answer"
