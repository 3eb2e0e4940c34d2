from __future__ import annotations

from typing import Any, ClassVar

import pytest
from behavior_fakes import EPS, FakeBoom, FakeWait, FakeWork, make_engine, order, run_all

from amiro.behavior import (
    End,
    RunStatus,
    Task,
    TaskContext,
    TaskError,
    TaskGraph,
    TaskStatus,
)
from amiro.core import names
from amiro.core.messages import BehaviorEvent


def chain(name: str, priority: int, *steps: tuple[str, Task]) -> TaskGraph:
    """A linear graph: each step's success leads to the next."""
    g = TaskGraph(name, priority)
    for i, (tid, task) in enumerate(steps):
        nxt = steps[i + 1][0] if i + 1 < len(steps) else None
        g.add(tid, task, on_success=nxt)
    return g


# --- edges ------------------------------------------------------------------------------


def test_success_and_failure_edges_are_followed() -> None:
    runtime, engine = make_engine()
    g = (
        TaskGraph("g", 1)
        .add("try", FakeWork(0.1, succeed=False), on_success="never", on_failure="recover")
        .add("never", FakeWork(0.1))
        .add("recover", FakeWork(0.1), on_success=End("recovered"))
    )
    run = engine.submit(g)
    assert run.id == "g#1" and run.status is RunStatus.QUEUED and not run.done
    run_all(runtime, engine)
    assert order(engine) == [("g#1", "try", "failure"), ("g#1", "recover", "success")]
    assert run.done and run.status == "finished" and run.outcome == "recovered"
    assert [r.task_id for r in run.records] == ["try", "recover"]


def test_default_ends_record_completed_and_failed() -> None:
    runtime, engine = make_engine()
    ok = engine.submit(TaskGraph("ok").add("a", FakeWork(0.1)))
    bad = engine.submit(TaskGraph("bad").add("a", FakeWork(0.1, succeed=False)))
    again = engine.submit(TaskGraph("ok").add("a", FakeWork(0.1)))
    run_all(runtime, engine)
    assert (ok.outcome, bad.outcome, again.outcome) == ("completed", "failed", "completed")
    assert again.id == "ok#2"
    finished = [e for e in engine.events if e.type == "graph_finished"]
    assert [(e.graph, e.detail["outcome"]) for e in finished] == [
        ("ok#1", "completed"),
        ("bad#1", "failed"),
        ("ok#2", "completed"),
    ]


def test_blackboard_params_and_results_per_run() -> None:
    runtime, engine = make_engine()
    g = (
        TaskGraph("g", blackboard={"person": "maria", "d": 0.2})
        .add("find", FakeWork("$d", write="position", value=(1.0, 2.0)), on_success="greet")
        .add("greet", FakeWork(0.1, value="$person"))
    )
    run = engine.submit(g)
    run_all(runtime, engine)
    assert run.blackboard["position"] == (1.0, 2.0)
    assert "position" not in g.blackboard  # the template stays clean
    assert run.records[0].end_s - run.records[0].start_s == pytest.approx(0.2, abs=0.051)
    assert run.records[1].detail == {"value": "maria"}


def test_missing_blackboard_key_fails_the_task() -> None:
    runtime, engine = make_engine()
    run = engine.submit(TaskGraph("g").add("a", FakeWork(value="$nobody")))
    run_all(runtime, engine)
    assert run.outcome == "failed"
    assert "blackboard has no 'nobody'" in run.records[0].detail["error"]


def test_invalid_graph_is_rejected_at_submit() -> None:
    _, engine = make_engine()
    with pytest.raises(TaskError):
        engine.submit(TaskGraph("g").add("a", FakeWork(), on_failure="ghost"))
    assert engine.idle and not engine.runs


# --- the paper's priority rule ------------------------------------------------------------


