"""The task execution engine: a priority queue of tasks, one running at a time (section 3.7).

Semantics of the paper: tasks are atomic; when a task ends, its successor runs next unless
the head of the queue belongs to a behaviour of strictly higher priority, in which case the
successor is re-inserted and waits until that behaviour has ended.  Equal priorities run in
arrival order.  Extension: a task type that declares ``cancellable = True`` is cancelled
within one control tick when a strictly more urgent behaviour waits (``preemption`` config),
and its behaviour later resumes from that task, started afresh.  Extension: a behaviour
submitted with a :class:`~amiro.behavior.checkpoint.Checkpoint` (taken by another engine,
e.g. before its process died) starts at the checkpoint's task with its blackboard restored.
"""

from __future__ import annotations

import enum
import itertools
from dataclasses import dataclass, field
from typing import Any

from pydantic import Field

from amiro.behavior.checkpoint import (
    EDGE_RESULTS,
    Checkpoint,
    CheckpointError,
    FinishedTask,
    portable,
)
from amiro.behavior.graph import End, TaskGraph
from amiro.behavior.modules import Modules
from amiro.behavior.task import (
    Task,
    TaskContext,
    TaskError,
    TaskRecord,
    TaskStatus,
    task_type_name,
)
from amiro.core import names
from amiro.core.config import Section
from amiro.core.messages import BehaviorEvent
from amiro.core.node import Node

# How many tasks may start in one tick; bounds a loop of tasks that fail as they start.
_MAX_STARTS_PER_TICK = 64


class EngineConfig(Section):
    tick_s: float = Field(0.05, gt=0)
    preemption: bool = True
    resume_max_age_s: float = Field(
        600.0, gt=0, description="an older checkpoint is stale: its behaviour runs from the entry"
    )


class RunStatus(enum.StrEnum):
    QUEUED = "queued"
    RUNNING = "running"
    FINISHED = "finished"


@dataclass(eq=False)
class GraphRun:
    """One submission of a behaviour: its own blackboard, records and outcome."""

    graph: TaskGraph
    id: str
    seq: int
    blackboard: dict[str, Any]
    submitted_s: float
    status: RunStatus = RunStatus.QUEUED
    outcome: str | None = None
    finished_s: float | None = None
    records: list[TaskRecord] = field(default_factory=list)
    suspended: bool = False
    cancel_requested: bool = False

    @property
    def name(self) -> str:
        return self.graph.name

    @property
    def priority(self) -> int:
        return self.graph.priority

    @property
    def done(self) -> bool:
        return self.status is RunStatus.FINISHED

    def to_dict(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "name": self.name,
            "priority": self.priority,
            "status": str(self.status),
            "outcome": self.outcome,
            "submitted_s": round(self.submitted_s, 3),
            "finished_s": None if self.finished_s is None else round(self.finished_s, 3),
            "tasks": [r.to_dict() for r in self.records],
        }


@dataclass(eq=False)
class _Pending:
    """A queued task instance; ``task`` is None until started (then the template's fresh())."""

    run: GraphRun
    task_id: str
    task: Task | None = None

    @property
    def key(self) -> tuple[int, int]:
        # Higher priority first; equal priority in the behaviours' arrival order.  One
        # behaviour has at most one pending task, so the run's sequence number suffices.
        return (-self.run.priority, self.run.seq)


@dataclass(eq=False)
class _Active:
    run: GraphRun
    task_id: str
    task: Task
    ctx: TaskContext
    started_s: float


