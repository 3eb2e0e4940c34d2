"""MoveTo and Wait: the two cancellable tasks that only move or pass time."""

from __future__ import annotations

from typing import Any

from pydantic import Field, field_validator

from amiro.behavior.task import Task, TaskContext, TaskError, TaskParams, TaskStatus
from amiro.core import names
from amiro.core.bus import GoalHandle, GoalStatus
from amiro.core.messages import Point, Pose2D
from amiro.navigation.move_to import MoveToGoal, MoveToResult


def goal_for(target: Any, approach: float) -> MoveToGoal:
    """A MoveTo goal from a place name, a pose, a person's position or a mapping."""
    if isinstance(target, str):
        return MoveToGoal(place=target)
    if isinstance(target, Pose2D):
        return MoveToGoal(pose=target)
    if isinstance(target, Point):
        return MoveToGoal(person=target, approach=approach)
    if isinstance(target, dict) and {"x", "y"} <= target.keys():
        if "theta" in target:
            return MoveToGoal(pose=Pose2D(float(target["x"]), float(target["y"]), target["theta"]))
        return MoveToGoal(person=Point(float(target["x"]), float(target["y"])), approach=approach)
    raise TaskError(f"MoveTo: cannot go to {target!r}")


class MoveTo(Task):
    """Drive to ``target`` (place name, pose, or person position with ``approach`` metres)."""

    type_name = "MoveTo"
    cancellable = True

    class Params(TaskParams):
        target: Any
        approach: float = Field(0.8, ge=0)

        @field_validator("target")
        @classmethod
        def _reachable(cls, value: Any) -> Any:
            goal_for(value, 0.0)  # raises for something MoveTo cannot go to
            return value

    def start(self, ctx: TaskContext) -> None:
        p = self.bind(ctx, self.Params)
        goal = goal_for(p.target, p.approach)
        self.handle: GoalHandle[MoveToGoal, Any, MoveToResult] = ctx.bus.send_goal(
            names.MOVE_TO, goal
        )

    def update(self, ctx: TaskContext) -> TaskStatus:
        handle = self.handle
        if handle.status is GoalStatus.REJECTED:
            self.detail = {"reason": "rejected"}
            return TaskStatus.FAILURE
        if not handle.done:
            return TaskStatus.RUNNING
        result = handle.result
        assert result is not None
        self.detail = {"reason": result.reason, "travelled_m": round(result.travelled_m, 2)}
        return TaskStatus.SUCCESS if result.success else TaskStatus.FAILURE

    def cancel(self, ctx: TaskContext) -> None:
        self.handle.cancel()


class Wait(Task):
    """Pass ``seconds`` of clock time."""

    type_name = "Wait"
    cancellable = True

    class Params(TaskParams):
        seconds: float = Field(1.0, ge=0)

    def start(self, ctx: TaskContext) -> None:
        self.until = ctx.now() + self.bind(ctx, self.Params).seconds

    def update(self, ctx: TaskContext) -> TaskStatus:
        return TaskStatus.SUCCESS if ctx.now() >= self.until else TaskStatus.RUNNING
