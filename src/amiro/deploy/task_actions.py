"""Search and RecognizeActivity as actions of their own: one task, typed goal and result.

``/amiro/behavior/run`` runs any behaviour by kind with a JSON payload; a ROS user (or a
behaviour tree of their own) wants the two perception tasks as typed actions instead:
``amiro_interfaces/action/Search`` and ``RecognizeActivity``.  The server on the edge runs
the task as a one-task behaviour on the engine (so it queues and yields by priority like
any other), reports the task's own progress as feedback and ends the goal with its outcome.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from amiro.behavior.engine import BehaviorEngine, GraphRun
from amiro.behavior.task import Task, TaskError
from amiro.core import names
from amiro.core.bus import ActionServer, GoalHandle
from amiro.core.messages import Point
from amiro.core.node import Node
from amiro.web.robot import single_task_graph

if TYPE_CHECKING:
    from _typeshed import DataclassInstance

G = TypeVar("G", bound="DataclassInstance")
F = TypeVar("F")
R = TypeVar("R")
PRIORITY = 3  # as a single task asked for on the dashboard
COMPLETED = "completed"


@dataclass(frozen=True)
class SearchGoal:
    person: str
    dwell_s: float = 1.2
    sightings: int = 2
    side_steps: int = 2


@dataclass(frozen=True)
class SearchFeedback:
    room: str  # the room being searched
    step: str  # head, turn, goto, step (a side step), look


@dataclass(frozen=True)
class SearchResult:
    found: bool
    outcome: str  # found, not_found, cancelled, server_lost...
    position: Point | None = None  # map frame, when found
    room: str = ""


@dataclass(frozen=True)
class RecognizeActivityGoal:
    person: str
    activity: str = "drink_water"
    timeout_s: float = 30.0
    confirmations: int = 3
    of_last: int = 5


@dataclass(frozen=True)
class RecognizeActivityFeedback:
    current: str  # the label the recogniser gives now ("" none)
    confirmations: int  # sightings of the expected activity among the last of_last readings


@dataclass(frozen=True)
class RecognizeActivityResult:
    recognised: bool
    outcome: str  # recognised, not_recognised, skeleton_incomplete, cancelled...


def _reason(run: GraphRun) -> str:
    """Why a run did not complete: its task's own reason, else the run's outcome."""
    for record in reversed(run.records):
        if "reason" in record.detail:
            return str(record.detail["reason"])
    return run.outcome or "failed"


class TaskAction(ABC, Generic[G, F, R]):
    """One task type as an action: the bus action's name, the task's parameters from a
    goal, its progress as feedback, its end as a result."""

    name: str
    task_type: str

    def params(self, goal: G) -> dict[str, Any]:
        """The goal's fields are the task's parameters of the same names."""
        return asdict(goal)

    @abstractmethod
    def feedback(self, task: Any) -> F: ...

    @abstractmethod
    def result(self, run: GraphRun) -> R: ...

    @abstractmethod
    def failure(self, reason: str) -> R: ...


class SearchAction(TaskAction[SearchGoal, SearchFeedback, SearchResult]):
    name = names.SEARCH
    task_type = "Search"

    def feedback(self, task: Any) -> SearchFeedback:
        return SearchFeedback(task.room, task.step)

    def result(self, run: GraphRun) -> SearchResult:
        if run.outcome != COMPLETED:
            return SearchResult(False, _reason(run))
        room = run.blackboard.get("person_room")
        return SearchResult(True, "found", run.blackboard.get("person_position"), room or "")

    def failure(self, reason: str) -> SearchResult:
        return SearchResult(False, reason)


class RecognizeActivityAction(
    TaskAction[RecognizeActivityGoal, RecognizeActivityFeedback, RecognizeActivityResult]
):
    name = names.RECOGNIZE_ACTIVITY
    task_type = "RecognizeActivity"

    def feedback(self, task: Any) -> RecognizeActivityFeedback:
        return RecognizeActivityFeedback(task.current, task.recent.count(task.activity))

    def result(self, run: GraphRun) -> RecognizeActivityResult:
        if run.outcome == COMPLETED:
            return RecognizeActivityResult(True, "recognised")
        return RecognizeActivityResult(False, _reason(run))

    def failure(self, reason: str) -> RecognizeActivityResult:
        return RecognizeActivityResult(False, reason)


@dataclass
class _Running:
    handle: GoalHandle[Any, Any, Any]
    run: GraphRun
    last: Any = None  # the feedback last published


class TaskActionServer(Node, ActionServer[Any, Any, Any]):
    """Edge side: serves one :class:`TaskAction` by running its task on the engine."""

    def __init__(self, engine: BehaviorEngine, action: TaskAction[Any, Any, Any]) -> None:
        super().__init__(f"{action.task_type.lower()}_action")
        self.engine = engine
        self.action = action
        self.active: dict[int, _Running] = {}

    def on_start(self) -> None:
        self.create_action_server(self.action.name, self)
        self.create_timer(0.1, self._poll)

    def execute(self, handle: GoalHandle[Any, Any, Any]) -> None:
        try:
            graph = single_task_graph(
                self.action.task_type, self.action.params(handle.goal), PRIORITY
            )
        except (TaskError, ValueError) as exc:
            handle.reject(self.action.failure(f"rejected: {exc}"))
            return
        self.active[handle.id] = _Running(handle, self.engine.submit(graph))

    def cancel(self, handle: GoalHandle[Any, Any, Any]) -> None:
        running = self.active.get(handle.id)
        if running is None or not self.engine.cancel_graph(running.run.id):
            handle.canceled(self.canceled_result(handle))
        # else the poll sees the run end as "cancelled"

    def canceled_result(self, handle: GoalHandle[Any, Any, Any]) -> Any:
        self.active.pop(handle.id, None)
        return self.action.failure("cancelled")

    def _poll(self) -> None:
        for key, running in list(self.active.items()):
            if running.run.done:
                del self.active[key]
                self._finish(running)
                continue
            task: Task | None = self.engine.running_task(running.run.id)
            if task is not None:
                feedback = self.action.feedback(task)
                if feedback != running.last:
                    running.last = feedback
                    running.handle.publish_feedback(feedback)

    def _finish(self, running: _Running) -> None:
        result, handle = self.action.result(running.run), running.handle
        if handle.cancel_requested:
            handle.canceled(result)
        elif running.run.outcome == COMPLETED:
            handle.succeed(result)
        else:
            handle.abort(result)


TASK_ACTIONS: tuple[TaskAction[Any, Any, Any], ...] = (SearchAction(), RecognizeActivityAction())
