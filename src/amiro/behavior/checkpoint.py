"""Behaviour checkpoints: where a run stands, in a JSON form that outlives its process.

A checkpoint names the behaviour, the task running (or next to run) when it was taken, the
tasks already finished with their results, in order, the run's blackboard, and optionally
where the robot was (its map pose and odometry at that moment).  The edge publishes one each
time a task starts; the cloud keeps the latest beside the pending notification and sends it
back with the redelivered notification, so a restarted edge starts that task afresh instead
of the behaviour's entry (see docs/behaviours.md).

A checkpoint from the wire is untrusted: :meth:`Checkpoint.from_dict` and
:meth:`Checkpoint.resume_point` raise :class:`CheckpointError` for a malformed one, or for
one whose finished tasks do not lead to its task through the graph's own edges (a
partially written, stale or foreign checkpoint); the engine then runs from the entry.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter, ValidationError

from amiro.behavior.graph import Edge, TaskGraph
from amiro.core import messages
from amiro.core.messages import Notification, Pose2D
from amiro.navigation.poses import between, compose

# Results that follow an edge; "preempted" and "cancelled" tasks are not finished.
EDGE_RESULTS = ("success", "failure")
# Blackboard values that are message dataclasses travel as {MESSAGE_TAG: name, "fields": {...}}.
MESSAGE_TAG = "$msg"


class CheckpointError(ValueError):
    """A checkpoint that cannot be read, or that does not fit the behaviour it resumes."""


@dataclass(frozen=True)
class FinishedTask:
    task: str
    result: str  # "success" or "failure": which edge the run followed


@dataclass(frozen=True)
class Checkpoint:
    """One run's progress: ``task`` runs next, after ``finished`` (in order)."""

    run: str
    graph: str
    task: str
    finished: tuple[FinishedTask, ...]
    blackboard: dict[str, Any]
    stamp: float
    omitted: tuple[str, ...] = ()  # blackboard keys whose values could not be encoded
    robot_pose: Pose2D | None = None  # the localisation's estimate at ``stamp``
    robot_odom: Pose2D | None = None  # the odometry at the same moment

    @property
    def notification_id(self) -> str:
        return str(self.blackboard.get("notification_id", ""))

    def robot_pose_now(self, odom_now: Pose2D | None) -> Pose2D | None:
        """The robot's map pose now: the checkpoint's moved by the odometry travelled since
        (valid while the base that counts it has outlived the checkpoint's process)."""
        if self.robot_pose is None or self.robot_odom is None or odom_now is None:
            return self.robot_pose
        return compose(self.robot_pose, between(self.robot_odom, odom_now))

    def to_dict(self) -> dict[str, Any]:
        """The JSON form (what events and notifications carry)."""
        return {
            "run": self.run,
            "graph": self.graph,
            "task": self.task,
            "finished": [{"task": f.task, "result": f.result} for f in self.finished],
            "blackboard": {k: encode_value(v) for k, v in self.blackboard.items()},
            "stamp": self.stamp,
            "omitted": list(self.omitted),
            "robot_pose": _pose_dict(self.robot_pose),
            "robot_odom": _pose_dict(self.robot_odom),
        }

    @classmethod
    def from_dict(cls, data: object) -> Checkpoint:
        """Parse the JSON form; raises CheckpointError, naming the first problem."""
        if not isinstance(data, dict):
            raise CheckpointError(f"bad checkpoint: not a JSON object but {type(data).__name__}")
        try:
            wire = _Wire.model_validate(data)
        except ValidationError as exc:
            first = exc.errors()[0]
            where = ".".join(str(p) for p in first["loc"]) or "checkpoint"
            raise CheckpointError(f"bad checkpoint: {where}: {first['msg']}") from None
        return cls(
            run=wire.run,
            graph=wire.graph,
            task=wire.task,
            finished=tuple(FinishedTask(f.task, f.result) for f in wire.finished),
            blackboard={k: decode_value(v) for k, v in wire.blackboard.items()},
            stamp=wire.stamp,
            omitted=tuple(wire.omitted),
            robot_pose=None if wire.robot_pose is None else wire.robot_pose.pose(),
            robot_odom=None if wire.robot_odom is None else wire.robot_odom.pose(),
        )

    def resume_point(self, graph: TaskGraph) -> str:
        """The task to start ``graph`` at: checked by replaying the finished tasks' edges."""
        if self.graph != graph.name:
            raise CheckpointError(f"checkpoint of '{self.graph}' does not fit '{graph.name}'")
        if self.task not in graph.tasks:
            raise CheckpointError(f"behaviour {graph.name} has no task '{self.task}'")
        at: Edge = graph.entry
        for done in self.finished:
            if at != done.task:
                raise CheckpointError(
                    f"'{done.task}' is recorded as finished but the run was at {at}"
                )
            at = graph.tasks[done.task].next(done.result == "success")
        if at != self.task:
            raise CheckpointError(f"the finished tasks lead to {at}, not to '{self.task}'")
        return self.task


