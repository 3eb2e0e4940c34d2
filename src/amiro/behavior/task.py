"""Tasks: the nodes of a behaviour's task execution graph (paper, section 3.7).

A task type is a subclass of :class:`Task`, registered under its ``type_name`` so that YAML
behaviours can name it.  The engine calls :meth:`Task.start` once, then :meth:`Task.update`
every control tick until it returns SUCCESS or FAILURE.  Tasks are atomic, as in the paper,
unless the type declares ``cancellable = True``: then a more urgent behaviour may stop it
through :meth:`Task.cancel` and the task is started afresh when its behaviour resumes.
"""

from __future__ import annotations

import enum
import logging
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar

from amiro.core.bus import Bus
from amiro.core.messages import BehaviorEvent

log = logging.getLogger("amiro.behavior")


class TaskStatus(enum.Enum):
    RUNNING = "running"
    SUCCESS = "success"
    FAILURE = "failure"


class TaskError(ValueError):
    """A task declared with an unknown type or unusable parameters."""


@dataclass
class TaskContext:
    """What a running task may use: the bus, the clock, its graph's blackboard, the modules.

    ``modules`` maps a module name ("robot", "navigation", "perception", "activity",
    "dialogue", "environment") to the object serving it, so tasks depend on ports, not on
    concrete backends.
    """

    bus: Bus
    now: Callable[[], float]
    blackboard: dict[str, Any]
    modules: dict[str, Any]
    emit: Callable[[BehaviorEvent], None]
    graph: str = ""
    task_id: str = ""

    def module(self, name: str) -> Any:
        try:
            return self.modules[name]
        except KeyError:
            raise TaskError(f"no '{name}' module is running for task {self.task_id}") from None

    def event(self, type_: str, **detail: Any) -> None:
        self.emit(BehaviorEvent(self.now(), type_, self.graph, self.task_id, dict(detail)))


_TASK_TYPES: dict[str, type[Task]] = {}


class Task:
    """Base of every task type.  ``params`` come from YAML or Python; values written as
    ``"$key"`` are read from the graph's blackboard when the task starts."""

    type_name: ClassVar[str] = ""
    cancellable: ClassVar[bool] = False

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if cls.type_name:
            _TASK_TYPES[cls.type_name] = cls

    def __init__(self, **params: Any) -> None:
        self.params: dict[str, Any] = params
        self.detail: dict[str, Any] = {}

    def resolved(self, ctx: TaskContext) -> dict[str, Any]:
        """Parameters with ``$key`` references replaced from the blackboard."""
        out: dict[str, Any] = {}
        for key, value in self.params.items():
            if isinstance(value, str) and value.startswith("$"):
                name = value[1:]
                if name not in ctx.blackboard:
                    raise TaskError(f"{self.type_name}: blackboard has no '{name}' for {key}")
                value = ctx.blackboard[name]
            out[key] = value
        return out

    def start(self, ctx: TaskContext) -> None:
        """Begin the task (send goals, publish commands)."""

    def update(self, ctx: TaskContext) -> TaskStatus:
        """Called every control tick; return RUNNING until the task ends."""
        raise NotImplementedError

    def cancel(self, ctx: TaskContext) -> None:
        """Stop at once (only for cancellable types): cancel goals, stop actuators."""

    def fresh(self) -> Task:
        """A new instance with the same parameters: how a preempted task resumes."""
        return type(self)(**self.params)

    def describe(self) -> str:
        shown = ", ".join(f"{k}={v}" for k, v in self.params.items())
        return f"{self.type_name}({shown})"


def task_types() -> dict[str, type[Task]]:
    return dict(_TASK_TYPES)


def make_task(type_name: str, params: dict[str, Any] | None = None) -> Task:
    cls = _TASK_TYPES.get(type_name)
    if cls is None:
        known = ", ".join(sorted(_TASK_TYPES)) or "none"
        raise TaskError(f"unknown task type '{type_name}' (known: {known})")
    try:
        return cls(**(params or {}))
    except TypeError as exc:
        raise TaskError(f"{type_name}: {exc}") from None


@dataclass
class TaskRecord:
    """One executed task, as the scenario JSON reports it."""

    graph: str
    task_id: str
    type: str
    result: str
    start_s: float
    end_s: float
    detail: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "task": self.type,
            "id": self.task_id,
            "graph": self.graph,
            "result": self.result,
            "start_s": round(self.start_s, 3),
            "end_s": round(self.end_s, 3),
        }
        if self.detail:
            out["detail"] = self.detail
        return out
