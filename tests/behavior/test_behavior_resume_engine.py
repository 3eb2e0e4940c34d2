"""Starting a behaviour at a checkpoint's task with its blackboard, or else at its entry."""

from __future__ import annotations

import json
from dataclasses import replace

from behavior_fakes import FakeWait, FakeWork, make_engine, order, run_all

from amiro.behavior import End, TaskGraph
from amiro.behavior.checkpoint import Checkpoint, FinishedTask
from amiro.core.messages import Point


def hydration_like() -> TaskGraph:
    """find (writes the position) -> go (reads it) -> talk; a failed find ends the behaviour."""
    return (
        TaskGraph("visit", 2, blackboard={"person": "maria"})
        .add(
            "find",
            FakeWork(1.0, write="position", value=Point(1.0, 2.0, 0.9)),
            on_success="go",
            on_failure=End("not_found"),
        )
        .add("go", FakeWait(2.0, value="$position"), on_success="talk")
        .add("talk", FakeWork(1.0, value="$person"))
    )


def checkpoint_while(task: str) -> Checkpoint:
    """Run ``visit`` until ``task`` is running and take its checkpoint through JSON."""
    runtime, engine = make_engine()
    run = engine.submit(hydration_like())
    assert runtime.spin_until(lambda: (engine.current() or {}).get("task") == task, 30)
    checkpoint = engine.checkpoint(run.id)
    assert checkpoint is not None
    return Checkpoint.from_dict(json.loads(json.dumps(checkpoint.to_dict())))


def test_resumed_run_starts_at_the_checkpoint_task_with_its_blackboard() -> None:
    checkpoint = checkpoint_while("go")
    assert checkpoint.task == "go" and checkpoint.finished == (FinishedTask("find", "success"),)
    assert checkpoint.blackboard["position"] == Point(1.0, 2.0, 0.9)

    runtime, engine = make_engine()  # the restarted process: a new engine, the same graph
    run = engine.submit(hydration_like(), resume=checkpoint)
    run_all(runtime, engine)
    assert order(engine) == [("visit#1", "go", "success"), ("visit#1", "talk", "success")]
    assert run.outcome == "completed"
    assert run.records[0].detail == {"value": Point(1.0, 2.0, 0.9)}  # restored, not re-found
    resumed = [e for e in engine.events if e.type == "behavior_resumed"]
    assert len(resumed) == 1 and resumed[0].task == "go"
    assert (
        resumed[0].detail["finished"] == ["find"] and resumed[0].detail["checkpoint"] == "visit#1"
    )
    started = [e.task for e in engine.events if e.type == "task_started"]
    assert started == ["go", "talk"]
    assert engine.resume_failures == 0


def test_finished_outcomes_must_lead_to_the_task_through_the_edges() -> None:
    checkpoint = checkpoint_while("go")
    # "find" failing would have ended the behaviour, so it cannot have led to "go".
    wrong_edge = replace(checkpoint, finished=(FinishedTask("find", "failure"),))
    # "talk" is not where "find" succeeding leads.
    wrong_task = replace(checkpoint, task="talk")
    # "go" cannot have finished before the entry ran.
    wrong_order = replace(checkpoint, finished=(FinishedTask("go", "success"),))
    for bad in (wrong_edge, wrong_task, wrong_order):
        runtime, engine = make_engine()
        run = engine.submit(hydration_like(), resume=bad)
        run_all(runtime, engine)
        assert [r.task_id for r in run.records] == ["find", "go", "talk"]
        assert engine.resume_failures == 1
        rejected = [e for e in engine.events if e.type == "resume_rejected"]
        assert len(rejected) == 1 and rejected[0].task == "find"
        assert not any(e.type == "behavior_resumed" for e in engine.events)


def test_unknown_task_foreign_graph_or_stale_checkpoint_runs_from_the_entry() -> None:
    checkpoint = checkpoint_while("talk")
    cases = {
        "no task 'dance'": replace(checkpoint, task="dance"),
        "does not fit 'visit'": replace(checkpoint, graph="medication"),
        "stale": replace(checkpoint, stamp=-601.0),  # the new engine starts at t = 0
    }
    for reason, bad in cases.items():
        runtime, engine = make_engine()
        run = engine.submit(hydration_like(), resume=bad)
        run_all(runtime, engine)
        assert run.records[0].task_id == "find" and run.outcome == "completed"
        rejected = [e for e in engine.events if e.type == "resume_rejected"]
        assert engine.resume_failures == 1 and reason in rejected[0].detail["reason"]


def test_checkpoint_of_a_preempted_run_names_its_pending_task() -> None:
    runtime, engine = make_engine()
    run = engine.submit(hydration_like())
    assert runtime.spin_until(lambda: (engine.current() or {}).get("task") == "go", 30)
    urgent = engine.submit(TaskGraph("urgent", 9).add("u", FakeWork(1.0)))
    assert runtime.spin_until(lambda: (engine.current() or {}).get("graph") == urgent.id, 5)
    checkpoint = engine.checkpoint(run.id)
    assert checkpoint is not None and checkpoint.task == "go"
    # The preempted "go" is not finished: it runs again on resume.
    assert checkpoint.finished == (FinishedTask("find", "success"),)
    run_all(runtime, engine)
    assert engine.checkpoint(run.id) is None and engine.checkpoint("nope#1") is None


def test_values_a_checkpoint_cannot_carry_are_named_not_sent() -> None:
    runtime, engine = make_engine()
    graph = TaskGraph("g", blackboard={"handle": object(), "n": 3}).add("a", FakeWork(1.0))
    run = engine.submit(graph)
    checkpoint = engine.checkpoint(run.id)
    assert checkpoint is not None and checkpoint.task == "a" and checkpoint.finished == ()
    assert checkpoint.omitted == ("handle",) and checkpoint.blackboard == {"n": 3}
    json.dumps(checkpoint.to_dict())  # the rest travels
    run_all(runtime, engine)
