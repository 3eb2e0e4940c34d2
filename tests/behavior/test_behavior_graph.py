from __future__ import annotations

import pytest
from behavior_fakes import FakeWork

from amiro.behavior import COMPLETED, FAILED, End, TaskError, TaskGraph


def test_defaults_end_completed_and_failed() -> None:
    g = TaskGraph("g").add("a", FakeWork()).validate()
    assert g.entry == "a"
    assert g.tasks["a"].on_success == COMPLETED
    assert g.tasks["a"].on_failure == FAILED
    assert g.outcomes() == {"completed", "failed"}


def test_fluent_builder_edges_and_explicit_entry() -> None:
    g = (
        TaskGraph("hydration", priority=5, blackboard={"person": "maria"}, entry="search")
        .add("move", FakeWork(), on_success=End("done"))
        .add("search", FakeWork(), on_success="move", on_failure=End("person_not_found"))
        .validate()
    )
    assert g.entry == "search"
    assert g.tasks["search"].next(True) == "move"
    assert g.tasks["search"].next(False) == End("person_not_found")
    assert g.to_dict()["tasks"]["search"]["on_failure"] == {"end": "person_not_found"}
    assert g.warnings() == []


def test_unknown_edge_target_is_an_error() -> None:
    g = TaskGraph("g").add("a", FakeWork(), on_success="nope")
    with pytest.raises(TaskError, match=r"task 'a' on_success leads to unknown task 'nope'"):
        g.validate()


def test_missing_entry_is_an_error() -> None:
    with pytest.raises(TaskError, match="entry 'x' is not one of its tasks"):
        TaskGraph("g", entry="x").add("a", FakeWork()).validate()
    with pytest.raises(TaskError, match="has no tasks"):
        TaskGraph("empty").validate()


def test_duplicate_ids_and_non_tasks_rejected() -> None:
    g = TaskGraph("g").add("a", FakeWork())
    with pytest.raises(TaskError, match="used twice"):
        g.add("a", FakeWork())
    with pytest.raises(TaskError, match="not a Task"):
        g.add("b", "FakeWork")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="priority"):
        TaskGraph("g", priority="high")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="outcome"):
        End("")


def test_unreachable_tasks_are_warnings_not_errors() -> None:
    g = TaskGraph("g").add("a", FakeWork()).add("orphan", FakeWork(), on_success="a")
    g.validate()
    assert g.reachable() == {"a"}
    assert g.warnings() == ["behaviour g: task 'orphan' is unreachable from entry 'a'"]
