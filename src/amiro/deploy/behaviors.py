"""Behaviour requests as an action: ask for a behaviour by kind, hear how it ended.

The dialogue ("go to the kitchen") and the dashboard's task form run where the person is
(the cloud), the behaviour engine runs on the edge.  ``/amiro/behavior/run`` joins them:
the goal names a handler kind (``go_to``) and its payload, or one task type and its
parameters; the server on the edge builds the graph with its :class:`HandlerRegistry`,
submits it to its engine, reports the running task as feedback and ends the goal with the
behaviour's outcome.  It is a bus action, so it works the same in one process; across
processes the ROS 2 action endpoints carry it (``serve_actions`` / ``call_actions``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from amiro.behavior.engine import BehaviorEngine, GraphRun
from amiro.behavior.graph import TaskGraph
from amiro.behavior.handlers import HandlerError, HandlerRegistry
from amiro.behavior.task import TaskError
from amiro.core import names
from amiro.core.bus import ActionServer, GoalHandle
from amiro.core.node import Node
from amiro.web.robot import single_task_graph

COMPLETED = "completed"


@dataclass(frozen=True)
class BehaviorGoal:
    """A behaviour to run: a handler ``kind`` with its ``payload`` (the blackboard), or with
    ``single_task`` a task type with its parameters.  ``priority`` None: the graph's own."""

    kind: str
    payload: dict[str, Any] = field(default_factory=dict, hash=False)
    priority: int | None = None
    single_task: bool = False


@dataclass(frozen=True)
class BehaviorFeedback:
    run: str
    task: str


@dataclass(frozen=True)
class BehaviorResult:
    """``outcome`` is the graph's end (``completed``, ``unreachable``, ...), or why the goal
    never ran (``rejected: ...``, ``server_lost``)."""

    ok: bool
    outcome: str
    run: str = ""


BehaviorHandle = GoalHandle[BehaviorGoal, BehaviorFeedback, BehaviorResult]


def behavior_graph(goal: BehaviorGoal, handlers: HandlerRegistry) -> TaskGraph:
    """The graph a goal asks for; raises HandlerError, TaskError or ValueError."""
    if goal.single_task:
        return single_task_graph(goal.kind, dict(goal.payload), goal.priority or 3)
    graph = handlers.build(goal.kind, goal.payload)
    if goal.priority is not None:
        graph.priority = goal.priority
    return graph


@dataclass
class _Running:
    handle: BehaviorHandle
    run: GraphRun
    task: str = ""


class BehaviorActionServer(Node, ActionServer[BehaviorGoal, BehaviorFeedback, BehaviorResult]):
    """Edge side: runs requested behaviours on the engine and reports how they end."""

    def __init__(
        self, engine: BehaviorEngine, handlers: HandlerRegistry, poll_s: float = 0.1
    ) -> None:
        super().__init__("behavior_requests")
        self.engine = engine
        self.handlers = handlers
        self.poll_s = poll_s
        self.active: dict[int, _Running] = {}
        self.finished: list[BehaviorResult] = []

    def on_start(self) -> None:
        self.create_action_server(names.BEHAVIOR_RUN, self)
        self.create_timer(self.poll_s, self._poll)

    def execute(self, handle: BehaviorHandle) -> None:
        try:
            run = self.engine.submit(behavior_graph(handle.goal, self.handlers))
        except (HandlerError, TaskError, ValueError) as exc:
            self.log.warning("behaviour request %s rejected: %s", handle.goal.kind, exc)
            handle.reject(BehaviorResult(False, f"rejected: {exc}"))
            return
        self.active[handle.id] = _Running(handle, run)

    def cancel(self, handle: BehaviorHandle) -> None:
        running = self.active.get(handle.id)
        if running is None or not self.engine.cancel_graph(running.run.id):
            handle.canceled(self.canceled_result(handle))
        # else the poll sees the run end as "cancelled"

    def canceled_result(self, handle: BehaviorHandle) -> BehaviorResult:
        running = self.active.pop(handle.id, None)
        return BehaviorResult(False, "cancelled", running.run.id if running else "")

    def _poll(self) -> None:
        current = self.engine.current()
        for key, running in list(self.active.items()):
            if running.run.done:
                del self.active[key]
                self._finish(running)
            elif current is not None and current["graph"] == running.run.id:
                self._feedback(running, current["task"])

    def _feedback(self, running: _Running, task: str) -> None:
        if task != running.task:
            running.task = task
            running.handle.publish_feedback(BehaviorFeedback(running.run.id, task))

    def _finish(self, running: _Running) -> None:
        run, handle = running.run, running.handle
        result = BehaviorResult(run.outcome == COMPLETED, run.outcome or "", run.id)
        self.finished.append(result)
        if handle.cancel_requested:
            handle.canceled(result)
        elif result.ok:
            handle.succeed(result)
        else:
            handle.abort(result)


@dataclass
class Request:
    """One behaviour asked for, and how it ended (``outcome`` None while it runs)."""

    id: str
    goal: BehaviorGoal
    sent_s: float
    run: str = ""
    outcome: str | None = None
    ok: bool = False
    ended_s: float | None = None

    def to_dict(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "kind": self.goal.kind,
            "run": self.run,
            "outcome": self.outcome,
            "ok": self.ok,
            "sent_s": round(self.sent_s, 3),
            "ended_s": None if self.ended_s is None else round(self.ended_s, 3),
        }


class BehaviorRequests(Node):
    """Cloud side: sends behaviour goals to whoever serves the action and keeps their ends.

    ``request`` raises BusError when no server is on the bus (no edge, or the action is not
    in ``call_actions``); a lost server ends the goal with ``server_lost``."""

    def __init__(self, keep: int = 200) -> None:
        super().__init__("behavior_client")
        self.keep = keep
        self.requests: list[Request] = []
        self._count = 0

    def request(
        self, goal: BehaviorGoal, on_done: Callable[[Request], None] | None = None
    ) -> Request:
        handle: BehaviorHandle = self.runtime.bus.send_goal(names.BEHAVIOR_RUN, goal)
        self._count += 1
        req = Request(f"request-{self._count}", goal, self.now())
        self.requests = [*self.requests[-self.keep + 1 :], req]

        def feedback(fb: BehaviorFeedback) -> None:
            req.run = fb.run

        def done(h: BehaviorHandle) -> None:
            result = h.result or BehaviorResult(False, h.status.value)
            req.run = result.run or req.run
            req.outcome, req.ok, req.ended_s = result.outcome, result.ok, self.now()
            if on_done is not None:
                on_done(req)

        handle.on_feedback(feedback)
        handle.on_done(done)
        return req