def test_paper_rule_atomic_task_then_all_of_urgent_graph_then_successor() -> None:
    runtime, engine = make_engine(preemption=False)
    a = engine.submit(chain("A", 1, ("a1", FakeWork(1.0)), ("a2", FakeWork(0.5))))
    runtime.spin_for(0.3)
    b = engine.submit(chain("B", 5, ("b1", FakeWork(0.2)), ("b2", FakeWork(0.2))))
    run_all(runtime, engine)
    assert order(engine) == [
        ("A#1", "a1", "success"),
        ("B#1", "b1", "success"),
        ("B#1", "b2", "success"),
        ("A#1", "a2", "success"),
    ]
    a1 = a.records[0]
    assert a1.end_s - a1.start_s == pytest.approx(1.0, abs=0.051)  # atomic: not cut short
    assert b.records[0].start_s >= a1.end_s - EPS
    assert a.records[1].start_s >= b.records[1].end_s - EPS
    types = [(e.type, e.graph) for e in engine.events if e.graph == "A#1"]
    assert ("graph_suspended", "A#1") in types and ("graph_resumed", "A#1") in types
    assert a.outcome == b.outcome == "completed"


def test_non_cancellable_task_is_never_preempted_even_with_extension_on() -> None:
    runtime, engine = make_engine(preemption=True)
    engine.submit(chain("A", 1, ("a1", FakeWork(1.0)), ("a2", FakeWork(0.5))))
    runtime.spin_for(0.3)
    engine.submit(chain("B", 5, ("b1", FakeWork(0.2))))
    run_all(runtime, engine)
    assert order(engine) == [
        ("A#1", "a1", "success"),
        ("B#1", "b1", "success"),
        ("A#1", "a2", "success"),
    ]
    assert not [e for e in engine.events if e.type == "task_preempted"]


def test_equal_priorities_run_in_arrival_order() -> None:
    runtime, engine = make_engine()
    engine.submit(chain("A", 3, ("a1", FakeWork(0.2)), ("a2", FakeWork(0.2))))
    engine.submit(chain("B", 3, ("b1", FakeWork(0.2))))
    runtime.spin_for(0.1)
    engine.submit(chain("C", 3, ("c1", FakeWork(0.2))))
    run_all(runtime, engine)
    assert [(g, t) for g, t, _ in order(engine)] == [
        ("A#1", "a1"),
        ("A#1", "a2"),
        ("B#1", "b1"),
        ("C#1", "c1"),
    ]


def test_deferred_graph_keeps_its_arrival_rank() -> None:
    """A (p1) is put aside for B (p5); C (p1) arrived after A, so A's successor goes first."""
    runtime, engine = make_engine(preemption=False)
    engine.submit(chain("A", 1, ("a1", FakeWork(0.5)), ("a2", FakeWork(0.2))))
    runtime.spin_for(0.2)
    engine.submit(chain("B", 5, ("b1", FakeWork(0.2))))
    engine.submit(chain("C", 1, ("c1", FakeWork(0.2))))
    run_all(runtime, engine)
    assert [(g, t) for g, t, _ in order(engine)] == [
        ("A#1", "a1"),
        ("B#1", "b1"),
        ("A#1", "a2"),
        ("C#1", "c1"),
    ]


def test_lower_priority_graph_waits_for_the_higher_one() -> None:
    runtime, engine = make_engine()
    engine.submit(chain("H", 5, ("h1", FakeWork(0.5)), ("h2", FakeWork(0.5))))
    runtime.spin_for(0.2)
    low = engine.submit(chain("L", 1, ("l1", FakeWork(0.1))))
    runtime.spin_for(0.5)
    assert low.status is RunStatus.QUEUED
    assert engine.queue_snapshot() == [
        {"graph": "L#1", "name": "L", "task": "l1", "type": "FakeWork", "priority": 1}
    ]
    current = engine.current()
    assert current is not None and (current["graph"], current["task"]) == ("H#1", "h2")
    run_all(runtime, engine)
    assert [(g, t) for g, t, _ in order(engine)] == [("H#1", "h1"), ("H#1", "h2"), ("L#1", "l1")]
    assert engine.current() is None and engine.queue_snapshot() == []


# --- the cancellable extension -------------------------------------------------------------


