"""Task execution graphs: one behaviour as tasks linked by success and failure edges.

A :class:`TaskGraph` is a template (paper, section 3.7): the engine runs fresh copies of its
tasks and of its blackboard, so the same graph can be submitted again and again.  An edge
leads to another task of the same graph or to an :class:`End` that names the outcome.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, TypeAlias

from amiro.behavior.task import Task, TaskError, task_type_name


@dataclass(frozen=True, slots=True)
class End:
    """The end of a behaviour, labelled with its outcome ("completed", "person_not_found")."""

    outcome: str = "completed"

    def __post_init__(self) -> None:
        if not isinstance(self.outcome, str) or not self.outcome:
            raise ValueError(f"an End needs a non-empty outcome label, got {self.outcome!r}")

    def __str__(self) -> str:
        return f"End({self.outcome})"


Edge: TypeAlias = str | End

COMPLETED = End("completed")
FAILED = End("failed")


@dataclass(slots=True)
class TaskNode:
    """A task of a graph with where to go on success and on failure."""

    id: str
    task: Task
    on_success: Edge = COMPLETED
    on_failure: Edge = FAILED

    def next(self, success: bool) -> Edge:
        return self.on_success if success else self.on_failure

    @property
    def type_name(self) -> str:
        return task_type_name(self.task)


class TaskGraph:
    """A behaviour: named, prioritised (higher is more urgent), with an entry task.

    Built fluently::

        TaskGraph("hydration", priority=5, blackboard={"person": "maria"})
            .add("search", Search(person="$person"), on_success="move",
                 on_failure=End("person_not_found"))
            .add("move", MoveTo(target="$person_position"))

    The first task added is the entry unless ``entry`` names another one.
    """

    def __init__(
        self,
        name: str,
        priority: int = 0,
        *,
        blackboard: Mapping[str, Any] | None = None,
        entry: str | None = None,
    ) -> None:
        if not isinstance(name, str) or not name:
            raise ValueError(f"a behaviour needs a non-empty name, got {name!r}")
        if isinstance(priority, bool) or not isinstance(priority, int):
            raise ValueError(f"behaviour {name}: priority must be an int, got {priority!r}")
        self.name = name
        self.priority = priority
        self.blackboard: dict[str, Any] = dict(blackboard or {})
        self.tasks: dict[str, TaskNode] = {}
        self._entry = entry

    def __repr__(self) -> str:
        return f"<TaskGraph {self.name} priority={self.priority} tasks={list(self.tasks)}>"

    @property
    def entry(self) -> str:
        if self._entry is not None:
            return self._entry
        if not self.tasks:
            raise TaskError(f"behaviour {self.name} has no tasks")
        return next(iter(self.tasks))

    def add(
        self,
        task_id: str,
        task: Task,
        on_success: Edge | None = None,
        on_failure: Edge | None = None,
    ) -> TaskGraph:
        """Add a task; absent edges end the behaviour as "completed" / "failed"."""
        if not isinstance(task_id, str) or not task_id:
            raise TaskError(f"behaviour {self.name}: task ids must be non-empty strings")
        if task_id in self.tasks:
            raise TaskError(f"behaviour {self.name}: task id '{task_id}' is used twice")
        if not isinstance(task, Task):
            raise TaskError(
                f"behaviour {self.name}: task '{task_id}' is a {type(task).__name__}, not a Task"
            )
        for label, edge in (("on_success", on_success), ("on_failure", on_failure)):
            if edge is not None and not isinstance(edge, str | End):
                raise TaskError(
                    f"behaviour {self.name}: task '{task_id}' {label} must be a task id or "
                    f"an End, got {edge!r}"
                )
        self.tasks[task_id] = TaskNode(
            task_id,
            task,
            COMPLETED if on_success is None else on_success,
            FAILED if on_failure is None else on_failure,
        )
        return self

    def node(self, task_id: str) -> TaskNode:
        try:
            return self.tasks[task_id]
        except KeyError:
            raise TaskError(f"behaviour {self.name} has no task '{task_id}'") from None

    def validate(self) -> TaskGraph:
        """Raise :class:`TaskError` for a missing entry or an edge to an unknown task."""
        entry = self.entry
        known = ", ".join(sorted(self.tasks)) or "none"
        if entry not in self.tasks:
            raise TaskError(
                f"behaviour {self.name}: entry '{entry}' is not one of its tasks ({known})"
            )
        for node in self.tasks.values():
            for label, edge in (("on_success", node.on_success), ("on_failure", node.on_failure)):
                if isinstance(edge, str) and edge not in self.tasks:
                    raise TaskError(
                        f"behaviour {self.name}: task '{node.id}' {label} leads to unknown "
                        f"task '{edge}' ({known})"
                    )
        return self

    def reachable(self) -> set[str]:
        """Task ids that some path from the entry can reach."""
        if not self.tasks:
            return set()
        seen: set[str] = set()
        todo = [self.entry]
        while todo:
            tid = todo.pop()
            if tid in seen or tid not in self.tasks:
                continue
            seen.add(tid)
            node = self.tasks[tid]
            todo.extend(e for e in (node.on_success, node.on_failure) if isinstance(e, str))
        return seen

    def warnings(self) -> list[str]:
        """Legal but suspicious shapes: tasks that no path from the entry reaches."""
        reach = self.reachable()
        return [
            f"behaviour {self.name}: task '{tid}' is unreachable from entry '{self.entry}'"
            for tid in self.tasks
            if tid not in reach
        ]

    def outcomes(self) -> set[str]:
        """Every outcome label this behaviour can end with."""
        return {
            e.outcome
            for node in self.tasks.values()
            for e in (node.on_success, node.on_failure)
            if isinstance(e, End)
        }

    def to_dict(self) -> dict[str, Any]:
        """The graph's shape, for the dashboard and reports."""

        def edge(e: Edge) -> Any:
            return {"end": e.outcome} if isinstance(e, End) else e

        return {
            "name": self.name,
            "priority": self.priority,
            "entry": self.entry if self.tasks else None,
            "blackboard": dict(self.blackboard),
            "tasks": {
                n.id: {
                    "type": n.type_name,
                    "params": dict(n.task.params),
                    "on_success": edge(n.on_success),
                    "on_failure": edge(n.on_failure),
                }
                for n in self.tasks.values()
            },
        }