class _FinishedWire(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    task: str = Field(min_length=1)
    result: Literal["success", "failure"]


class _PoseWire(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    x: float = Field(allow_inf_nan=False)
    y: float = Field(allow_inf_nan=False)
    theta: float = Field(allow_inf_nan=False)

    def pose(self) -> Pose2D:
        return Pose2D(self.x, self.y, self.theta)


def _pose_dict(pose: Pose2D | None) -> dict[str, float] | None:
    return None if pose is None else {"x": pose.x, "y": pose.y, "theta": pose.theta}


class _Wire(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    run: str
    graph: str = Field(min_length=1)
    task: str = Field(min_length=1)
    finished: list[_FinishedWire]
    blackboard: dict[str, Any]
    stamp: float = Field(allow_inf_nan=False)
    omitted: list[str] = []
    robot_pose: _PoseWire | None = None
    robot_odom: _PoseWire | None = None


def carried(note: Notification) -> object:
    """The checkpoint JSON a (re-sent) notification carries, None for a first delivery."""
    return note.checkpoint


def with_checkpoint(note: Notification, checkpoint: dict[str, Any]) -> Notification:
    """The notification to re-send, carrying ``checkpoint``."""
    return dataclasses.replace(note, checkpoint=checkpoint)


def portable(blackboard: Mapping[str, Any]) -> tuple[dict[str, Any], tuple[str, ...]]:
    """The blackboard entries a checkpoint can carry, and the keys of those it cannot."""
    kept: dict[str, Any] = {}
    omitted: list[str] = []
    for key, value in blackboard.items():
        try:
            encode_value(value)
        except CheckpointError:
            omitted.append(key)
        else:
            kept[key] = value
    return kept, tuple(omitted)


def encode_value(value: Any) -> Any:
    """JSON values as they are (tuples become lists); amiro messages tagged with their type."""
    if value is None or isinstance(value, bool | int | float | str):
        return value
    if isinstance(value, list | tuple):
        return [encode_value(v) for v in value]
    if isinstance(value, dict) and all(isinstance(k, str) for k in value):
        if MESSAGE_TAG in value:
            raise CheckpointError(f"a mapping with a '{MESSAGE_TAG}' key is ambiguous")
        return {k: encode_value(v) for k, v in value.items()}
    name = type(value).__name__
    if dataclasses.is_dataclass(value) and _message_type(name) is type(value):
        fields = TypeAdapter(type(value)).dump_python(value, mode="json")
        return {MESSAGE_TAG: name, "fields": fields}
    raise CheckpointError(f"cannot checkpoint a {name}")


def decode_value(value: Any) -> Any:
    """The inverse of :func:`encode_value`; raises CheckpointError for an unknown message."""
    if isinstance(value, list):
        return [decode_value(v) for v in value]
    if not isinstance(value, dict):
        return value
    if MESSAGE_TAG not in value:
        return {k: decode_value(v) for k, v in value.items()}
    name = value[MESSAGE_TAG]
    cls = _message_type(name) if isinstance(name, str) else None
    if cls is None:
        raise CheckpointError(f"bad checkpoint: unknown message type {name!r}")
    try:
        return TypeAdapter(cls).validate_python(value.get("fields"))
    except ValidationError as exc:
        problem = f"{exc.error_count()} error(s)"
        raise CheckpointError(f"bad checkpoint: not a {name}: {problem}") from None


def _message_type(name: str) -> type | None:
    """A dataclass of :mod:`amiro.core.messages` by name, None for anything else."""
    cls = getattr(messages, name, None)
    return cls if isinstance(cls, type) and dataclasses.is_dataclass(cls) else None