def preemption_setup(preemption: bool) -> tuple[Any, Any, Any, Any, float]:
    FakeWait.cancelled_at.clear()
    runtime, engine = make_engine(preemption=preemption)
    a = engine.submit(chain("A", 1, ("a1", FakeWait(2.0)), ("a2", FakeWork(0.2))))
    runtime.spin_for(0.5)
    t_submit = runtime.clock.now()
    b = engine.submit(chain("B", 5, ("b1", FakeWork(0.3)), ("b2", FakeWork(0.3))))
    run_all(runtime, engine)
    return engine, a, b, runtime, t_submit


def test_cancellable_task_is_preempted_within_one_tick_and_resumes_afresh() -> None:
    engine, a, b, _, t_submit = preemption_setup(preemption=True)
    assert order(engine) == [
        ("A#1", "a1", "preempted"),
        ("B#1", "b1", "success"),
        ("B#1", "b2", "success"),
        ("A#1", "a1", "success"),
        ("A#1", "a2", "success"),
    ]
    preempted = a.records[0]
    assert t_submit <= preempted.end_s <= t_submit + 0.05 + EPS
    assert FakeWait.cancelled_at == [preempted.end_s]
    assert b.records[0].start_s == pytest.approx(preempted.end_s)
    resumed = a.records[1]
    assert resumed.start_s >= b.records[-1].end_s - EPS
    assert resumed.end_s - resumed.start_s == pytest.approx(2.0, abs=0.051)  # started afresh
    ev = [e for e in engine.events if e.type == "task_preempted"]
    assert len(ev) == 1 and ev[0].task == "a1" and ev[0].detail["by"] == "B#1"
    resumed_ev = [e for e in engine.events if e.type == "graph_resumed"]
    assert [(e.graph, e.task) for e in resumed_ev] == [("A#1", "a1")]
    assert a.outcome == b.outcome == "completed"


class FinishOnSignal(Task):
    """Cancellable; ends with a result on the first update after ``signal`` is set."""

    cancellable = True
    signal: ClassVar[list[bool]] = []
    starts: ClassVar[list[float]] = []

    def start(self, ctx: TaskContext) -> None:
        FinishOnSignal.starts.append(ctx.now())

    def update(self, ctx: TaskContext) -> TaskStatus:
        if not FinishOnSignal.signal:
            return TaskStatus.RUNNING
        ctx.blackboard["result"] = "kept"
        return TaskStatus.SUCCESS


def test_task_finishing_on_the_preempting_tick_keeps_its_result() -> None:
    FinishOnSignal.signal.clear()
    FinishOnSignal.starts.clear()
    runtime, engine = make_engine(preemption=True)
    a = engine.submit(
        chain("A", 1, ("a1", FinishOnSignal()), ("a2", FakeWork(0.1, value="$result")))
    )
    runtime.spin_for(0.3)
    FinishOnSignal.signal.append(True)  # a1 is done at its next poll ...
    engine.submit(chain("B", 5, ("b1", FakeWork(0.2))))  # ... which is when B arrives
    run_all(runtime, engine)
    assert order(engine) == [
        ("A#1", "a1", "success"),
        ("B#1", "b1", "success"),
        ("A#1", "a2", "success"),
    ]
    assert len(FinishOnSignal.starts) == 1  # not re-run from the start
    assert not [e for e in engine.events if e.type == "task_preempted"]
    assert a.records[-1].detail == {"value": "kept"}


def test_with_extension_off_a_cancellable_task_is_waited_for() -> None:
    engine, a, b, _, t_submit = preemption_setup(preemption=False)
    assert order(engine) == [
        ("A#1", "a1", "success"),
        ("B#1", "b1", "success"),
        ("B#1", "b2", "success"),
        ("A#1", "a2", "success"),
    ]
    assert FakeWait.cancelled_at == []
    assert a.records[0].end_s > t_submit + 1.0
    assert b.records[0].start_s >= a.records[0].end_s - EPS


def test_equal_priority_does_not_preempt() -> None:
    runtime, engine = make_engine(preemption=True)
    engine.submit(chain("A", 3, ("a1", FakeWait(1.0))))
    runtime.spin_for(0.2)
    engine.submit(chain("B", 3, ("b1", FakeWork(0.1))))
    run_all(runtime, engine)
    assert order(engine) == [("A#1", "a1", "success"), ("B#1", "b1", "success")]


