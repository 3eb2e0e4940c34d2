"""Check: branch on the blackboard through the graph's own success and failure edges."""

from __future__ import annotations

from amiro.behavior.task import Task, TaskContext, TaskParams, TaskStatus


class Check(Task):
    """Succeeds when the blackboard's ``key`` holds a non-empty value, fails otherwise, so a
    behaviour can choose its route (a person to find, or a room to drive to) as data."""

    type_name = "Check"

    class Params(TaskParams):
        key: str

    def start(self, ctx: TaskContext) -> None:
        self.key = self.bind(ctx, self.Params).key

    def update(self, ctx: TaskContext) -> TaskStatus:
        key = self.key
        value = ctx.blackboard.get(key)
        self.detail = {"key": key, "value": value}
        return TaskStatus.SUCCESS if value not in (None, "", [], {}) else TaskStatus.FAILURE