class BehaviorEngine(Node):
    """Runs behaviours (task graphs) one task at a time, by priority."""

    def __init__(
        self,
        name: str = "behavior",
        config: EngineConfig | None = None,
        modules: Modules | None = None,
    ) -> None:
        super().__init__(name)
        self.config = config or EngineConfig()
        self.modules = modules if modules is not None else Modules()
        self.events: list[BehaviorEvent] = []
        self.records: list[TaskRecord] = []
        self.runs: dict[str, GraphRun] = {}
        self._queue: list[_Pending] = []
        self._active: _Active | None = None
        self._seq = itertools.count(1)
        self._per_name: dict[str, int] = {}
        self.resume_failures = 0

    # --- lifecycle ------------------------------------------------------------------------
    def on_start(self) -> None:
        self.create_publisher(names.EVENTS, BehaviorEvent)
        self.create_timer(self.config.tick_s, self.tick)

    # --- public API -----------------------------------------------------------------------
    def submit(self, graph: TaskGraph, resume: Checkpoint | None = None) -> GraphRun:
        """Queue a behaviour's entry task, or ``resume``'s task with its blackboard restored
        (a checkpoint that does not fit the graph is logged, counted and ignored); raises
        TaskError for an invalid graph."""
        graph.validate()
        count = self._per_name.get(graph.name, 0) + 1
        self._per_name[graph.name] = count
        run = GraphRun(
            graph=graph,
            id=f"{graph.name}#{count}",
            seq=next(self._seq),
            blackboard=dict(graph.blackboard),
            submitted_s=self.now(),
        )
        self.runs[run.id] = run
        pending = _Pending(run, graph.entry)
        self._queue.append(pending)
        self._emit_event(
            "graph_submitted",
            run.id,
            None,
            name=graph.name,
            priority=graph.priority,
            entry=graph.entry,
            queued=len(self._queue),
        )
        for warning in graph.warnings():
            self.log.warning("%s", warning)
        if resume is not None:
            pending.task_id = self._resume(run, resume)
        return run

    def checkpoint(self, run_id: str) -> Checkpoint | None:
        """Where a run stands (the task running or next to run); None once it has ended."""
        run = self.runs.get(run_id)
        if run is None or run.done:
            return None
        if self._active is not None and self._active.run is run:
            task: str | None = self._active.task_id
        else:
            task = next((p.task_id for p in self._queue if p.run is run), None)
        if task is None:
            return None
        blackboard, omitted = portable(run.blackboard)
        if omitted:
            self.log.warning("checkpoint of %s leaves out %s", run.id, ", ".join(omitted))
        finished = tuple(
            FinishedTask(r.task_id, r.result) for r in run.records if r.result in EDGE_RESULTS
        )
        return Checkpoint(run.id, run.name, task, finished, blackboard, self.now(), omitted)

    def cancel_graph(self, run_id: str) -> bool:
        """Drop a behaviour; its running task is cancelled if cancellable, else it ends first.

        Returns False when the run is unknown or already finished.
        """
        run = self.runs.get(run_id)
        if run is None or run.done:
            return False
        active = self._active
        if active is not None and active.run is run:
            if type(active.task).cancellable:
                error = self._call_cancel(active)
                self._record(active, "cancelled", error)
                self._active = None
                self._end_graph(run, "cancelled")
            else:
                run.cancel_requested = True
            return True
        self._queue = [p for p in self._queue if p.run is not run]
        self._end_graph(run, "cancelled")
        return True

    def running_task(self, run_id: str) -> Task | None:
        """The task a run is executing now (None while it waits or once it has ended), for
        a caller that reports that task's own progress."""
        active = self._active
        return active.task if active is not None and active.run.id == run_id else None

    @property
    def idle(self) -> bool:
        return self._active is None and not self._queue

    def current(self) -> dict[str, Any] | None:
        """The running task, for the dashboard; None when nothing runs."""
        a = self._active
        if a is None:
            return None
        return {
            "graph": a.run.id,
            "name": a.run.name,
            "priority": a.run.priority,
            "task": a.task_id,
            "type": task_type_name(a.task),
            "started_s": a.started_s,
            "cancellable": type(a.task).cancellable,
        }

    def queue_snapshot(self) -> list[dict[str, Any]]:
        """Pending tasks in the order they would run."""
        return [
            {
                "graph": p.run.id,
                "name": p.run.name,
                "task": p.task_id,
                "type": p.run.graph.tasks[p.task_id].type_name,
                "priority": p.run.priority,
            }
            for p in sorted(self._queue, key=lambda p: p.key)
        ]

    def report(self) -> dict[str, Any]:
        return {
            "runs": [r.to_dict() for r in self.runs.values()],
            "events": [e.to_dict() for e in self.events],
        }

    def _resume(self, run: GraphRun, checkpoint: Checkpoint) -> str:
        """The task a new run starts at: the checkpoint's (blackboard restored) or the entry."""
        age = self.now() - checkpoint.stamp
        try:
            if age > self.config.resume_max_age_s:
                raise CheckpointError(f"checkpoint is stale ({age:.1f} s old)")
            task = checkpoint.resume_point(run.graph)
        except CheckpointError as exc:
            self.resume_failures += 1
            self.log.warning("%s runs from its entry: %s", run.id, exc)
            self._emit_event("resume_rejected", run.id, run.graph.entry, reason=str(exc))
            return run.graph.entry
        run.blackboard.update(checkpoint.blackboard)
        self._emit_event(
            "behavior_resumed",
            run.id,
            task,
            checkpoint=checkpoint.run,
            finished=[f.task for f in checkpoint.finished],
            age_s=round(age, 3),
        )
        return task

    # --- control loop ---------------------------------------------------------------------
    def tick(self) -> None:
        """One control step: update the running task, preempt it if it is still running and
        allowed to be, start the next.  Polling first keeps the result of a task that ends on
        the tick a more urgent behaviour arrives (it is not cancelled and re-run)."""
        nxt: _Pending | None = None
        if self._active is not None:
            status, error = self._poll(self._active)
            if status is TaskStatus.RUNNING:
                if not self._should_preempt(self._active):
                    return
                self._preempt(self._active)
            else:
                nxt = self._complete(status, error)
        for _ in range(_MAX_STARTS_PER_TICK):
            if nxt is None:
                if self._active is not None or not self._queue:
                    return
                nxt = self._pop()
            nxt = self._start(nxt)

    def _should_preempt(self, active: _Active) -> bool:
        if not self.config.preemption or not type(active.task).cancellable:
            return False
        head = self._peek()
        return head is not None and head.run.priority > active.run.priority

    def _preempt(self, active: _Active) -> None:
        head = self._peek()
        by = head.run.id if head is not None else None
        error = self._call_cancel(active)
        self._record(active, "preempted", error)
        self._emit_event(
            "task_preempted",
            active.run.id,
            active.task_id,
            task_type=task_type_name(active.task),
            by=by,
        )
        self._active = None
        try:
            resumed: Task | None = active.task.fresh()
        except Exception as exc:
            self.log.error("fresh() of %s failed: %r", active.task_id, exc)
            resumed = None  # fall back to the graph's template
        active.run.status = RunStatus.QUEUED
        active.run.suspended = True
        self._queue.append(_Pending(active.run, active.task_id, resumed))

    def _start(self, pending: _Pending) -> _Pending | None:
        """Start a task; if starting fails, complete it and return its successor (if any)."""
        run = pending.run
        node = run.graph.tasks[pending.task_id]
        error: BaseException | None = None
        task = pending.task
        if task is None:
            try:
                task = node.task.fresh()
            except Exception as exc:
                task, error = node.task, exc
        ctx = TaskContext(
            bus=self.runtime.bus,
            now=self.now,
            blackboard=run.blackboard,
            modules=self.modules,
            emit=self._emit,
            graph=run.id,
            task_id=pending.task_id,
        )
        run.status = RunStatus.RUNNING
        if run.suspended:
            run.suspended = False
            self._emit_event("graph_resumed", run.id, pending.task_id, name=run.name)
        self._active = _Active(run, pending.task_id, task, ctx, self.now())
        self._emit_event(
            "task_started",
            run.id,
            pending.task_id,
            task_type=task_type_name(task),
            params=dict(task.params),
        )
        if error is None:
            try:
                task.start(ctx)
            except Exception as exc:
                error = exc
        if error is not None:
            return self._complete(TaskStatus.FAILURE, error)
        return None

    def _poll(self, active: _Active) -> tuple[TaskStatus, BaseException | None]:
        try:
            status = active.task.update(active.ctx)
        except Exception as exc:
            return TaskStatus.FAILURE, exc
        if not isinstance(status, TaskStatus):
            return TaskStatus.FAILURE, TaskError(f"update() returned {status!r}")
        return status, None

    def _complete(self, status: TaskStatus, error: BaseException | None) -> _Pending | None:
        """Record the running task's end and follow its edge (the paper's rule)."""
        active = self._active
        assert active is not None
        self._active = None
        run = active.run
        success = status is TaskStatus.SUCCESS
        if error is not None:
            self.log.warning("task %s of %s failed: %r", active.task_id, run.id, error)
        self._record(active, status.value, error)
        if run.cancel_requested:
            self._end_graph(run, "cancelled")
            return None
        edge = run.graph.tasks[active.task_id].next(success)
        if isinstance(edge, End):
            self._end_graph(run, edge.outcome)
            return None
        successor = _Pending(run, edge)
        head = self._peek()
        if head is not None and head.run.priority > run.priority:
            run.status = RunStatus.QUEUED
            run.suspended = True
            self._queue.append(successor)
            self._emit_event("graph_suspended", run.id, edge, by=head.run.id)
            return None
        return successor

    # --- helpers --------------------------------------------------------------------------
    def _peek(self) -> _Pending | None:
        return min(self._queue, key=lambda p: p.key) if self._queue else None

    def _pop(self) -> _Pending:
        head = self._peek()
        assert head is not None
        self._queue.remove(head)
        return head

    def _call_cancel(self, active: _Active) -> BaseException | None:
        try:
            active.task.cancel(active.ctx)
        except Exception as exc:
            self.log.error("cancel of %s in %s raised %r", active.task_id, active.run.id, exc)
            return exc
        return None

    def _record(self, active: _Active, result: str, error: BaseException | None) -> None:
        detail = dict(active.task.detail) if isinstance(active.task.detail, dict) else {}
        if error is not None:
            detail["error"] = f"{type(error).__name__}: {error}"
        now = self.now()
        record = TaskRecord(
            graph=active.run.id,
            task_id=active.task_id,
            type=task_type_name(active.task),
            result=result,
            start_s=active.started_s,
            end_s=now,
            detail=detail,
        )
        self.records.append(record)
        active.run.records.append(record)
        self._emit_event(
            "task_finished",
            active.run.id,
            active.task_id,
            task_type=record.type,
            result=result,
            duration_s=round(now - active.started_s, 3),
            detail=detail,
        )

    def _end_graph(self, run: GraphRun, outcome: str) -> None:
        run.status = RunStatus.FINISHED
        run.outcome = outcome
        run.finished_s = self.now()
        self._emit_event(
            "graph_finished",
            run.id,
            None,
            name=run.name,
            outcome=outcome,
            tasks=len(run.records),
        )

    def _emit_event(self, type_: str, graph: str | None, task: str | None, **detail: Any) -> None:
        self._emit(BehaviorEvent(self.now(), type_, graph, task, detail))

    def _emit(self, event: BehaviorEvent) -> None:
        """Keep the event and publish it on /amiro/events (tasks emit through here too)."""
        self.events.append(event)
        self.runtime.bus.publish(names.EVENTS, event)
