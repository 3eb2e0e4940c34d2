"""Services and actions that can cross processes: how their payloads travel.

Actions are real ROS 2 actions of a generated type (``amiro_interfaces/action/MoveTo``,
``nav2_msgs/action/NavigateToPose``): an :class:`ActionCodec` maps amiro's goal, feedback
and result dataclasses to that type's messages and back.  Services still travel as JSON
in ``std_msgs/String``: one generic codec, pydantic's ``TypeAdapter``, handles any
dataclass (nested dataclasses, Pose2D/Point, enums, None).
"""

from __future__ import annotations

import importlib
import json
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Generic, TypeVar

from pydantic import TypeAdapter, ValidationError

from amiro.core.bus import GoalStatus

T = TypeVar("T")


class WireError(ValueError):
    """A message from the wire that is not what the protocol expects (counted, dropped)."""


class Payload(Generic[T]):
    """A dataclass to and from plain JSON values, validated on the way in."""

    def __init__(self, cls: type[T]) -> None:
        self.cls = cls
        self._adapter: TypeAdapter[T] = TypeAdapter(cls)

    def dump(self, value: T) -> Any:
        return self._adapter.dump_python(value, mode="json")

    def load(self, data: Any) -> T:
        try:
            return self._adapter.validate_python(data)
        except ValidationError as exc:
            raise WireError(f"not a {self.cls.__name__}: {exc.error_count()} error(s)") from None


def envelope(text: str, *keys: str) -> dict[str, Any]:
    """The JSON object in ``text``, which must hold ``keys``."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise WireError(f"not JSON: {exc.msg}") from None
    if not isinstance(data, dict):
        raise WireError("not a JSON object")
    missing = [k for k in keys if k not in data]
    if missing:
        raise WireError(f"missing {', '.join(missing)}")
    return data


G = TypeVar("G")
F = TypeVar("F")
R = TypeVar("R")


class ActionCodec(ABC, Generic[G, F, R]):
    """One action on the wire: amiro's bus action ``name`` as the ROS 2 action ``ros_name``
    of type ``ros_type``; its goal, feedback and result to that type's messages and back."""

    def __init__(self, name: str, ros_type: str, ros_name: str | None = None) -> None:
        self.name = name
        self.ros_type = ros_type
        self.ros_name = ros_name or name

    @cached_property
    def action(self) -> Any:
        """The generated action class (``Goal``, ``Feedback``, ``Result`` inside)."""
        package, kind, name = self.ros_type.split("/")
        return getattr(importlib.import_module(f"{package}.{kind}"), name)

    @abstractmethod
    def goal_to_ros(self, goal: G) -> Any: ...

    @abstractmethod
    def goal_from_ros(self, msg: Any) -> G:
        """Raise :class:`WireError` for a goal amiro cannot run (the server rejects it)."""

    @abstractmethod
    def feedback_to_ros(self, feedback: F, elapsed_s: float) -> Any:
        """``elapsed_s``: time since the goal started (Nav2's navigation_time)."""

    @abstractmethod
    def feedback_from_ros(self, msg: Any) -> F: ...

    @abstractmethod
    def result_to_ros(self, result: R | None, status: GoalStatus) -> Any: ...

    @abstractmethod
    def result_from_ros(self, msg: Any, status: GoalStatus) -> R: ...

    @abstractmethod
    def failure(self, reason: str) -> R:
        """The result a client reports when the goal fails on the wire (server lost,
        rejected) rather than in the server."""


@dataclass(frozen=True)
class ServiceSpec:
    name: str
    request: Payload[Any]
    response: Payload[Any]
    timeout_s: float = field(default=5.0)


def service_spec(name: str, request: type, response: type, timeout_s: float = 5.0) -> ServiceSpec:
    return ServiceSpec(name, Payload(request), Payload(response), timeout_s)
