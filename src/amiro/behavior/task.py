"""Tasks: the nodes of a behaviour's task execution graph (paper, section 3.7).

A task type is a subclass of :class:`Task`, registered under its ``type_name`` so that YAML
behaviours can name it.  The engine calls :meth:`Task.start` once, then :meth:`Task.update`
every control tick until it returns SUCCESS or FAILURE.  Tasks are atomic, as in the paper,
unless the type declares ``cancellable = True``: then a more urgent behaviour may stop it
through :meth:`Task.cancel` and the task is started afresh when its behaviour resumes.

Each task type declares its parameters as a pydantic model, ``Params`` (a :class:`TaskParams`,
unknown names refused), so a misspelt or mistyped parameter is an error when the behaviour is
built, not a silently ignored key.  A ``"$key"`` value stands for any field until the task
starts; the values read from the blackboard are validated then.
"""

from __future__ import annotations

import difflib
import enum
import logging
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar, TypeVar

from pydantic import BaseModel, ConfigDict, ValidationError

from amiro.core.bus import Bus
from amiro.core.messages import BehaviorEvent

if TYPE_CHECKING:
    from amiro.behavior.modules import Modules

T = TypeVar("T")

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

    ``modules`` holds the modules running in this process, typed by their ports, so tasks
    depend on ports, not on concrete backends.
    """

    bus: Bus
    now: Callable[[], float]
    blackboard: dict[str, Any]
    modules: Modules
    emit: Callable[[BehaviorEvent], None]
    graph: str = ""
    task_id: str = ""

    def need(self, module: T | None, name: str) -> T:
        """``module`` (one of ``self.modules``), or a TaskError when it is not running here."""
        if module is None:
            raise TaskError(f"no '{name}' module is running for task {self.task_id}")
        return module

    def event(self, type_: str, **detail: Any) -> None:
        self.emit(BehaviorEvent(self.now(), type_, self.graph, self.task_id, dict(detail)))


class TaskParams(BaseModel):
    """Base of a task type's parameter model: unknown names are refused."""

    model_config = ConfigDict(extra="forbid", frozen=True)


P = TypeVar("P", bound=TaskParams)


def is_reference(value: Any) -> bool:
    """A ``"$key"`` value: read from the graph's blackboard when the task starts."""
    return isinstance(value, str) and value.startswith("$")


def check_params(model: type[TaskParams], params: Mapping[str, Any]) -> None:
    """Validate parameters as written (YAML, Python): a ``"$key"`` value is accepted for any
    known field, and checks that need it (a missing field, a rule across fields) wait for
    the start.  Raises ValueError with a one-line reason naming the field."""
    for name in params:
        if name not in model.model_fields:
            near = difflib.get_close_matches(name, list(model.model_fields), n=1)
            hint = f" (did you mean '{near[0]}'?)" if near else ""
            raise ValueError(f"unknown parameter '{name}'{hint}")
    refs = {name for name, value in params.items() if is_reference(value)}
    try:
        model.model_validate({k: v for k, v in params.items() if k not in refs})
    except ValidationError as exc:
        errors = [e for e in exc.errors() if not refs or (e["loc"] and e["loc"][0] not in refs)]
        if errors:
            raise ValueError(_reason(errors[0], len(errors))) from None


def _reason(error: Any, count: int) -> str:
    """One line for a pydantic error: the field, what is wrong, and the value given."""
    where = ".".join(str(part) for part in error["loc"])
    more = f" (and {count - 1} more)" if count > 1 else ""
    if error["type"] == "missing":
        return f"missing parameter '{where}'{more}"
    message = str(error["msg"]).removeprefix("Value error, ")
    if not where:
        return f"{message}{more}"
    given = "" if error["type"] == "value_error" else f" (got {error['input']!r})"
    return f"parameter '{where}': {message}{given}{more}"


_TASK_TYPES: dict[str, type[Task]] = {}


class Task:
    """Base of every task type.  ``params`` come from YAML or Python, as written (with any
    ``"$key"`` references): the engine reports them and :meth:`fresh` copies them."""

    type_name: ClassVar[str] = ""
    cancellable: ClassVar[bool] = False

    class Params(TaskParams):
        """A task type without parameters; subclasses declare their own."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if cls.type_name:
            _TASK_TYPES[cls.type_name] = cls

    def __init__(self, **params: Any) -> None:
        try:
            check_params(self.Params, params)
        except ValueError as exc:
            raise TaskError(f"{task_type_name(self)}: {exc}") from None
        self.params: dict[str, Any] = params
        self.detail: dict[str, Any] = {}

    def resolved(self, ctx: TaskContext) -> dict[str, Any]:
        """Parameters with ``$key`` references replaced from the blackboard."""
        out: dict[str, Any] = {}
        for key, value in self.params.items():
            if is_reference(value):
                name = value[1:]
                if name not in ctx.blackboard:
                    raise TaskError(f"{self.type_name}: blackboard has no '{name}' for {key}")
                value = ctx.blackboard[name]
            out[key] = value
        return out

    def bind(self, ctx: TaskContext, model: type[P]) -> P:
        """The resolved parameters validated by ``model`` (the type's own ``Params``, passed
        so that the caller gets its typed fields); raises TaskError naming the field."""
        try:
            return model.model_validate(self.resolved(ctx))
        except ValidationError as exc:
            errors = exc.errors()
            reason = _reason(errors[0], len(errors))
            raise TaskError(f"{task_type_name(self)}: {reason}") from None

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


def task_type_name(task: Task) -> str:
    """The task's registered type, or its class name for unregistered (test) types."""
    return task.type_name or type(task).__name__


def task_types() -> dict[str, type[Task]]:
    return dict(_TASK_TYPES)


def make_task(type_name: str, params: Mapping[str, Any] | None = None) -> Task:
    """A task of a registered type; TaskError for an unknown type or bad parameters."""
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
