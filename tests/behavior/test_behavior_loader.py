from __future__ import annotations

from pathlib import Path

import pytest
from behavior_fakes import FakeWork, make_engine, order, run_all

from amiro.behavior import End, GraphRun, load_behavior, loads_behavior
from amiro.core.config import ConfigError
from amiro.system import SHIPPED_BEHAVIORS, shipped_behavior

assert FakeWork.type_name == "FakeWork"  # registers the fake types used below

GOOD = """
name: hydration
priority: 5
blackboard: {person: maria, d: 0.1}
entry: search
tasks:
  search: {type: FakeWork, params: {duration: $d}, on_success: move,
           on_failure: {end: person_not_found}}
  move: {type: FakeWork, params: {duration: 0.1, value: $person}, on_success: remind,
         on_failure: {end: person_unreachable}}
  remind: {type: FakeWait, params: {duration: 0.1, succeed: false}}
"""


def test_yaml_happy_path_builds_and_runs() -> None:
    g = loads_behavior(GOOD)
    assert (g.name, g.priority, g.entry) == ("hydration", 5, "search")
    assert g.blackboard == {"person": "maria", "d": 0.1}
    assert g.tasks["search"].on_success == "move"
    assert g.tasks["search"].on_failure == End("person_not_found")
    assert g.tasks["remind"].on_success == End("completed")
    assert g.tasks["remind"].on_failure == End("failed")
    assert g.tasks["remind"].type_name == "FakeWait"
    runtime, engine = make_engine()
    run = engine.submit(g)
    run_all(runtime, engine)
    assert [t for _, t, _ in order(engine)] == ["search", "move", "remind"]
    assert run.outcome == "failed"
    assert run.records[1].detail == {"value": "maria"}


def test_load_from_path_with_overrides(tmp_path: Path) -> None:
    path = tmp_path / "hydration.yaml"
    path.write_text(GOOD, encoding="utf-8")
    g = load_behavior(path, overrides={"person": "ion"})
    assert g.blackboard == {"person": "ion", "d": 0.1}


def one_line_error(text: str, source: str = "beh.yaml") -> str:
    with pytest.raises(ConfigError) as info:
        loads_behavior(text, source=source)
    msg = str(info.value)
    assert "\n" not in msg
    assert msg.startswith(f"{source}: ")
    return msg


def test_unknown_task_type() -> None:
    msg = one_line_error(GOOD.replace("type: FakeWait", "type: Dance"))
    assert "tasks.remind.type: unknown task type 'Dance'" in msg
    assert "FakeWork" in msg  # lists the known types


def test_bad_params() -> None:
    msg = one_line_error(GOOD.replace("succeed: false", "speed: 3"))
    assert "tasks.remind.params:" in msg and "speed" in msg


def test_bad_edge_target() -> None:
    msg = one_line_error(GOOD.replace("on_success: remind", "on_success: remnd"))
    assert "tasks.move.on_success: unknown task 'remnd'" in msg


def test_missing_or_unknown_entry() -> None:
    msg = one_line_error(GOOD.replace("entry: search\n", ""))
    assert "entry" in msg and "required" in msg.lower()
    msg = one_line_error(GOOD.replace("entry: search", "entry: start"))
    assert "entry: 'start' is not a task" in msg


def test_unknown_keys_and_bad_shapes() -> None:
    assert "colour" in one_line_error(GOOD + "colour: blue\n")
    assert "tasks.search" in one_line_error(GOOD.replace("on_success: move,", "next: move,"))
    assert "at least one task" in one_line_error("name: x\nentry: a\ntasks: {}\n")
    assert "mapping" in one_line_error("- just a list\n")
    assert "line" in one_line_error("name: [unclosed\n")


def test_missing_file_is_a_config_error(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="no such file"):
        load_behavior(tmp_path / "missing.yaml")


def test_bad_edge_shape() -> None:
    msg = one_line_error(GOOD.replace("{end: person_not_found}", "{ends: person_not_found}"))
    assert "tasks.search.on_failure: Value error, an edge is a task id or {end: outcome}" in msg


# --- typed task parameters ---------------------------------------------------------------

LISTEN = """
name: ask
priority: 1
blackboard: {wait: 0.2}
entry: listen
tasks:
  listen: {type: Listen, params: {expect: [affirm], timeout_s: $wait}}
"""


def test_a_misspelt_parameter_is_refused_naming_file_task_and_field(tmp_path: Path) -> None:
    path = tmp_path / "hydration.yaml"
    path.write_text(LISTEN.replace("timeout_s: $wait", "timout_s: 10"), encoding="utf-8")
    with pytest.raises(ConfigError) as info:
        load_behavior(path)
    msg = str(info.value)
    assert "\n" not in msg and msg.startswith(f"{path}: ")
    assert "tasks.listen.params: Listen: unknown parameter 'timout_s'" in msg
    assert "did you mean 'timeout_s'" in msg


def test_a_misspelt_parameter_written_as_a_reference_is_refused() -> None:
    msg = one_line_error(LISTEN.replace("timeout_s: $wait", "timout_s: $wait"))
    assert "tasks.listen.params: Listen: unknown parameter 'timout_s'" in msg


def test_a_parameter_of_the_wrong_type_is_refused() -> None:
    msg = one_line_error(LISTEN.replace("timeout_s: $wait", "timeout_s: soon"))
    assert "tasks.listen.params: Listen: parameter 'timeout_s'" in msg and "'soon'" in msg
    msg = one_line_error(LISTEN.replace("expect: [affirm]", "expect: {yes: 1}"))
    assert "parameter 'expect'" in msg


def test_a_missing_required_parameter_is_refused() -> None:
    msg = one_line_error(LISTEN.replace("type: Listen", "type: Search"))
    assert "tasks.listen.params: Search: unknown parameter 'expect'" in msg
    text = "name: x\nentry: s\ntasks:\n  s: {type: Search, params: {dwell_s: 1}}\n"
    assert "Search: missing parameter 'person'" in one_line_error(text)


def run_listen(wait: object) -> GraphRun:
    runtime, engine = make_engine()
    run = engine.submit(loads_behavior(LISTEN, overrides={"wait": wait}))
    run_all(runtime, engine)
    started = [e for e in engine.events if e.type == "task_started"]
    assert started[0].detail["params"] == {"expect": ["affirm"], "timeout_s": "$wait"}
    return run


def test_references_resolve_and_are_validated_when_the_task_starts() -> None:
    g = loads_behavior(LISTEN)  # `$wait` stands for a number until the task starts
    assert g.tasks["listen"].task.params == {"expect": ["affirm"], "timeout_s": "$wait"}
    timed_out = run_listen(0.2).records[0]
    assert timed_out.detail == {"reason": "no_answer"}
    assert timed_out.end_s - timed_out.start_s == pytest.approx(0.2, abs=0.051)
    refused = run_listen("soon").records[0]
    assert refused.result == "failure" and refused.end_s == refused.start_s
    assert "Listen: parameter 'timeout_s'" in refused.detail["error"]


def test_shipped_behaviours_load() -> None:
    for name in SHIPPED_BEHAVIORS:
        graph = load_behavior(shipped_behavior(name))
        assert graph.name == name and graph.tasks