# --- failures -------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("where", "error"),
    [
        ("update", "RuntimeError: boom in update"),
        ("start", "RuntimeError: boom in start"),
        ("module", "TaskError: no 'navigation' module"),
    ],
)
def test_raising_task_takes_failure_edge_and_engine_keeps_running(where: str, error: str) -> None:
    runtime, engine = make_engine()
    g = (
        TaskGraph("A", 2)
        .add("boom", FakeBoom(where), on_success=End("impossible"), on_failure="recover")
        .add("recover", FakeWork(0.1), on_success=End("recovered"))
    )
    a = engine.submit(g)
    runtime.spin_for(0.2)
    later = engine.submit(chain("B", 1, ("b1", FakeWork(0.1))))
    run_all(runtime, engine)
    assert a.records[0].result == "failure"
    assert a.records[0].detail["error"].startswith(error)
    assert a.outcome == "recovered"
    assert later.outcome == "completed"
    assert engine.running and not runtime.supervisor.health
    finished = [e for e in engine.events if e.type == "task_finished" and e.task == "boom"]
    assert finished[0].detail["detail"]["error"].startswith(error)


def test_task_failing_at_start_in_a_loop_does_not_hang_the_tick() -> None:
    runtime, engine = make_engine()
    g = TaskGraph("loop").add("boom", FakeBoom("start"), on_failure="boom")
    run = engine.submit(g)
    runtime.spin_for(0.2)
    assert engine.cancel_graph(run.id)
    run_all(runtime, engine, timeout=1.0)
    assert run.outcome == "cancelled"
    assert len(run.records) > 10


# --- cancel_graph ---------------------------------------------------------------------------


def test_cancel_graph_queued_running_cancellable_and_atomic() -> None:
    runtime, engine = make_engine()
    FakeWait.cancelled_at.clear()
    waiting = engine.submit(chain("W", 1, ("w1", FakeWait(5.0)), ("w2", FakeWork(0.1))))
    queued = engine.submit(chain("Q", 1, ("q1", FakeWork(0.1))))
    runtime.spin_for(0.2)
    assert engine.cancel_graph(queued.id)
    assert queued.outcome == "cancelled" and not queued.records
    assert engine.cancel_graph(waiting.id)  # cancellable: stopped at once
    assert waiting.outcome == "cancelled" and waiting.records[-1].result == "cancelled"
    assert FakeWait.cancelled_at == [waiting.records[-1].end_s]
    assert not engine.cancel_graph(waiting.id) and not engine.cancel_graph("nope#1")

    atomic = engine.submit(chain("T", 1, ("t1", FakeWork(0.5)), ("t2", FakeWork(0.1))))
    runtime.spin_for(0.2)
    assert engine.cancel_graph(atomic.id)
    assert not atomic.done  # the atomic task finishes first
    run_all(runtime, engine)
    assert [(r.task_id, r.result) for r in atomic.records] == [("t1", "success")]
    assert atomic.outcome == "cancelled"


# --- events ---------------------------------------------------------------------------------


def test_events_are_published_in_order_on_the_events_topic() -> None:
    runtime, engine = make_engine()
    got: list[BehaviorEvent] = []
    runtime.bus.subscribe(names.EVENTS, BehaviorEvent, got.append, depth=1000)
    engine.submit(chain("A", 1, ("a1", FakeWork(0.1)), ("a2", FakeWork(0.1, succeed=False))))
    run_all(runtime, engine)
    runtime.spin_for(0.1)
    assert [(e.type, e.task) for e in got] == [
        ("graph_submitted", None),
        ("task_started", "a1"),
        ("task_finished", "a1"),
        ("task_started", "a2"),
        ("task_finished", "a2"),
        ("graph_finished", None),
    ]
    assert got == engine.events
    assert got[2].detail["result"] == "success" and got[4].detail["result"] == "failure"
    assert got[-1].detail["outcome"] == "failed"
    assert all(e.graph == "A#1" for e in got)
    stamps = [e.stamp for e in got]
    assert stamps == sorted(stamps)
    assert engine.report()["runs"][0]["outcome"] == "failed"
