from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from behavior_fakes import FakeWork, make_engine, run_all

from amiro.behavior import HandlerError, HandlerRegistry, TaskGraph, yaml_handler


def go_to(payload: dict[str, Any]) -> TaskGraph:
    return TaskGraph("go_to", 3, blackboard={"target": payload["target"]}).add(
        "move", FakeWork(0.1, value="$target")
    )


def test_handle_builds_and_submits() -> None:
    runtime, engine = make_engine()
    handlers = HandlerRegistry(engine)
    handlers.register("go_to", go_to)
    assert "go_to" in handlers and handlers.kinds() == ["go_to"]
    run = handlers.handle("go_to", {"target": "kitchen"})
    assert run.id == "go_to#1" and engine.runs[run.id] is run
    run_all(runtime, engine)
    assert run.outcome == "completed"
    assert run.records[0].detail == {"value": "kitchen"}


def test_unknown_kind_and_bad_payload_are_clear_errors() -> None:
    _, engine = make_engine()
    handlers = HandlerRegistry(engine)
    handlers.register("go_to", go_to)
    with pytest.raises(HandlerError, match=r"no handler for event kind 'dance' \(known: go_to\)"):
        handlers.handle("dance", {})
    with pytest.raises(HandlerError, match="payload lacks 'target'"):
        handlers.handle("go_to", {})
    with pytest.raises(HandlerError, match="already registered"):
        handlers.register("go_to", go_to)
    assert engine.idle and not engine.runs


def test_decorator_and_yaml_handler(tmp_path: Path) -> None:
    runtime, engine = make_engine()
    handlers = HandlerRegistry(engine)

    @handlers.handler("medication")
    def medication(payload: dict[str, Any]) -> TaskGraph:
        return TaskGraph("medication", 8).add("remind", FakeWork(0.1))

    path = tmp_path / "hydration.yaml"
    path.write_text(
        "name: hydration\npriority: 5\nblackboard: {person: nobody}\nentry: a\n"
        "tasks:\n  a: {type: FakeWork, params: {duration: 0.1, value: $person}}\n",
        encoding="utf-8",
    )
    handlers.register("hydration", yaml_handler(path))
    hydration = handlers.handle("hydration", {"person": "maria"})
    meds = handlers.handle("medication")
    run_all(runtime, engine)
    assert hydration.records[0].detail == {"value": "maria"}
    assert meds.outcome == hydration.outcome == "completed"
