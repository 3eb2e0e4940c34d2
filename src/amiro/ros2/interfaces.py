"""Services and actions that can cross processes: their types and their JSON encoding.

No interface package can be generated here (only prebuilt ROS 2 wheels), so requests,
goals, feedback and results travel as JSON in ``std_msgs/String``.  One generic codec,
pydantic's ``TypeAdapter``, handles any dataclass (nested dataclasses, Pose2D/Point,
enums, None), so a new action only needs an :class:`ActionSpec` here, no per-type code.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Generic, TypeVar

from pydantic import TypeAdapter, ValidationError

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


@dataclass(frozen=True)
class ActionSpec:
    """An action's goal, feedback and result types, and the result a client reports when
    the goal fails on the wire (server lost, rejected) rather than in the server."""

    name: str
    goal: Payload[Any]
    feedback: Payload[Any]
    result: Payload[Any]
    failure: Callable[[str], Any]


@dataclass(frozen=True)
class ServiceSpec:
    name: str
    request: Payload[Any]
    response: Payload[Any]
    timeout_s: float = field(default=5.0)


def action_spec(
    name: str, goal: type, feedback: type, result: type, failure: Callable[[str], Any]
) -> ActionSpec:
    return ActionSpec(name, Payload(goal), Payload(feedback), Payload(result), failure)


def service_spec(name: str, request: type, response: type, timeout_s: float = 5.0) -> ServiceSpec:
    return ServiceSpec(name, Payload(request), Payload(response), timeout_s)
